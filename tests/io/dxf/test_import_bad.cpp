// Bad input gets a clear error naming the file, the block and the problem;
// repairable defects are repaired and reported; nothing crashes.
#include <gtest/gtest.h>

#include "dxf_text.hpp"
#include "vgd/io/dxf/import.hpp"

using vgd::dxf::import_string;
using vgd::test::DxfText;

namespace {

// Runs the import expecting a vgd::Error; returns its message.
std::string import_error(const std::string& text, const std::string& name = "bad.dxf") {
  try {
    import_string(text, name);
  } catch (const vgd::Error& e) {
    EXPECT_EQ(e.diagnostic().file, name);
    return e.what();
  }
  ADD_FAILURE() << "expected an import error";
  return {};
}

bool has_diag(const vgd::dxf::ImportResult& r, vgd::Severity s, const std::string& entity, const std::string& words) {
  for (const auto& d : r.diagnostics.items())
    if (d.severity == s && d.entity.find(entity) != std::string::npos && d.message.find(words) != std::string::npos)
      return true;
  return false;
}

std::string with_block(const std::function<void(DxfText&)>& body, const std::string& units = "Units: METRIC") {
  DxfText d;
  d.begin_blocks().block("P_M").text("1", "Piece Name: P").text("1", "Size: M");
  body(d);
  d.endblk().end_section().begin_entities();
  if (!units.empty()) d.text("1", units);
  d.insert("P_M").end_section().eof();
  return d.str();
}

}  // namespace

TEST(DxfBadInput, EmptyFileIsAnError) {
  EXPECT_NE(import_error("").find("empty file"), std::string::npos);
  EXPECT_NE(import_error("  \n \r\n").find("empty file"), std::string::npos);
}

TEST(DxfBadInput, BinaryDxfIsRefusedWithAdvice) {
  std::string bin = "AutoCAD Binary DXF\r\n\x1a";
  bin.push_back('\0');
  bin += "\x01\x02";
  const auto msg = import_error(bin);
  EXPECT_NE(msg.find("binary DXF"), std::string::npos) << msg;
  EXPECT_NE(msg.find("ASCII"), std::string::npos) << msg;
}

