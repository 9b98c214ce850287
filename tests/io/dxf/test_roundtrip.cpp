// Import -> export -> import keeps pieces, sizes, attributes and geometry.
#include <gtest/gtest.h>

#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/dxf/export.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/pattern/draft.hpp"

using namespace vgd;
using pattern::Piece;
using pattern::Style;
using pattern::Vec2;

namespace {

Style feature_style() {
  Style s;
  s.name = "ROUND TRIP";
  s.flavour = "ASTM";
  s.sample_size = "38";
  s.sizes = {"38", "40"};
  for (const std::string size : {"38", "40"}) {
    Piece p;
    p.block = "FRONT_" + size;
    p.name = "FRONT";
    p.size = size;
    p.quantity = 2;
    p.quantity_flipped = 1;
    p.category = "SELF";
    p.fabric = "TWILL";
    p.annotation = "CUT ON GRAIN";
    p.annotations = {{"marker note", "keep"}, {"", "LOOSE TEXT"}};
    const double k = size == "38" ? 1.0 : 1.05;
    for (auto [x, y, kind] : {std::tuple{0.0, 0.0, pattern::PointKind::turn}, {0.25, 0.0, pattern::PointKind::turn},
                              {0.27, 0.3, pattern::PointKind::curve}, {0.25, 0.6, pattern::PointKind::turn},
                              {0.0, 0.6, pattern::PointKind::turn}, {0.02, 0.3, pattern::PointKind::plain}})
      p.boundary.push_back({Vec2(x * k + 0.123456789, y * k - 0.0101), kind});
    p.notches.push_back({Vec2(0.125 * k + 0.123456789, -0.0101), 90.0, 0.004, 0.001, 0, 1});
    p.grain_line = pattern::Segment{Vec2(0.1, 0.1), Vec2(0.1, 0.5)};
    p.grade_reference = pattern::Segment{Vec2(0.05, 0.05), Vec2(0.06, 0.05)};
    p.internal_lines.push_back({{Vec2(0.05, 0.2), Vec2(0.15, 0.25), Vec2(0.2, 0.2)}, false});
    p.cutouts.push_back({{Vec2(0.1, 0.3), Vec2(0.1, 0.32), Vec2(0.12, 0.32), Vec2(0.12, 0.3)}, true});
    p.sew_lines.push_back({{Vec2(0.01, 0.01), Vec2(0.24, 0.01)}, false});
    p.drill_holes = {Vec2(0.1, 0.4)};
    s.pieces.push_back(p);
  }
  return s;
}

void expect_same_geometry(const Piece& a, const Piece& b, double tol) {
  ASSERT_EQ(a.boundary.size(), b.boundary.size()) << a.block;
  for (std::size_t i = 0; i < a.boundary.size(); ++i) {
    EXPECT_LE((a.boundary[i].p - b.boundary[i].p).norm(), tol) << a.block << " vertex " << i;
    EXPECT_EQ(a.boundary[i].kind, b.boundary[i].kind) << a.block << " vertex " << i;
  }
  ASSERT_EQ(a.notches.size(), b.notches.size());
  for (std::size_t i = 0; i < a.notches.size(); ++i) {
    EXPECT_LE((a.notches[i].position - b.notches[i].position).norm(), tol);
    EXPECT_NEAR(a.notches[i].length_m, b.notches[i].length_m, tol);
  }
  EXPECT_EQ(a.grain_line.has_value(), b.grain_line.has_value());
  EXPECT_EQ(a.mirror_line.has_value(), b.mirror_line.has_value());
  EXPECT_EQ(a.internal_lines.size(), b.internal_lines.size());
  EXPECT_EQ(a.cutouts.size(), b.cutouts.size());
  EXPECT_EQ(a.sew_lines.size(), b.sew_lines.size());
  EXPECT_EQ(a.drill_holes.size(), b.drill_holes.size());
}

void expect_same_style(const Style& a, const Style& b, double tol) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.sample_size, b.sample_size);
  EXPECT_EQ(a.sizes, b.sizes);
  EXPECT_EQ(a.flavour, b.flavour);
  ASSERT_EQ(a.pieces.size(), b.pieces.size());
  for (std::size_t i = 0; i < a.pieces.size(); ++i) {
    const auto &p = a.pieces[i], &q = b.pieces[i];
    EXPECT_EQ(p.block, q.block);
    EXPECT_EQ(p.name, q.name);
    EXPECT_EQ(p.size, q.size);
    EXPECT_EQ(p.quantity, q.quantity);
    EXPECT_EQ(p.quantity_flipped, q.quantity_flipped);
    EXPECT_EQ(p.category, q.category);
    EXPECT_EQ(p.fabric, q.fabric);
    EXPECT_EQ(p.annotation, q.annotation);
    EXPECT_EQ(p.annotations, q.annotations);
    expect_same_geometry(p, q, tol);
  }
}

}  // namespace

