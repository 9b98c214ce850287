// Fit maps (render/fit_map.hpp): per-vertex strain of a garment against its
// rest shape, the colour ramp, and the legend drawn onto an image; and
// `vgd render --map` end to end.
#include <gtest/gtest.h>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/render/fit_map.hpp"
#include "vgd/render/image.hpp"

using namespace vgd;
namespace fs = std::filesystem;

namespace {

// A 0.4 × 0.3 m rest grid of 5 × 4 vertices (uv, m), its positions stretched
// by `su` along the warp and `sv` along the weft and laid in the x-y plane.
render::Mesh stretched_sheet(double su, double sv) {
  render::Mesh m;
  m.name = "SHEET";
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i) {
      const float u = 0.1f * i, v = 0.1f * j;
      m.uv.push_back({u, v});
      m.positions.push_back({static_cast<float>(su * u), static_cast<float>(1.0 + sv * v), 0.0f});
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = 5 * j + i;
      m.triangles.push_back({a, a + 1, a + 6});
      m.triangles.push_back({a, a + 6, a + 5});
    }
  return m;
}

// The sheet as dir/garment.obj with its material coordinates (vt), as vgd
// drape writes a garment.
void write_garment_obj(const fs::path& dir, const render::Mesh& m) {
  std::string obj = "g SHEET\n";
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    obj += "v " + std::to_string(m.positions[i][0]) + " " + std::to_string(m.positions[i][1]) + " 0\nvt " +
           std::to_string(m.uv[i][0]) + " " + std::to_string(m.uv[i][1]) + "\n";
  for (const auto& t : m.triangles)
    obj += "f " + std::to_string(t[0] + 1) + "/" + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + "/" +
           std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "/" + std::to_string(t[2] + 1) + "\n";
  write_file_atomic(dir / "garment.obj", obj);
}

bool same(const render::Colour& a, const render::Colour& b) {
  return std::abs(a.r - b.r) < 1e-6 && std::abs(a.g - b.g) < 1e-6 && std::abs(a.b - b.b) < 1e-6;
}

}  // namespace

TEST(FitMap, AUniformStretchGivesItsStrainAtEveryVertex) {
  const auto m = stretched_sheet(1.05, 1.20);
  const auto warp = render::fit_values(m, render::FitMap::warp);
  const auto weft = render::fit_values(m, render::FitMap::weft);
  const auto shear = render::fit_values(m, render::FitMap::shear);
  const auto stretch = render::fit_values(m, render::FitMap::stretch);
  ASSERT_EQ(warp.size(), m.positions.size());
  for (std::size_t i = 0; i < warp.size(); ++i) {
    EXPECT_NEAR(warp[i], 5.0, 1e-4);
    EXPECT_NEAR(weft[i], 20.0, 1e-4);
    EXPECT_NEAR(shear[i], 0.0, 1e-3);
    EXPECT_NEAR(stretch[i], 20.0, 1e-4);
  }
  render::Mesh none = m;
  none.uv.clear();
  EXPECT_THROW(render::fit_values(none, render::FitMap::weft), vgd::Error);
}

TEST(FitMap, TheRampSpansTheScaleAndClampsBeyondIt) {
  auto m = stretched_sheet(1.0, 1.20);  // weft 20 %: the middle of 0–40 %
  m.texture = std::make_shared<render::Texture>();
  render::colour_by(m, render::fit_values(m, render::FitMap::weft), render::default_scale(render::FitMap::weft));
  ASSERT_EQ(m.vertex_colours.size(), m.positions.size());
  EXPECT_TRUE(same(m.vertex_colours[7], render::ramp(0.5)));
  EXPECT_FALSE(m.texture) << "a map replaces the texture";
  EXPECT_TRUE(same(m.colour, {1, 1, 1}));
  render::colour_by(m, std::vector<double>(m.positions.size(), 90.0), {0, 40});
  EXPECT_TRUE(same(m.vertex_colours[0], render::ramp(1.0)));
  render::colour_by(m, std::vector<double>(m.positions.size(), -5.0), {0, 40});
  EXPECT_TRUE(same(m.vertex_colours[0], render::ramp(0.0)));
  // Blue at the low end, red at the high end.
  EXPECT_GT(render::ramp(0).b, render::ramp(0).r + 0.4f);
  EXPECT_GT(render::ramp(1).r, render::ramp(1).b + 0.4f);
}

