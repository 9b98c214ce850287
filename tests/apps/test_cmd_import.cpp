// vgd draft / import / export-dxf and the program's conventions (exit codes,
// --help, --version, JSON on stdout, messages on stderr), run as a user would.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/dxf/import.hpp"

using vgd::test::run_vgd;
namespace fs = std::filesystem;

namespace {
const fs::path kSkirt = vgd::test::source_dir() / "data/garments/a-line-skirt.dxf";
}

TEST(Cli, VersionAndHelpExitZero) {
  auto r = run_vgd("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("vgd 0."), std::string::npos) << r.out;
  for (const char* cmd : {"draft", "import", "export-dxf", "validate", "edit", "svg", "mesh"}) {
    r = run_vgd(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
  }
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run_vgd("").code, 2);
  EXPECT_EQ(run_vgd("frobnicate").code, 2);
  EXPECT_EQ(run_vgd("import").code, 2);  // FILE is required
  EXPECT_EQ(run_vgd("import x.dxf --no-such-option").code, 2);
}

TEST(CliImport, BadFileExitsOneAndNamesIt) {
  const auto dir = vgd::test::scratch_dir("cli_import_bad");
  vgd::write_file_atomic(dir / "notes.dxf", "this is not a DXF\n");
  const auto r = run_vgd("import notes.dxf -o out.xvc", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("notes.dxf:1"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.xvc")) << "nothing may be written for a bad input";
  EXPECT_EQ(run_vgd("import missing.dxf --report", dir).code, 1);
}

TEST(CliImport, ReportJsonHasTheDocumentedFields) {
  const auto r = run_vgd("import " + kSkirt.string() + " --report --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);  // stdout is JSON only
  for (const char* k : {"producer", "flavour", "style", "units", "sample_size", "pieces", "blocks", "sizes"})
    EXPECT_TRUE(j["summary"].contains(k)) << k;
  EXPECT_EQ(j["summary"]["pieces"], 3);
  EXPECT_EQ(j["summary"]["blocks"], 15);
  EXPECT_EQ(j["summary"]["sample_size"], "38");
  ASSERT_EQ(j["blocks"].size(), 15u);
  for (const char* k : {"block", "piece", "size", "quantity", "category", "boundary_vertices", "closed", "area_m2",
                        "perimeter_m", "grain_angle_deg", "notches", "internal_lines", "drill_holes", "mirror_line",
                        "self_intersecting"})
    EXPECT_TRUE(j["blocks"][0].contains(k)) << k;
  EXPECT_TRUE(j["warnings"].is_array());
}

TEST(CliImport, ImportExportImportKeepsTheGarment) {
  const auto dir = vgd::test::scratch_dir("cli_roundtrip");
  ASSERT_EQ(run_vgd("-q import " + kSkirt.string() + " -o skirt.xvc", dir).code, 0);
  ASSERT_EQ(run_vgd("validate skirt.xvc", dir).code, 0);
  const auto e = run_vgd("export-dxf skirt.xvc -o back.dxf --units in", dir);
  ASSERT_EQ(e.code, 0) << e.err;
  const auto a = vgd::dxf::import_file(kSkirt), b = vgd::dxf::import_file(dir / "back.dxf");
  EXPECT_EQ(b.style.units, "in");
  ASSERT_EQ(a.style.pieces.size(), b.style.pieces.size());
  for (std::size_t i = 0; i < a.style.pieces.size(); ++i) {
    EXPECT_EQ(a.style.pieces[i].block, b.style.pieces[i].block);
    EXPECT_NEAR(a.blocks[i].area_m2, b.blocks[i].area_m2, 1e-12);
    EXPECT_EQ(a.blocks[i].boundary_vertices, b.blocks[i].boundary_vertices);
  }
}

// A bad block is dropped with its message, and the others are written
// (exit 3: something was dropped); --strict writes nothing. The bad blocks:
// one with no boundary, one 293 m wide (garbage, or the wrong units). A
// small piece placed 1.25 km from the origin is a piece, kept; a second
// BLOCK with the same name is kept under a name of its own.
TEST(CliImport, ADroppedBlockLosesOnlyItself) {
  const auto dir = vgd::test::scratch_dir("cli_dropped_block");
  std::string text = vgd::read_file(kSkirt);
  const auto at = text.find("  0\nENDSEC");  // end of BLOCKS
  auto square = [](const std::string& name, double x0, double y0, double w) {
    std::string b = "  0\nBLOCK\n  8\n0\n  2\n" + name + "\n 70\n0\n 10\n0\n 20\n0\n";
    b += "  0\nPOLYLINE\n  8\n1\n 66\n1\n 70\n1\n";
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + w}, {x0, y0 + w}})
      b += "  0\nVERTEX\n  8\n1\n 10\n" + std::to_string(x) + "\n 20\n" + std::to_string(y) + "\n";
    b += "  0\nSEQEND\n  8\n1\n";
    b += "  0\nTEXT\n  8\n1\n 10\n0\n 20\n0\n 40\n1\n  1\nPiece Name: " + name + "\n  0\nENDBLK\n  8\n0\n";
    return b;
  };
  // The skirt's file is in mm: 293 m is 293 000 units; 1.25 km is 1 250 000.
  text.insert(at, "  0\nBLOCK\n  8\n0\n  2\nEMPTY\n 70\n0\n 10\n0\n 20\n0\n  0\nTEXT\n  8\n1\n 10\n0\n 20\n0\n 40\n1\n  1\n"
                  "Piece Name: EMPTY\n  0\nENDBLK\n  8\n0\n" +
                  square("HUGE", 0, 0, 293000) + square("FAR", 1250000, 0, 79) + square("TWICE", 0, 0, 50) +
                  square("TWICE", 100, 0, 60));
  vgd::write_file_atomic(dir / "bad.dxf", text);
  auto r = run_vgd("import bad.dxf -o out.xvc", dir);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("EMPTY"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("block HUGE: the piece is 293.0 m wide and 293.0 m high (limit 20 m)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("is kept as 'TWICE #2'"), std::string::npos) << r.err;
  ASSERT_TRUE(fs::exists(dir / "out.xvc"));
  const auto doc = vgd::read_file(dir / "out.xvc");
  EXPECT_NE(doc.find("block=\"FAR\""), std::string::npos);
  EXPECT_NE(doc.find("block=\"TWICE\""), std::string::npos);
  EXPECT_NE(doc.find("block=\"TWICE #2\""), std::string::npos);
  EXPECT_EQ(doc.find("block=\"HUGE\""), std::string::npos);
  fs::remove(dir / "out.xvc");
  r = run_vgd("import bad.dxf -o out.xvc --strict", dir);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.xvc"));
}

TEST(CliDraft, DraftedFileImportsCleanly) {
  const auto dir = vgd::test::scratch_dir("cli_draft");
  auto r = run_vgd("draft skirt --sizes 36,40 -o s.dxf", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto a = vgd::dxf::import_file(dir / "s.dxf");
  EXPECT_EQ(a.style.sizes, (std::vector<std::string>{"36", "40"}));
  EXPECT_EQ(a.diagnostics.count(vgd::Severity::warning), 0u);
  r = run_vgd("draft skirt --waist 1.5 --hip 0.9 -o t.dxf", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("waist"), std::string::npos) << r.err;
  EXPECT_EQ(run_vgd("draft skirt --sizes 99 -o u.dxf", dir).code, 1);
}

// --join-per-side and --sew-lines say what they did and write what they say:
// CLO's 9 blocks as 5 pieces; Valentina's trousers on their sew lines.
TEST(CliImport, JoinPerSideAndSewLinesSayWhatTheyDid) {
  VGD_REQUIRE_SHARED();
  const auto dir = vgd::test::scratch_dir("cli_join_sew");
  auto r = run_vgd({"import", vgd::test::shared_dxf("clo-pattern.dxf").string(), "--join-per-side", "-o",
                    (dir / "clo.xvc").string()});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("blocks 11_M and 37_M are the left and right halves of one piece"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("blocks 36_M and 39_M have the same outline"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(": 5 pieces, 5 blocks"), std::string::npos) << r.err;
  const auto doc = vgd::read_file(dir / "clo.xvc");
  EXPECT_EQ(doc.find("block=\"37_M\""), std::string::npos);
  r = run_vgd({"import", vgd::test::shared_dxf("clo-pattern.dxf").string(), "-o", (dir / "as-written.xvc").string()});
  EXPECT_EQ(r.err.find("halves"), std::string::npos) << r.err;  // off unless asked, and said
  EXPECT_NE(r.err.find("note: 4 pair(s) of blocks look written once per side (11_M and 37_M, ...): --join-per-side"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(": 9 pieces, 9 blocks"), std::string::npos) << r.err;
  r = run_vgd({"import", vgd::test::shared_dxf("Valentina_Trousers_ASTM_R12.dxf").string(), "--sew-lines", "-o",
               (dir / "trousers.xvc").string()});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("11 block(s) sewn on their sew line (layer 14): a seam allowance of 0.9-6.9 cm cut off"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(vgd::read_file(dir / "trousers.xvc").find("role=\"sew\""), std::string::npos);
}
