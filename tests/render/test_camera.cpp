// Camera presets: names, where each camera stands, and framing that keeps the
// whole box inside the margins and touches them.
#include <gtest/gtest.h>

#include <cmath>

#include "vgd/render/camera.hpp"

using namespace vgd;

namespace {

using D3 = std::array<double, 3>;
D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
D3 unit(const D3& a) {
  const double l = std::sqrt(dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}

// A standing body: 0.5 m wide, 0.3 m deep, 1.7 m tall, feet on y = 0.
render::Box body_box() {
  render::Box b;
  b.extend(std::array<float, 3>{-0.25f, 0.0f, -0.15f});
  b.extend(std::array<float, 3>{0.25f, 1.7f, 0.15f});
  return b;
}

}  // namespace

TEST(ViewPresets, FiveNamedViewsAndTheirAliases) {
  ASSERT_EQ(render::view_presets().size(), 5u);
  for (const char* n : {"front", "back", "left", "right", "three-quarter", "three_quarter", "3/4", "FRONT"})
    EXPECT_TRUE(render::find_view(n)) << n;
  EXPECT_FALSE(render::find_view("top"));
}

TEST(FrameCamera, EachPresetStandsOnItsSide) {
  const auto box = body_box();
  auto eye = [&](const char* v) { return render::frame_camera(*render::find_view(v), box, 1.0).eye; };
  EXPECT_GT(eye("front")[2], 1.0);   // the body faces +Z
  EXPECT_LT(eye("back")[2], -1.0);
  EXPECT_GT(eye("left")[0], 1.0);    // the body's left is +X
  EXPECT_LT(eye("right")[0], -1.0);
  const auto q = eye("three-quarter");
  EXPECT_GT(q[0], 0.3);
  EXPECT_GT(q[2], q[0]);             // more front than side
}

TEST(FrameCamera, TheWholeBoxFitsInsideTheMarginsAndTouchesOne) {
  const auto box = body_box();
  for (const double aspect : {1.0, 0.6, 1.8}) {
    for (const auto& view : render::view_presets()) {
      const double margin = 0.05;
      const auto cam = render::frame_camera(view, box, aspect, margin);
      const D3 f = unit(sub(cam.target, cam.eye));
      const D3 r = unit(cross(f, cam.up));
      const D3 u = cross(r, f);
      const double ty = std::tan(cam.fov_y_deg * M_PI / 360.0), tx = ty * aspect;
      double worst = 0;  // largest |normalised device coordinate| over the corners
      for (int c = 0; c < 8; ++c) {
        const D3 p{c & 1 ? box.max[0] : box.min[0], c & 2 ? box.max[1] : box.min[1], c & 4 ? box.max[2] : box.min[2]};
        const D3 v = sub(p, cam.eye);
        const double depth = dot(v, f);
        ASSERT_GT(depth, cam.near_m) << view.name;
        ASSERT_LT(depth, cam.far_m) << view.name;
        worst = std::max({worst, std::abs(dot(v, r)) / (depth * tx), std::abs(dot(v, u)) / (depth * ty)});
      }
      EXPECT_LE(worst, 1 - 2 * margin + 1e-9) << view.name << " aspect " << aspect;
      EXPECT_GT(worst, 1 - 2 * margin - 0.08) << view.name << " aspect " << aspect << ": framed too loosely";
    }
  }
}