TEST(DxfRoundTrip, EveryFeatureSurvivesExportAndImport) {
  const Style s = feature_style();
  const auto text = dxf::export_string(s);
  const auto back = dxf::import_string(text, "roundtrip.dxf");
  expect_same_style(s, back.style, 1e-12);
  EXPECT_EQ(back.diagnostics.count(Severity::warning), 0u);
}

TEST(DxfRoundTrip, InchOutputRoundTrips) {
  const Style s = feature_style();
  dxf::ExportOptions o;
  o.units = LengthUnit::inch;
  const auto back = dxf::import_string(dxf::export_string(s, o), "inch.dxf");
  EXPECT_EQ(back.style.units, "in");
  expect_same_style(s, back.style, 1e-12);
}

TEST(DxfRoundTrip, OneSizeCanBeExported) {
  dxf::ExportOptions o;
  o.size = "40";
  const auto back = dxf::import_string(dxf::export_string(feature_style(), o), "one.dxf");
  ASSERT_EQ(back.style.pieces.size(), 1u);
  EXPECT_EQ(back.style.pieces[0].size, "40");
  o.size = "99";
  EXPECT_THROW(dxf::export_string(feature_style(), o), Error);
}

TEST(DxfRoundTrip, ExportWritesAtomicallyAndRefusesNaN) {
  const auto dir = test::scratch_dir("dxf_export");
  const auto path = dir / "out.dxf";
  dxf::export_file(feature_style(), path);
  const auto before = read_file(path);
  Style bad = feature_style();
  bad.pieces[0].boundary[2].p.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(dxf::export_file(bad, path), Error);
  EXPECT_EQ(read_file(path), before) << "a failed export must leave the old file intact";
}

class SharedDxfRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(SharedDxfRoundTrip, ImportExportImportPreservesEverything) {
  VGD_REQUIRE_SHARED();
  const auto first = dxf::import_file(test::shared_dxf(GetParam()));
  const auto text = dxf::export_string(first.style);
  const auto second = dxf::import_string(text, GetParam() + " (re-exported)");
  // The file units differ (inch files come back in mm): allow for decimal text.
  expect_same_style(first.style, second.style, 1e-9);
  EXPECT_EQ(second.summary.pieces, first.summary.pieces);
  EXPECT_EQ(second.summary.blocks, first.summary.blocks);
}

INSTANTIATE_TEST_SUITE_P(AllFiles, SharedDxfRoundTrip,
                         ::testing::ValuesIn(vgd::test::shared_dxf_files()), vgd::test::FileParamName());

// data/garments/a-line-skirt.dxf is the project's own garment: it must be what
// `vgd draft skirt` produces today (regenerate it with that command if the draft changes).
TEST(DraftedSkirtData, CommittedFileMatchesTheDraft) {
  const auto committed = dxf::import_file(test::source_dir() / "data/garments/a-line-skirt.dxf");
  const auto fresh = dxf::import_string(dxf::export_string(pattern::draft_skirt_style()), "fresh.dxf");
  expect_same_style(fresh.style, committed.style, 1e-12);
  EXPECT_EQ(committed.summary.pieces, 3);
  EXPECT_EQ(committed.summary.blocks, 15);
  EXPECT_EQ(committed.diagnostics.count(Severity::warning), 0u);
}