TEST(FitMap, TheLegendIsARampWithItsLabels) {
  render::Image img(400, 300, {240, 240, 240, 255});
  render::draw_legend(img, render::FitMap::weft, {0, 40});
  // The bar: red near its top, blue near its bottom, right of the middle.
  int red = 0, blue = 0, ink = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = img.width / 2; x < img.width; ++x) {
      const auto* p = img.pixel(x, y);
      red += y < img.height / 2 && p[0] > 180 && p[2] < 80;
      blue += y > img.height / 2 && p[2] > 150 && p[0] < 80;
      ink += p[0] < 60 && p[1] < 60 && p[2] < 60;
    }
  EXPECT_GT(red, 30);
  EXPECT_GT(blue, 30);
  EXPECT_GT(ink, 150) << "the frame, ticks and labels";
  // Nothing on the left half.
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width / 2; ++x) ASSERT_EQ(img.pixel(x, y)[0], 240) << x << "," << y;
}

TEST(CmdRender, AFitMapColoursTheGarmentByItsStrainWithALegend) {
  const auto dir = test::scratch_dir("cmd_render_fit_map");
  // garment.obj with material coordinates (vt), as vgd drape writes it: the
  // sheet stretched 30 % along the weft.
  const auto m = stretched_sheet(1.0, 1.30);
  write_garment_obj(dir, m);
  const auto r = test::run_vgd({"render", dir.string(), "--map", "weft", "--views", "front", "--size", "200x150",
                                "--no-floor", "-o", (dir / "out").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("weft strain, % of SHEET: p50 30.0, p95 30.0, max 30.0"), std::string::npos) << r.err;
  const auto img = render::read_png(dir / "out" / "front.png");
  // The sheet, in the middle of the view, takes the ramp's colour at 30/40
  // (orange-yellow: much red, some green, little blue), shaded by the light.
  const auto* p = img.pixel(img.width / 3, img.height / 2);
  EXPECT_GT(p[0], p[2] + 60) << int(p[0]) << " " << int(p[1]) << " " << int(p[2]);
  EXPECT_GT(p[1], p[2] + 30) << int(p[0]) << " " << int(p[1]) << " " << int(p[2]);
  // Bad ranges and a range without a map are usage errors.
  const auto bad = test::run_vgd({"render", dir.string(), "--map", "weft", "--map-range", "40,0", "-o",
                                  (dir / "bad").string()});
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--map-range"), std::string::npos) << bad.err;
  const auto alone = test::run_vgd({"render", dir.string(), "--map-range", "0,40", "-o", (dir / "bad").string()});
  EXPECT_EQ(alone.code, 2);
  EXPECT_NE(alone.err.find("applies to a fit map"), std::string::npos) << alone.err;
  const auto unknown = test::run_vgd({"render", dir.string(), "--map", "tension", "-o", (dir / "bad").string()});
  EXPECT_EQ(unknown.code, 2);
  // A pressure map needs the drape's contact-pressure.json, which this folder lacks.
  const auto none = test::run_vgd({"render", dir.string(), "--map", "pressure", "-o", (dir / "bad").string()});
  EXPECT_EQ(none.code, 1);
  EXPECT_NE(none.err.find("contact-pressure.json"), std::string::npos) << none.err;
}

// The contact-pressure map takes one value per vertex of garment.obj from
// the drape's contact-pressure.json (Pa), drawn in kPa over 0–5 kPa: the
// sheet's top row pressing 4 kPa comes out orange-red, its bottom row at 0
// blue. A file of another drape (another vertex count) or not a pressure
// map is refused naming it.
TEST(CmdRender, APressureMapColoursEachVertexByTheDrapesPressure) {
  const auto dir = test::scratch_dir("cmd_render_pressure_map");
  const auto m = stretched_sheet(1.0, 1.0);
  write_garment_obj(dir, m);
  std::string values;
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    values += std::string(values.empty() ? "" : ",") + (i >= 15 ? "4000" : "0");
  write_file_atomic(dir / "contact-pressure.json", "{\"unit\": \"Pa\", \"values\": [" + values + "]}");
  const auto r = test::run_vgd({"render", dir.string(), "--map", "pressure", "--views", "front", "--size", "200x150",
                                "--no-floor", "-o", (dir / "out").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("contact pressure, kPa of SHEET: p50 0.0, p95 4.0, max 4.0"), std::string::npos) << r.err;
  const auto img = render::read_png(dir / "out" / "front.png");
  // Find the sheet's rows on the image: its highest and lowest coloured pixels in the middle column.
  int top = -1, bottom = -1;
  const int x = img.width / 3;
  for (int y = 0; y < img.height; ++y) {
    const auto* p = img.pixel(x, y);
    const bool coloured = std::abs(p[0] - p[1]) > 30 || std::abs(p[1] - p[2]) > 30;
    if (coloured && top < 0) top = y;
    if (coloured) bottom = y;
  }
  ASSERT_GT(bottom, top + 10);
  const auto* hi = img.pixel(x, top + 2);
  const auto* lo = img.pixel(x, bottom - 2);
  EXPECT_GT(hi[0], hi[2] + 60) << int(hi[0]) << " " << int(hi[1]) << " " << int(hi[2]);
  EXPECT_GT(lo[2], lo[0] + 60) << int(lo[0]) << " " << int(lo[1]) << " " << int(lo[2]);
  write_file_atomic(dir / "contact-pressure.json", "{\"unit\": \"Pa\", \"values\": [1, 2, 3]}");
  const auto fewer = test::run_vgd({"render", dir.string(), "--map", "pressure", "-o", (dir / "bad").string()});
  EXPECT_EQ(fewer.code, 1);
  EXPECT_NE(fewer.err.find("holds 3 pressures for the 20 vertices"), std::string::npos) << fewer.err;
  write_file_atomic(dir / "contact-pressure.json", "{\"unit\": \"Pa\", \"values\": [1, -2]}");
  const auto negative = test::run_vgd({"render", dir.string(), "--map", "pressure", "-o", (dir / "bad").string()});
  EXPECT_EQ(negative.code, 1);
  EXPECT_NE(negative.err.find("values[1]"), std::string::npos) << negative.err;
  EXPECT_THROW(render::fit_values(m, render::FitMap::pressure), vgd::Error);
  EXPECT_STREQ(render::unit_of(render::FitMap::pressure), "kPa");
}

// The stress map against plane stress by hand: a sheet stretched 2 % along
// the warp only (ε_f = 0, γ = 0) in shirting's moduli (E_w 5000, E_f 3000,
// G 400 N/m, ν_wf 0.3; ν_fw = 0.18) carries σ_w = E_w ε_w / (1 − ν_wf ν_fw) =
// 100 / 0.946 = 105.7 N/m, the larger principal tension; 2 % along the weft
// only, σ_f = 60 / 0.946 = 63.4 N/m; compressed both ways, 0 (cloth buckles).
// Without a fabric the map is refused.
TEST(FitMap, StressIsTheLargerPrincipalTensionOfPlaneStress) {
  const render::Membrane shirting{5000.0, 3000.0, 400.0, 0.3};
  const double d = 1.0 - 0.3 * 0.3 * 3000.0 / 5000.0;
  for (double v : render::fit_values(stretched_sheet(1.02, 1.0), render::FitMap::stress, &shirting))
    EXPECT_NEAR(v, 5000.0 * 0.02 / d, 1e-2);
  for (double v : render::fit_values(stretched_sheet(1.0, 1.02), render::FitMap::stress, &shirting))
    EXPECT_NEAR(v, 3000.0 * 0.02 / d, 1e-2);
  for (double v : render::fit_values(stretched_sheet(0.97, 0.98), render::FitMap::stress, &shirting))
    EXPECT_EQ(v, 0.0);
  EXPECT_THROW(render::fit_values(stretched_sheet(1.02, 1.0), render::FitMap::stress), vgd::Error);
  const render::Membrane bad{0.0, 3000.0, 400.0, 0.3};
  EXPECT_THROW(render::fit_values(stretched_sheet(1.02, 1.0), render::FitMap::stress, &bad), vgd::Error);
  EXPECT_STREQ(render::unit_of(render::FitMap::stress), "N/m");
}

// `vgd render --map stress` takes each piece's fabric from the garment
// document: the sheet stretched 2 % along the warp, cut from shirting (the
// default) and then from a MATERIAL of its own (E_warp 10 000 N/m): twice the
// tension, each said with its fabric's name.
TEST(CmdRender, AStressMapTakesEachPiecesFabricFromTheDocument) {
  const auto dir = test::scratch_dir("cmd_render_stress_map");
  const auto m = stretched_sheet(1.02, 1.0);
  write_garment_obj(dir, m);
  auto doc = [&](bool own) {
    std::string x = R"(<?xml version="1.0" encoding="UTF-8"?>
<GARMENT id="garment" version="1.0" name="SHEET">
  <PATTERNS id="patterns">
    <PATTERN id="pattern1" block="SHEET" piece="SHEET" size="38" quantity="1">
      <C2DSEQ id="seq1"><C2D x="0" y="0" kind="turn"/><C2D x="0.4" y="0"/><C2D x="0.4" y="0.3"/><C2D x="0" y="0.3"/></C2DSEQ>)";
    if (own) x += R"(
      <ASSOCIATION id="assoc1" ref="stiff" role="material"/>)";
    x += R"(
    </PATTERN>
  </PATTERNS>
  <MATERIALS id="materials">)";
    if (own) x += R"(
    <MATERIAL id="stiff" name="stiff twill" scope="piece">
      <PARAMETER id="p1" name="density" value="0.3" unit="kg/m2"/>
      <PARAMETER id="p2" name="E_warp" value="10000" unit="N/m"/>
      <PARAMETER id="p3" name="E_weft" value="6000" unit="N/m"/>
      <PARAMETER id="p4" name="G" value="400" unit="N/m"/>
      <PARAMETER id="p5" name="nu_warp_weft" value="0.3" unit="1"/>
    </MATERIAL>)";
    x += R"(
  </MATERIALS>
