// Real pattern files through the whole xvc stage: the repository's drafted skirt always,
// the shared DXF samples when ../shared is there. Each imported style must give a valid
// document that reads back to the same style and draws one outline per pattern.
#include <gtest/gtest.h>

#include "fixtures.hpp"
#include <tinyxml2.h>

#include <cstdio>
#include <functional>
#include <map>

#include "vgd/io/dxf/import.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;
namespace fs = std::filesystem;

namespace {
void check_garment(const fs::path& dxf) {
  SCOPED_TRACE(dxf.filename().string());
  const auto imported = vgd::dxf::import_file(dxf);
  const Document doc = from_style(imported.style);
  const std::string xml = save_string(doc);
  const auto d = validate_string(xml, dxf.filename().string(), schema());
  EXPECT_FALSE(d.has_errors()) << dump(d);
  // Same style back, bit for bit, through the text.
  const auto back = to_style(load_string(xml, "back.xvc"));
  ASSERT_EQ(back.pieces.size(), imported.style.pieces.size());
  for (std::size_t k = 0; k < back.pieces.size(); ++k) {
    const auto &a = back.pieces[k], &b = imported.style.pieces[k];
    ASSERT_EQ(a.boundary.size(), b.boundary.size()) << a.block;
    for (std::size_t i = 0; i < a.boundary.size(); ++i) {
      EXPECT_EQ(a.boundary[i].p, b.boundary[i].p) << a.block << " vertex " << i;
      EXPECT_EQ(a.boundary[i].kind, b.boundary[i].kind) << a.block << " vertex " << i;
    }
    EXPECT_EQ(a.notches.size(), b.notches.size()) << a.block;
  }
  EXPECT_EQ(back.sizes, imported.style.sizes);
  const std::string svg = render_svg(doc, stylesheet());
  std::size_t outlines = 0;
  for (auto p = svg.find("class=\"outline\""); p != std::string::npos; p = svg.find("class=\"outline\"", p + 1)) ++outlines;
  EXPECT_EQ(outlines, doc.patterns().size());
  EXPECT_EQ(svg.find("NaN"), std::string::npos);
}
}  // namespace

TEST(RealFiles, DraftedSkirtIsValidLosslessAndDrawable) {
  check_garment(vgd::test::source_dir() / "data" / "garments" / "a-line-skirt.dxf");
}

TEST(RealFiles, SharedSamplesAreValidLosslessAndDrawable) {
  VGD_REQUIRE_SHARED();
  int files = 0;
  for (const auto& e : fs::directory_iterator(vgd::test::shared_dir() / "data" / "dxf")) {
    const auto ext = e.path().extension().string();
    if (ext != ".dxf" && ext != ".DXF") continue;
    check_garment(e.path());
    ++files;
  }
  EXPECT_GT(files, 0);
}

// The seed's XSL view, run by the xsltproc program itself on a real Gerber file
// (7 pieces x 15 sizes, inch units): every pattern, notch, grain line and drill
// hole of the imported style must be drawn, inside the drawing's view box.
TEST(RealFiles, XsltprocDrawsAnImportedGerberFile) {
  VGD_REQUIRE_SHARED();
  const auto imported = vgd::dxf::import_file(vgd::test::shared_dxf("MEN_CLASSIC_TEE.DXF"));
  const Document doc = from_style(imported.style);
  const std::string svg = render_svg_with_xsltproc(doc, stylesheet());
  tinyxml2::XMLDocument x;
  ASSERT_EQ(x.Parse(svg.c_str(), svg.size()), tinyxml2::XML_SUCCESS) << "the SVG is not well-formed";
  const auto* root = x.RootElement();
  ASSERT_STREQ(root->Name(), "svg");
  double vb[4] = {0, 0, 0, 0};
  ASSERT_EQ(std::sscanf(root->Attribute("viewBox"), "%lf %lf %lf %lf", &vb[0], &vb[1], &vb[2], &vb[3]), 4);

  std::map<std::string, int> count;
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  std::function<void(const tinyxml2::XMLElement*)> walk = [&](const tinyxml2::XMLElement* e) {
    if (const char* c = e->Attribute("class")) ++count[c];
    for (const char* a : {"x1", "x2", "cx"})
      if (e->Attribute(a)) min_x = std::min(min_x, e->DoubleAttribute(a)), max_x = std::max(max_x, e->DoubleAttribute(a));
    for (const char* a : {"y1", "y2", "cy"})
      if (e->Attribute(a)) min_y = std::min(min_y, e->DoubleAttribute(a)), max_y = std::max(max_y, e->DoubleAttribute(a));
    for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) walk(c);
  };
  walk(root);

  int notches = 0, grains = 0, drills = 0;
  for (const auto& p : imported.style.pieces) {
    notches += static_cast<int>(p.notches.size());
    grains += p.grain_line.has_value();
    drills += static_cast<int>(p.drill_holes.size());
  }
  EXPECT_EQ(count["pattern"], 105);
  EXPECT_EQ(count["outline"], 105);
  EXPECT_EQ(count["notch"], notches);
  EXPECT_EQ(count["grain"], grains);
  EXPECT_EQ(count["drill"], drills);
  EXPECT_GT(notches, 0);
  EXPECT_GE(min_x, vb[0]);
  EXPECT_LE(max_x, vb[0] + vb[2]);
  EXPECT_GE(min_y, vb[1]);
  EXPECT_LE(max_y, vb[1] + vb[3]);
}
