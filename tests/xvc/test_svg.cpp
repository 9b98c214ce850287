#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <sstream>

#include "fixtures.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;

namespace {
// What a test needs to know about a drawing.
struct Drawing {
  double width = 0, height = 0;  // viewBox
  std::vector<std::string> pattern_ids, labels;
  std::map<std::string, int> count;          // by class
  std::vector<std::pair<double, double>> xy;  // every coordinate drawn
  bool has_nan = false;
};

void add_number_pairs(Drawing& d, const std::string& text) {
  std::istringstream in(text);
  std::vector<double> nums;
  std::string tok;
  while (in >> tok) {
    if (tok == "M" || tok == "L" || tok == "Z") continue;
    const auto v = vgd::parse_double(tok);
    if (!v) d.has_nan = true;
    else nums.push_back(*v);
  }
  for (std::size_t i = 0; i + 1 < nums.size(); i += 2) d.xy.emplace_back(nums[i], nums[i + 1]);
}

void walk(Drawing& d, const tinyxml2::XMLElement* e) {
  const std::string name = e->Name();
  const char* cls = e->Attribute("class");
  if (cls) ++d.count[cls];
  if (cls && std::string(cls) == "pattern") d.pattern_ids.emplace_back(e->Attribute("id"));
  if (cls && std::string(cls) == "label") d.labels.emplace_back(e->GetText() ? e->GetText() : "");
  auto num = [&](const char* a) {
    const auto v = vgd::parse_double(e->Attribute(a) ? e->Attribute(a) : "");
    if (!v) d.has_nan = true;
    return v.value_or(0);
  };
  if (name == "path" && cls) add_number_pairs(d, e->Attribute("d"));
  if (name == "line") {
    d.xy.emplace_back(num("x1"), num("y1"));
    d.xy.emplace_back(num("x2"), num("y2"));
  }
  if (name == "circle") d.xy.emplace_back(num("cx"), num("cy"));
  if (name == "text") d.xy.emplace_back(num("x"), num("y"));
  for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) walk(d, c);
}

Drawing read_svg(const std::string& svg) {
  tinyxml2::XMLDocument xml;
  EXPECT_EQ(xml.Parse(svg.c_str(), svg.size()), tinyxml2::XML_SUCCESS) << "SVG is not well-formed";
  Drawing d;
  const auto* root = xml.RootElement();
  if (!root) return d;
  EXPECT_STREQ(root->Name(), "svg");
  EXPECT_STREQ(root->Attribute("xmlns"), "http://www.w3.org/2000/svg");
  std::istringstream vb(root->Attribute("viewBox") ? root->Attribute("viewBox") : "");
  double x0 = -1, y0 = -1;
  vb >> x0 >> y0 >> d.width >> d.height;
  EXPECT_EQ(x0, 0);
  EXPECT_EQ(y0, 0);
  walk(d, root);
  return d;
}

std::size_t total_notches(const Document& doc) {
  std::size_t n = 0;
  for (const Node* p : doc.patterns()) n += to_piece(doc, p->id()).notches.size();
  return n;
}

void expect_complete_drawing(const Document& doc, const Drawing& d) {
  EXPECT_FALSE(d.has_nan) << "a coordinate did not come out as a number";
  EXPECT_EQ(d.count.at("outline"), static_cast<int>(doc.patterns().size()));
  ASSERT_EQ(d.pattern_ids.size(), doc.patterns().size());
  for (std::size_t i = 0; i < d.pattern_ids.size(); ++i) EXPECT_EQ(d.pattern_ids[i], doc.patterns()[i]->id());
  EXPECT_EQ(d.count.at("notch"), static_cast<int>(total_notches(doc)));
  EXPECT_EQ(d.count.at("grain"), 4);  // the POCKET has none
  EXPECT_EQ(d.count.at("drill"), 8);
  EXPECT_EQ(d.count.at("cutout"), 4);
  EXPECT_EQ(d.labels.front(), "FRONT 36");
  EXPECT_EQ(d.labels.back(), "POCKET 38");
  // Everything inside the picture.
  ASSERT_FALSE(d.xy.empty());
  for (const auto& [x, y] : d.xy) {
    EXPECT_GE(x, 0);
    EXPECT_LE(x, d.width);
    EXPECT_GE(y, 0);
    EXPECT_LE(y, d.height);
  }
}
}  // namespace

