// Off-screen drawing (OSMesa): a preview is not blank, shows the garment's
// colour where the garment is and the body's where the body is, casts a floor
// shadow, is anti-aliased, and the same scene gives the same bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/synthetic_scene.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/render/offscreen.hpp"

using namespace vgd;

namespace {

const render::ViewPreset& front() {
  static const render::ViewPreset v = *render::find_view("front");
  return v;
}

double luma(const std::uint8_t* p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; }

}  // namespace

TEST(Offscreen, ThePreviewShowsTheGarmentColourWhereTheGarmentIs) {
  const auto im = render::render_view(test::dressed_cylinder(), front(), 128, 128);
  ASSERT_EQ(im.width, 128);
  ASSERT_EQ(im.height, 128);
  // Framed on the body (0–1.7 m, 5 % margins): the garment (0.6–1.0 m) lies
  // between rows 0.43 H and 0.62 H, the chest (1.4 m) near row 0.21 H.
  const auto* garment = im.pixel(64, 67);
  EXPECT_GT(garment[0], garment[1] + 60) << "red expected at the garment";
  EXPECT_GT(garment[0], garment[2] + 60);
  const auto* chest = im.pixel(64, 27);
  EXPECT_LT(std::abs(chest[0] - chest[1]), 25) << "a neutral body expected";
  EXPECT_LT(luma(chest), 236) << "the body is not the background";
  // Not blank: most of the picture is background, but a good part is not.
  const auto* corner = im.pixel(2, 2);
  int differing = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) differing += std::abs(luma(im.pixel(x, y)) - luma(corner)) > 12;
  EXPECT_GT(differing, 128 * 128 / 20);
  EXPECT_LT(differing, 128 * 128 / 2);
}

TEST(Offscreen, TheSameSceneGivesTheSameBytes) {
  const auto scene = test::dressed_cylinder();
  const auto view = *render::find_view("three-quarter");
  const auto a = render::render_view(scene, view, 96, 80);
  const auto b = render::render_view(scene, view, 96, 80);
  EXPECT_EQ(render::encode_png(a), render::encode_png(b));
  // And one renderer drawing twice (state left over from the first frame changes nothing).
  render::OffscreenRenderer r;
  r.set_scene(scene);
  const auto c = r.render(view, 96, 80);
  r.render(front(), 50, 50);
  EXPECT_EQ(r.render(view, 96, 80).rgba, c.rgba);
  EXPECT_EQ(c.rgba, a.rgba);
}

TEST(Offscreen, TheBodyCastsASoftShadowOnTheFloor) {
  render::OffscreenRenderer r;
  r.set_scene(test::dressed_cylinder());
  render::OffscreenOptions with, without;
  without.look.shadow = false;
  const auto a = r.render(front(), 128, 128, with), b = r.render(front(), 128, 128, without);
  // The floor round the feet (the bottom rows, beside the body) is darker with the shadow.
  double sa = 0, sb = 0;
  for (int y = 118; y < 128; ++y)
    for (int x = 30; x < 98; ++x) sa += luma(a.pixel(x, y)), sb += luma(b.pixel(x, y));
  EXPECT_LT(sa, sb - 100) << "no shadow under the body";
  // Away from the body the floor is the same.
  EXPECT_EQ(a.pixel(3, 3)[0], b.pixel(3, 3)[0]);
}

TEST(Offscreen, SupersamplingSmoothsTheSilhouette) {
  render::OffscreenRenderer r;
  r.set_scene(test::dressed_cylinder());
  render::OffscreenOptions aliased, smooth;
  aliased.supersample = 1;
  smooth.supersample = 3;
  auto largest_step = [](const render::Image& im) {
    // The largest jump between neighbours along rows crossing the body's sides:
    // anti-aliasing spreads the background-to-body step over two pixels.
    int step = 0;
    for (int y = 10; y < 30; ++y)
      for (int x = 0; x + 1 < im.width; ++x) step = std::max(step, std::abs(im.pixel(x + 1, y)[0] - im.pixel(x, y)[0]));
    return step;
  };
  EXPECT_LT(largest_step(r.render(front(), 128, 128, smooth)), largest_step(r.render(front(), 128, 128, aliased)));
}

TEST(Offscreen, AnEmptySceneIsRefused) {
  render::OffscreenRenderer r;
  r.set_scene(render::Scene{});
  EXPECT_THROW(r.render(front(), 32, 32), Error);
}

TEST(Offscreen, TheContextIsOpenGl33CoreOrNewer) {
  render::OffscreenRenderer r;
  const std::string d = r.gl_description();
  EXPECT_NE(d.find("Core Profile"), std::string::npos) << d;
}

// project() puts a world point where the renderer draws it: the red tube's
// top and bottom edges at its front (y = 1.0 and 0.6 m, z = 0.2 m) project to
// the first and last red rows of the picture's middle column, within a pixel;
// unproject() takes a pixel and depth back to the point; a point behind the
// camera projects nowhere.
TEST(Offscreen, ProjectGivesThePixelWhereAPointIsDrawn) {
  const auto scene = test::dressed_cylinder();
  render::OffscreenRenderer r;
  r.set_scene(scene);
  const int w = 160, h = 120;
  const auto view = *render::find_view("three-quarter");
  const render::Camera cam = render::frame_camera(view, r.framing_box({}), static_cast<double>(w) / h);
  const auto im = r.render(view, w, h);
  const auto front_of = [&](double y) {
    const double a = view.azimuth_deg * M_PI / 180.0;  // the tube's point facing the camera
    return std::array<double, 3>{0.2 * std::sin(a), y, 0.2 * std::cos(a)};
  };
  const auto top = render::project(cam, w, h, front_of(1.0)), bottom = render::project(cam, w, h, front_of(0.6));
  ASSERT_TRUE(top && bottom);
  const int col = static_cast<int>(std::lround(top->x));
  ASSERT_NEAR(top->x, bottom->x, 1.0);
  int first = -1, last = -1;
  for (int y = 0; y < h; ++y) {
    const auto* p = im.pixel(col, y);
    if (p[0] > p[1] + 60 && p[0] > p[2] + 60) {
      if (first < 0) first = y;
      last = y;
    }
  }
  ASSERT_GE(first, 0) << "the red tube is drawn";
  EXPECT_NEAR(first + 0.5, top->y, 1.0);
  EXPECT_NEAR(last + 0.5, bottom->y, 1.0);
  const auto back = render::unproject(cam, w, h, top->x, top->y, top->depth);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], front_of(1.0)[k], 1e-9);
  const std::array<double, 3> behind{2 * cam.eye[0] - cam.target[0], 2 * cam.eye[1] - cam.target[1],
                                     2 * cam.eye[2] - cam.target[2]};
  EXPECT_FALSE(render::project(cam, w, h, behind).has_value());
}