</GARMENT>
)";
    return x;
  };
  const double d = 1.0 - 0.3 * 0.3 * 3000.0 / 5000.0;
  write_file_atomic(dir / "plain.xvc", doc(false));
  write_file_atomic(dir / "own.xvc", doc(true));
  const auto plain = test::run_vgd({"render", dir.string(), "--map", "stress", "--look", (dir / "plain.xvc").string(),
                                    "--views", "front", "--size", "200x150", "-o", (dir / "plain").string()});
  ASSERT_EQ(plain.code, 0) << plain.err;
  const std::string want = format_fixed(5000.0 * 0.02 / d, 1);
  EXPECT_NE(plain.err.find("tension, N/m of SHEET (shirting"), std::string::npos) << plain.err;
  EXPECT_NE(plain.err.find("p50 " + want), std::string::npos) << want << "\n" << plain.err;
  const auto own = test::run_vgd({"render", dir.string(), "--map", "stress", "--look", (dir / "own.xvc").string(),
                                  "--views", "front", "--size", "200x150", "-o", (dir / "own").string()});
  ASSERT_EQ(own.code, 0) << own.err;
  EXPECT_NE(own.err.find("tension, N/m of SHEET (stiff twill): p50 " + format_fixed(10000.0 * 0.02 / d, 1)),
            std::string::npos) << own.err;
}
