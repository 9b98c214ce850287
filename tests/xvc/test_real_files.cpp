// Real pattern files through the whole xvc stage: the repository's drafted skirt always,
// the shared DXF samples when ../shared is there. Each imported style must give a valid
// document that reads back to the same style and draws one outline per pattern.
#include <gtest/gtest.h>

#include "fixtures.hpp"
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