TEST(Svg, XsltprocDrawsEveryPatternNotchAndGrainLine) {
  const auto dir = vgd::test::scratch_dir("xvc_svg_xsltproc");
  const Document doc = full_document();
  save_file(doc, dir / "g.xvc");
  ASSERT_EQ(run("xsltproc --nonet -o '" + (dir / "g.svg").string() + "' '" + stylesheet().string() + "' '" +
                (dir / "g.xvc").string() + "' 2> '" + (dir / "err.txt").string() + "'"),
            0)
      << slurp(dir / "err.txt");
  const Drawing d = read_svg(slurp(dir / "g.svg"));
  expect_complete_drawing(doc, d);
  // One row per piece, in millimetres: FRONT 36 and 38 side by side (300 mm each, a 30 mm
  // gap), then BACK, then POCKET; rows 450, 450 and 100 mm high with 16 mm for labels.
  EXPECT_NEAR(d.width, 300 + 30 + 300 + 2 * 20, 1e-9);
  EXPECT_NEAR(d.height, 2 * 20 + 450 + 450 + 100 + 3 * 16 + 2 * 30, 1e-9);
}

TEST(Svg, RowLayoutPutsEveryPatternSideBySide) {
  const Document doc = full_document();
  const Drawing d = read_svg(render_svg(doc, stylesheet(), {{"layout", "row"}}));
  expect_complete_drawing(doc, d);
  EXPECT_NEAR(d.width, 4 * 300 + 100 + 4 * 30 + 2 * 20, 1e-9);
  EXPECT_NEAR(d.height, 450 + 16 + 2 * 20, 1e-9);
}

TEST(Svg, RenderSvgMatchesXsltproc) {
  const Document doc = full_document();
  const std::string a = render_svg(doc, stylesheet());
  const std::string b = render_svg_with_xsltproc(doc, stylesheet());
  expect_complete_drawing(doc, read_svg(a));
  EXPECT_EQ(a, b);
}

TEST(Svg, OwnLayoutKeepsPatternCoordinates) {
  const Document doc = from_style(full_style());
  const Drawing d = read_svg(render_svg(doc, stylesheet(), {{"layout", "own"}}));
  expect_complete_drawing(doc, d);
  // x from 0 to 3.1 m plus margins; the third pattern starts 1.1 m right of the first.
  EXPECT_NEAR(d.width, 3100 + 40, 1e-9);
}

TEST(Svg, ScaleParameterChangesUnits) {
  const Document doc = from_style(full_style());
  const Drawing mm = read_svg(render_svg(doc, stylesheet(), {{"layout", "row"}}));
  const Drawing cm = read_svg(render_svg(doc, stylesheet(), {{"layout", "row"}, {"scale", "100"}}));
  EXPECT_NEAR(cm.width - 40, (mm.width - 40 - 4 * 30) / 10 + 4 * 30, 1e-6);
}

TEST(Svg, EmptyGarmentGivesAnEmptyPicture) {
  const Drawing d = read_svg(render_svg(Document{}, stylesheet()));
  EXPECT_EQ(d.count.count("outline"), 0u);
  EXPECT_GT(d.width, 0);
}

TEST(Svg, BrokenStylesheetIsAnError) {
  const auto dir = vgd::test::scratch_dir("xvc_svg_broken");
  vgd::write_file_atomic(dir / "bad.xsl", "<xsl:stylesheet version=\"1.0\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\"><xsl:bogus/>");
  EXPECT_THROW(render_svg(Document{}, dir / "bad.xsl"), vgd::Error);
  EXPECT_THROW(render_svg_with_xsltproc(Document{}, dir / "bad.xsl"), vgd::Error);
}
