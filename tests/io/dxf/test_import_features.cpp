// What the importer understands: units, INSERT transforms, arcs, LWPOLYLINE,
// attributes, AAMA markers, notches, mirror lines, chaining.
#include <gtest/gtest.h>

#include <cmath>

#include "dxf_text.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/pattern/contour.hpp"

using vgd::dxf::import_string;
using vgd::pattern::signed_area;
using vgd::pattern::Vec2;
using vgd::test::DxfText;

namespace {
std::string file_with(const std::function<void(DxfText&)>& blocks, const std::function<void(DxfText&)>& entities) {
  DxfText d;
  d.begin_blocks();
  blocks(d);
  d.end_section().begin_entities();
  entities(d);
  d.end_section().eof();
  return d.str();
}
}  // namespace

TEST(DxfImport, InchFileIsConvertedToMetres) {
  const auto r = import_string(file_with([](DxfText& d) { d.square_piece("S_M", "S", "M", 10); },
                                         [](DxfText& d) { d.text("1", "Units: ENGLISH").insert("S_M"); }),
                               "inch.dxf");
  EXPECT_EQ(r.style.units, "in");
  EXPECT_NEAR(r.blocks[0].area_m2, 0.254 * 0.254, 1e-12);
  EXPECT_NEAR(r.blocks[0].perimeter_m, 4 * 0.254, 1e-12);
}

TEST(DxfImport, InsunitsHeaderGivesUnitsWhenNoTextDoes) {
  DxfText d;
  d.pair(0, "SECTION").pair(2, "HEADER").pair(9, "$INSUNITS").pair(70, "5").pair(0, "ENDSEC");
  d.begin_blocks().square_piece("S_M", "S", "M", 10).end_section().begin_entities().insert("S_M").end_section().eof();
  const auto r = import_string(d.str(), "cm.dxf");
  EXPECT_EQ(r.style.units, "cm");
  EXPECT_NEAR(r.blocks[0].area_m2, 0.01, 1e-12);
}

TEST(DxfImport, UnitsOverrideWins) {
  vgd::dxf::ImportOptions o;
  o.units = vgd::LengthUnit::inch;
  const auto r = import_string(vgd::test::one_square_file(1), "x.dxf", o);
  EXPECT_NEAR(r.blocks[0].area_m2, 0.0254 * 0.0254, 1e-15);
}

TEST(DxfImport, InsertTransformIsApplied) {
  // Rotated 90°, scaled 2 and moved: the outline must land at the transformed place.
  const auto r = import_string(
      file_with([](DxfText& d) { d.square_piece("S_M", "S", "M", 100, 10, 0); },
                [](DxfText& d) { d.text("1", "Units: METRIC").insert("S_M", 1000, 500, 2, 2, 90); }),
      "ins.dxf");
  const auto& b = r.style.pieces[0].boundary;
  Vec2 lo = b[0].p, hi = b[0].p;
  for (const auto& c : b) lo = lo.cwiseMin(c.p), hi = hi.cwiseMax(c.p);
  // (x, y) -> (1000 - 2y, 500 + 2x) for x in [10, 110], y in [0, 100].
  EXPECT_NEAR(lo.x(), 0.800, 1e-9);
  EXPECT_NEAR(hi.x(), 1.000, 1e-9);
  EXPECT_NEAR(lo.y(), 0.520, 1e-9);
  EXPECT_NEAR(hi.y(), 0.720, 1e-9);
  EXPECT_NEAR(r.blocks[0].area_m2, 0.04, 1e-12);
  EXPECT_NEAR(vgd::pattern::grain_angle_deg(r.style.pieces[0]), 180.0, 1e-9);  // was +90°, turned by 90°
}

TEST(DxfImport, MirroringInsertKeepsOutlineCounterClockwise) {
  const auto r = import_string(
      file_with([](DxfText& d) { d.square_piece("S_M", "S", "M", 100); },
                [](DxfText& d) { d.text("1", "Units: METRIC").insert("S_M", 0, 0, -1, 1); }),
      "mir.dxf");
  EXPECT_GT(signed_area(r.style.pieces[0].boundary), 0.0);
}