TEST(DxfBadInput, NotADxfNamesTheLine) {
  const auto msg = import_error("# A markdown file\n\nhello\n");
  EXPECT_NE(msg.find("bad.dxf:1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("group code"), std::string::npos) << msg;
}

TEST(DxfBadInput, TruncatedFileNamesWhereItEnds) {
  const std::string full = vgd::test::one_square_file();
  const auto cut = full.substr(0, full.find("ENDBLK"));
  const auto msg = import_error(cut);
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  EXPECT_NE(msg.find("SQ_M"), std::string::npos) << msg;
}

TEST(DxfBadInput, TruncatedInsideAPairIsCaught) {
  const std::string full = vgd::test::one_square_file();
  const auto cut = full.substr(0, full.find("\n", full.find(" 10\n") + 1) + 1);  // code without value
  EXPECT_NE(import_error(cut).find("truncated"), std::string::npos);
}

TEST(DxfBadInput, NonNumericCoordinateNamesLineAndBlock) {
  std::string t = vgd::test::one_square_file();
  const auto pos = t.find("100\n");
  t.replace(pos, 3, "1O0");  // letter O instead of zero
  const auto msg = import_error(t);
  EXPECT_NE(msg.find("expects a number"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1O0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("block SQ_M"), std::string::npos) << msg;
}

TEST(DxfBadInput, NoBlocksIsAnError) {
  DxfText d;
  d.begin_entities().polyline("1", {{0, 0}, {1, 0}, {1, 1}}).end_section().eof();
  EXPECT_NE(import_error(d.str()).find("no pattern pieces"), std::string::npos);
}

TEST(DxfBadInput, BlockWithoutBoundaryIsDroppedAndNamed) {
  DxfText d;
  d.begin_blocks().square_piece("GOOD_M", "GOOD", "M").block("EMPTY_M").text("1", "Piece Name: EMPTY");
  d.line("7", 0, 0, 0, 1).endblk().end_section();
  d.begin_entities().text("1", "Units: METRIC").insert("GOOD_M").insert("EMPTY_M").end_section().eof();
  const auto r = import_string(d.str(), "x.dxf");
  EXPECT_EQ(r.style.pieces.size(), 1u);
  EXPECT_TRUE(has_diag(r, vgd::Severity::error, "EMPTY_M", "no boundary"));
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_FALSE(r.blocks[1].imported);
}

TEST(DxfBadInput, OnlyBadBlocksMakesTheFileAnError) {
  const auto msg = import_error(with_block([](DxfText& d) { d.line("7", 0, 0, 0, 1); }));
  EXPECT_NE(msg.find("P_M"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no boundary"), std::string::npos) << msg;
}

TEST(DxfBadInput, OpenBoundaryIsReportedNotClosedSilently) {
  const auto r = import_string(with_block([](DxfText& d) {
    d.polyline("1", {{0, 0}, {100, 0}, {100, 100}, {0, 100}, {0, 20}});  // 20 mm gap
  }), "open.dxf");
  ASSERT_EQ(r.style.pieces.size(), 1u);
  EXPECT_FALSE(r.style.pieces[0].closed);
  EXPECT_FALSE(r.blocks[0].closed);
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "P_M", "open boundary"));
}

TEST(DxfBadInput, TinyClosingGapIsRepairedAndReported) {
  const auto r = import_string(with_block([](DxfText& d) {
    d.polyline("1", {{0, 0}, {100, 0}, {100, 100}, {0, 100}, {0, 0.3}});  // 0.3 mm gap
  }), "gap.dxf");
  EXPECT_TRUE(r.style.pieces[0].closed);
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "P_M", "closed a gap of 0.300 mm"));
}

TEST(DxfBadInput, DuplicatePointsAndZeroLengthSegmentsAreRemoved) {
  const auto r = import_string(with_block([](DxfText& d) {
    d.polyline("1", {{0, 0}, {100, 0}, {100, 0}, {100, 0}, {100, 100}});
    d.polyline("1", {{100, 100}, {100, 100}});  // a zero-length part
    d.polyline("1", {{100, 100}, {0, 100}, {0, 0}});
  }), "dup.dxf");
  ASSERT_EQ(r.style.pieces.size(), 1u);
  EXPECT_EQ(r.style.pieces[0].boundary.size(), 4u);
  EXPECT_TRUE(r.style.pieces[0].closed);
  EXPECT_TRUE(has_diag(r, vgd::Severity::info, "P_M", "duplicate boundary vertices removed"));
}

TEST(DxfBadInput, DuplicatePartIsDroppedAndReported) {
  const auto r = import_string(with_block([](DxfText& d) {
    d.polyline("1", {{0, 0}, {100, 0}, {100, 100}});
    d.polyline("1", {{0, 0}, {100, 0}, {100, 100}});
    d.polyline("1", {{100, 100}, {0, 100}, {0, 0}});
  }), "dup.dxf");
  EXPECT_TRUE(r.style.pieces[0].closed);
  EXPECT_EQ(r.style.pieces[0].boundary.size(), 4u);
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "P_M", "duplicate boundary part"));
}

TEST(DxfBadInput, SelfIntersectingBoundaryIsFlagged) {
  // A lopsided bow tie: a large crossing that cannot be repaired by cutting a small loop.
  const auto r = import_string(with_block([](DxfText& d) {
    d.polyline("1", {{0, 0}, {100, 100}, {100, 0}, {0, 50}}, true);
  }), "bow.dxf");
  ASSERT_EQ(r.style.pieces.size(), 1u);
  EXPECT_TRUE(r.blocks[0].self_intersecting);
  EXPECT_TRUE(r.style.pieces[0].self_intersecting);
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "P_M", "not repairable"));
}

TEST(DxfBadInput, SmallSelfIntersectionLoopIsRepaired) {
  // A square whose bottom edge makes a 1 mm loop: typical of a graded size.
  const auto r = import_string(with_block([](DxfText& d) {
    d.polyline("1", {{0, 0}, {50, 0}, {51, 1}, {51, -1}, {50.5, -1}, {50.5, 0.5}, {100, 0}, {100, 100}, {0, 100}},
               true);
  }), "loop.dxf");
  EXPECT_TRUE(r.blocks[0].self_intersecting);
  EXPECT_FALSE(r.style.pieces[0].self_intersecting);
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "P_M", "repaired"));
}

