// Textured meshes: a garment with pattern coordinates and a texture shows the
// texture's colours where the garment is and changes no other pixel; the same
// textured scene gives the same bytes; a texture without coordinates is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "render/synthetic_scene.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/render/offscreen.hpp"

using namespace vgd;

namespace {

// A two-colour check, 8 x 8 pixels: green and white squares of 4 x 4.
std::shared_ptr<render::Texture> green_white_check(double repeat_m) {
  auto t = std::make_shared<render::Texture>();
  t->image = render::Image(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      auto* p = t->image.pixel(x, y);
      const bool green = (x < 4) != (y < 4);
      p[0] = green ? 30 : 245, p[1] = green ? 150 : 245, p[2] = green ? 50 : 245;
    }
  t->repeat_m = {repeat_m, repeat_m};
  return t;
}

// The dressed cylinder with the skirt's pattern coordinates: u = arc length
// round the tube from the front (+Z), cut at the back; v = height, m.
render::Scene with_uv(render::Scene s) {
  for (auto& m : s.meshes) {
    if (m.kind != render::MeshKind::garment) continue;
    for (const auto& p : m.positions) m.uv.push_back({0.2f * std::atan2(p[0], p[2]), p[1]});
  }
  return s;
}

render::Mesh& skirt(render::Scene& s) { return s.meshes[1]; }

const render::ViewPreset& front() {
  static const render::ViewPreset v = *render::find_view("front");
  return v;
}

bool same_pixel(const render::Image& a, const render::Image& b, int x, int y) {
  return std::equal(a.pixel(x, y), a.pixel(x, y) + 4, b.pixel(x, y));
}

}  // namespace

TEST(Texture, ATexturedGarmentShowsBothColoursAndNothingElseChanges) {
  const int n = 128;
  // Where the garment is: the pixels a red and a blue garment colour differently.
  const auto red = render::render_view(with_uv(test::dressed_cylinder({0.8f, 0.1f, 0.1f})), front(), n, n);
  const auto blue = render::render_view(with_uv(test::dressed_cylinder({0.1f, 0.1f, 0.8f})), front(), n, n);
  render::Scene textured = with_uv(test::dressed_cylinder({1, 1, 1}));
  skirt(textured).texture = green_white_check(0.1);
  const auto tex = render::render_view(textured, front(), n, n);

  int garment = 0, changed = 0, green = 0, white = 0, outside_changed = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      if (same_pixel(red, blue, x, y)) {
        outside_changed += !same_pixel(red, tex, x, y);
        continue;
      }
      ++garment;
      changed += !same_pixel(red, tex, x, y);
      const auto* p = tex.pixel(x, y);
      green += p[1] > p[0] + 40 && p[1] > p[2] + 40;
      white += p[0] > 150 && std::abs(p[0] - p[1]) < 20 && std::abs(p[1] - p[2]) < 20;
    }
  ASSERT_GT(garment, n * n / 40) << "the garment is in view";
  EXPECT_EQ(outside_changed, 0) << "the texture changes only the garment's pixels";
  EXPECT_GT(changed, garment * 9 / 10);
  EXPECT_GT(green, garment / 6) << "the check's green squares";
  EXPECT_GT(white, garment / 6) << "the check's white squares";
}

TEST(Texture, TheSameTexturedSceneGivesTheSameBytes) {
  render::Scene s = with_uv(test::dressed_cylinder({1, 1, 1}));
  skirt(s).texture = green_white_check(0.03);
  const auto view = *render::find_view("three-quarter");
  const auto a = render::render_view(s, view, 96, 80), b = render::render_view(s, view, 96, 80);
  EXPECT_TRUE(render::encode_png(a) == render::encode_png(b));
}

TEST(Texture, UvWithoutATextureChangesNothing) {
  const auto plain = render::render_view(test::dressed_cylinder(), front(), 64, 64);
  const auto uv = render::render_view(with_uv(test::dressed_cylinder()), front(), 64, 64);
  EXPECT_TRUE(plain.rgba == uv.rgba);
}

TEST(Texture, FineChecksAverageInsteadOfAliasing) {
  // 2 mm checks seen from ~3 m at 128 px (about 1.5 cm a pixel): mipmapping
  // blends them into one light green; without it neighbouring pixels would
  // flicker between green and white.
  render::Scene s = with_uv(test::dressed_cylinder({1, 1, 1}));
  skirt(s).texture = green_white_check(0.004);
  const auto im = render::render_view(s, front(), 128, 128);
  int steps = 0;
  for (int x = 56; x < 72; ++x) steps += std::abs(im.pixel(x + 1, 67)[0] - im.pixel(x, 67)[0]) > 40;
  EXPECT_EQ(steps, 0);
}

TEST(Texture, ATextureNeedsCoordinatesAndAValidImage) {
  render::Scene s = test::dressed_cylinder();
  skirt(s).texture = green_white_check(0.1);
  EXPECT_THROW(render::check_scene(s), Error) << "no uv";
  s = with_uv(test::dressed_cylinder());
  skirt(s).uv.pop_back();
  EXPECT_THROW(render::check_scene(s), Error) << "one uv short";
  s = with_uv(test::dressed_cylinder());
  auto bad = green_white_check(0.1);
  bad->repeat_m[1] = 0;
  skirt(s).texture = bad;
  EXPECT_THROW(render::check_scene(s), Error) << "zero repeat";
  skirt(s).texture = green_white_check(0.1);
  EXPECT_NO_THROW(render::check_scene(s));
}