TEST(DxfImport, BulgesBecomeArcs) {
  // A 100 x 100 mm square whose top edge is a half circle (bulge 1 = 180°).
  const auto r = import_string(
      file_with([](DxfText& d) {
        d.block("A_M").text("1", "Piece Name: A");
        d.polyline("1", {{0, 0}, {100, 0}, {100, 100}, {0, 100}}, true, {0, 0, 1, 0});
        d.endblk();
      }, [](DxfText& d) { d.text("1", "Units: METRIC").insert("A_M"); }),
      "arc.dxf");
  const double exact = 0.01 + M_PI * 0.05 * 0.05 / 2;
  EXPECT_NEAR(r.blocks[0].area_m2, exact, 0.01 * exact);  // 10° chords lose < 1 %
  EXPECT_GT(r.blocks[0].boundary_vertices, 20);
}

TEST(DxfImport, LwpolylineBoundaryIsRead) {
  const auto r = import_string(
      file_with([](DxfText& d) {
        d.block("L_M").text("1", "Piece Name: L").lwpolyline("1", {{0, 0}, {200, 0}, {200, 50}, {0, 50}}, true);
        d.endblk();
      }, [](DxfText& d) { d.text("1", "Units: METRIC").insert("L_M"); }),
      "lw.dxf");
  EXPECT_EQ(r.blocks[0].boundary_vertices, 4);
  EXPECT_NEAR(r.blocks[0].area_m2, 0.01, 1e-12);
}

TEST(DxfImport, SplitOutlineInAnyOrderAndDirectionIsChained) {
  const auto r = import_string(
      file_with([](DxfText& d) {
        d.block("C_M").text("1", "Piece Name: C");
        d.polyline("1", {{100, 100}, {100, 0}});  // reversed
        d.polyline("1", {{0, 100}, {0, 0}});
        d.polyline("1", {{0, 0}, {50, 0}, {100, 0}});
        d.polyline("1", {{0, 100}, {100, 100}});  // reversed
        d.endblk();
      }, [](DxfText& d) { d.text("1", "Units: METRIC").insert("C_M"); }),
      "chain.dxf");
  EXPECT_TRUE(r.blocks[0].closed);
  EXPECT_EQ(r.blocks[0].boundary_vertices, 5);
  EXPECT_NEAR(r.blocks[0].area_m2, 0.01, 1e-12);
  EXPECT_GT(signed_area(r.style.pieces[0].boundary), 0.0);
}