TEST(DxfBadInput, NonsenseUnitsWarnAndFallBack) {
  const auto r = import_string(with_block([](DxfText& d) {
    d.polyline("1", {{0, 0}, {100, 0}, {100, 100}, {0, 100}}, true);
  }, "Units: FURLONGS"), "units.dxf");
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "", "unknown units 'FURLONGS'"));
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "", "states no units"));
  EXPECT_EQ(r.style.units, "mm");
}

TEST(DxfBadInput, HugeCoordinatesDropTheBlock) {
  const auto msg = import_error(with_block([](DxfText& d) {
    d.polyline("1", {{0, 0}, {1e12, 0}, {1e12, 1e12}}, true);
  }));
  EXPECT_NE(msg.find("out of range"), std::string::npos) << msg;
  EXPECT_NE(msg.find("P_M"), std::string::npos) << msg;
}

TEST(DxfBadInput, OverflowingNumberIsRejected) {
  const auto msg = import_error(with_block([](DxfText& d) {
    d.pair(0, "POLYLINE").pair(8, "1").pair(66, "1").pair(0, "VERTEX").pair(8, "1").pair(10, "1e999").pair(20, "0");
    d.pair(0, "SEQEND");
  }));
  EXPECT_NE(msg.find("expects a number"), std::string::npos) << msg;
}

TEST(DxfBadInput, UnbalancedBlockIsAnError) {
  DxfText d;
  d.begin_blocks().block("A").polyline("1", {{0, 0}, {1, 0}, {1, 1}}, true).block("B").endblk().end_section().eof();
  const auto msg = import_error(d.str());
  EXPECT_NE(msg.find("no ENDBLK"), std::string::npos) << msg;
}

TEST(DxfBadInput, ContentAfterEofIsAnError) {
  EXPECT_NE(import_error(vgd::test::one_square_file() + "  0\nLINE\n").find("after the EOF"), std::string::npos);
}

TEST(DxfBadInput, InsertCyclesAndFanOutAreCut) {
  // A inserts itself; B inserts C ten times, C inserts D ten times, ... : 10^8 copies if expanded.
  DxfText d;
  d.begin_blocks().block("A_M").text("1", "Piece Name: A").polyline("1", {{0, 0}, {10, 0}, {10, 10}}, true);
  d.insert("A_M").endblk();
  const char* chain[] = {"B", "C", "D", "E", "F", "G", "H", "I", "J"};
  for (int i = 0; i < 9; ++i) {
    d.block(chain[i]).polyline("1", {{0, 0}, {10, 0}, {10, 10}}, true);
    if (i + 1 < 9)
      for (int k = 0; k < 10; ++k) d.insert(chain[i + 1], k, 0);
    d.endblk();
  }
  d.end_section().begin_entities().text("1", "Units: METRIC").insert("A_M").insert("B").end_section().eof();
  const auto r = import_string(d.str(), "cycle.dxf");
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "A_M", "makes a cycle"));
  EXPECT_TRUE(has_diag(r, vgd::Severity::warning, "", "copies ignored"));
  EXPECT_LT(r.diagnostics.items().size(), 50u) << "one warning per problem, not one per copy";
}

TEST(DxfBadInput, BlockDiagnosticsGiveTheEntityLine) {
  // The warning names the line where the open POLYLINE starts.
  const std::string text = with_block([](DxfText& d) { d.polyline("1", {{0, 0}, {100, 0}, {100, 100}, {0, 100}, {0, 20}}); });
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.find("POLYLINE"); ++i) line += text[i] == '\n';
  const auto r = import_string(text, "open.dxf");
  bool found = false;
  for (const auto& d : r.diagnostics.items())
    if (d.message.find("open boundary") != std::string::npos) {
      EXPECT_EQ(d.line, static_cast<int>(line));
      found = true;
    }
  EXPECT_TRUE(found);
}