TEST(DxfImport, TextsBecomeAttributesCaseInsensitively) {
  const auto r = import_string(
      file_with([](DxfText& d) {
        d.block("F_36").text("1", "PIECE NAME: FRONT").text("1", "size: 36").text("1", "Quantity: 1,1");
        d.text("1", "Category: SELF").text("1", "Fabric: DENIM").text("1", "Annotation: CUT 2");
        d.text("1", "Marker Note: keep").text("1", "FREE TEXT").text("2", "# 17");
        d.polyline("1", {{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true).endblk();
        d.block("F_38").text("1", "Piece Name: FRONT").text("1", "Size: 38");
        d.polyline("1", {{0, 0}, {11, 0}, {11, 11}, {0, 11}}, true).endblk();
      }, [](DxfText& d) {
        d.text("1", "Style Name: JEANS").text("1", "Sample Size: 36").text("1", "Units: METRIC");
        d.text("1", "Author: TEST").insert("F_36").insert("F_38");
      }),
      "attr.dxf");
  ASSERT_EQ(r.style.pieces.size(), 2u);
  const auto& a = r.style.pieces[0];
  EXPECT_EQ(a.name, "FRONT");
  EXPECT_EQ(a.size, "36");
  EXPECT_EQ(a.quantity, 2);
  EXPECT_EQ(a.quantity_flipped, 1);
  EXPECT_EQ(a.category, "SELF");
  EXPECT_EQ(a.fabric, "DENIM");
  EXPECT_EQ(a.annotation, "CUT 2");
  ASSERT_EQ(a.annotations.size(), 2u);  // the grade-rule label "# 17" is not an annotation
  EXPECT_EQ(a.annotations[0].first, "marker note");
  EXPECT_EQ(a.annotations[1].second, "FREE TEXT");
  // Size 38 states none of these: they come from the sample-size block.
  const auto& b = r.style.pieces[1];
  EXPECT_EQ(b.category, "SELF");
  EXPECT_EQ(b.quantity, 2);
  EXPECT_EQ(r.style.name, "JEANS");
  EXPECT_EQ(r.style.sample_size, "36");
  EXPECT_EQ(r.style.sizes, (std::vector<std::string>{"36", "38"}));
  EXPECT_EQ(r.summary.pieces, 1);
  EXPECT_EQ(r.summary.blocks, 2);
  EXPECT_EQ(r.style.producer, "TEST");
}

TEST(DxfImport, TurnAndCurvePointsMarkBoundaryVertices) {
  const auto r = import_string(
      file_with([](DxfText& d) {
        d.block("T_M").text("1", "Piece Name: T");
        d.polyline("1", {{0, 0}, {50, 0}, {100, 0}, {100, 100}, {0, 100}}, true);
        d.point("2", 0, 0).point("2", 100, 0).point("3", 50, 0).point("2", 500, 500);  // last one is off the outline
        d.endblk();
      }, [](DxfText& d) { d.text("1", "Units: METRIC").insert("T_M"); }),
      "turn.dxf");
  int turns = 0, curves = 0;
  for (const auto& c : r.style.pieces[0].boundary) {
    turns += c.kind == vgd::pattern::PointKind::turn;
    curves += c.kind == vgd::pattern::PointKind::curve;
  }
  EXPECT_EQ(turns, 2);
  EXPECT_EQ(curves, 1);
}

TEST(DxfImport, NotchAttributesAndDefaultDirection) {
  const auto r = import_string(
      file_with([](DxfText& d) {
        d.block("N_M").text("1", "Piece Name: N");
        d.polyline("1", {{0, 0}, {100, 0}, {100, 100}, {0, 100}}, true);
        d.pair(0, "POINT").pair(8, "4").pair(10, 50.0).pair(20, 0.0).pair(30, -4.0).pair(39, 3.0);
        d.pair(0, "POINT").pair(8, "4").pair(10, 100.0).pair(20, 50.0).pair(50, 135.0);
        d.endblk();
      }, [](DxfText& d) { d.text("1", "Units: METRIC").insert("N_M"); }),
      "notch.dxf");
  const auto& n = r.style.pieces[0].notches;
  ASSERT_EQ(n.size(), 2u);
  EXPECT_NEAR(n[0].length_m, 0.004, 1e-12);
  EXPECT_NEAR(n[0].width_m, 0.003, 1e-12);
  EXPECT_NEAR(n[0].angle_deg, 90.0, 1e-9);  // on the bottom edge, cut inwards (+y)
  EXPECT_NEAR(n[1].angle_deg, 135.0, 1e-9);
}

TEST(DxfImport, HalfPieceUnfoldsAboutItsMirrorLine) {
  // Right half of a 200 x 100 mm rectangle, fold along x = 0, a notch on the right.
  auto text = file_with([](DxfText& d) {
    d.block("H_M").text("1", "Piece Name: H");
    d.polyline("1", {{0, 0}, {100, 0}, {100, 100}, {0, 100}}, true);
    d.line("6", 0, 0, 0, 100);
    d.point("4", 100, 50);
    d.line("8", 20, 20, 40, 40);
    d.endblk();
  }, [](DxfText& d) { d.text("1", "Units: METRIC").insert("H_M"); });
  const auto half = import_string(text, "half.dxf");
  EXPECT_TRUE(half.blocks[0].mirror_line);
  EXPECT_NEAR(half.blocks[0].area_m2, 0.01, 1e-12);

  vgd::dxf::ImportOptions o;
  o.unfold_mirrored = true;
  const auto full = import_string(text, "half.dxf", o);
  const auto& p = full.style.pieces[0];
  EXPECT_NEAR(std::abs(signed_area(p.boundary)), 0.02, 1e-12);
  EXPECT_GT(signed_area(p.boundary), 0.0);
  EXPECT_EQ(p.boundary.size(), 6u);  // the fold's ends stay as vertices of the full outline
  EXPECT_FALSE(p.mirror_line.has_value());
  EXPECT_EQ(p.notches.size(), 2u);
  EXPECT_EQ(p.internal_lines.size(), 2u);
  EXPECT_NEAR(full.blocks[0].area_m2, 0.01, 1e-12) << "the report gives areas as stored, before unfolding";
}

TEST(DxfImport, AstmQualityOutlineIsUsedOnlyWithoutLayer1) {
  const auto r = import_string(
      file_with([](DxfText& d) {
        d.block("Q_M").text("1", "Piece Name: Q");
        d.polyline("84", {{0, 0}, {100, 0}, {100, 100}, {0, 100}}, true);
        d.endblk();
        d.block("R_M").text("1", "Piece Name: R");
        d.polyline("1", {{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true);
        d.polyline("84", {{0, 0}, {100, 0}, {100, 100}, {0, 100}}, true);
        d.endblk();
      }, [](DxfText& d) { d.text("1", "Units: METRIC").insert("Q_M").insert("R_M"); }),
      "astm.dxf");
  EXPECT_EQ(r.style.flavour, "ASTM");
  EXPECT_NEAR(r.blocks[0].area_m2, 0.01, 1e-12);
  EXPECT_NEAR(r.blocks[1].area_m2, 0.0001, 1e-12);
}

TEST(DxfImport, ValentinaStyleFileWithoutTextsUsesBlockNames) {
  DxfText d;
  d.pair(999, "dxfrw 0.6.3");
  d.begin_blocks().block("$MODEL_SPACE").endblk().block("FRONT");
  d.polyline("1", {{0, 0}, {100, 0}, {100, 100}, {0, 100}, {0, 0}}, true).endblk().end_section();
  d.begin_entities().insert("FRONT").end_section().eof();
  const auto r = import_string(d.str(), "val.dxf");
  ASSERT_EQ(r.style.pieces.size(), 1u);
  EXPECT_EQ(r.style.pieces[0].name, "FRONT");
  EXPECT_EQ(r.style.pieces[0].boundary.size(), 4u);  // closed flag + repeated first vertex
  EXPECT_EQ(r.style.producer, "dxfrw 0.6.3");
  EXPECT_EQ(r.style.units, "mm");
}

// Names in the file's code page: an R12 file from a Russian system writes its
// piece names in ANSI_1251 (and says so in $DWGCODEPAGE); one that names no
// code page is ANSI_1252; characters outside it come as \U+XXXX escapes.
// Every name reads as UTF-8, and the import says what it did.
TEST(DxfImport, NamesAreReadInTheFilesCodePage) {
  auto file = [](const std::string& code_page, const std::string& name, const std::string& block) {
    DxfText d;
    if (!code_page.empty()) d.pair(0, "SECTION").pair(2, "HEADER").pair(9, "$DWGCODEPAGE").pair(3, code_page).pair(0, "ENDSEC");
    d.begin_blocks().square_piece(block, name, "M").end_section().begin_entities().insert(block).end_section().eof();
    return d.str();
  };
  auto info = [](const vgd::dxf::ImportResult& r) {
    std::string all;
    for (const auto& d : r.diagnostics.items()) all += d.message + "\n";
    return all;
  };
  // "Спинка" (back) in ANSI_1251 bytes.
  const std::string back_1251 = "\xD1\xEF\xE8\xED\xEA\xE0";
  auto r = import_string(file("ANSI_1251", back_1251, back_1251 + "_M"), "ru.dxf");
  ASSERT_EQ(r.style.pieces.size(), 1u);
  EXPECT_EQ(r.style.pieces[0].name, "Спинка");
  EXPECT_EQ(r.style.pieces[0].block, "Спинка_M");
  EXPECT_NE(info(r).find("texts read in its code page ANSI_1251"), std::string::npos) << info(r);
  // "Devant gauche, épaule" with é in ANSI_1252, the code page unnamed: a warning says so.
  r = import_string(file("", "Devant \xE9paule", "D_M"), "fr.dxf");
  EXPECT_EQ(r.style.pieces[0].name, "Devant épaule");
  EXPECT_NE(info(r).find("names no code page ($DWGCODEPAGE): read as ANSI_1252"), std::string::npos) << info(r);
  // A UTF-8 file is kept as it is; \U+ escapes become their characters.
  r = import_string(file("ANSI_1252", "R\\U+00FCcken \\U+0420", "B_M"), "de.dxf");
  EXPECT_EQ(r.style.pieces[0].name, "Rücken Р");
  EXPECT_EQ(info(r).find("code page"), std::string::npos) << info(r);
  r = import_string(file("", "Ärmel", "A_M"), "utf8.dxf");
  EXPECT_EQ(r.style.pieces[0].name, "Ärmel");
}
