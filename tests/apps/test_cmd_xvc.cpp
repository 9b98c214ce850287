// The xvc subcommands of the vgd program (apps/vgd/cmd_validate.cpp, cmd_edit.cpp,
// cmd_svg.cpp), run as a user would.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "support/run_vgd.hpp"
#include "xvc/fixtures.hpp"
#include "vgd/core/file.hpp"
#include "vgd/xvc/arrangement.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;
namespace fs = std::filesystem;

namespace {
// Runs `vgd ARGS` in `dir`.
vgd::test::CliResult vgd_run(const fs::path& dir, const std::string& args) { return vgd::test::run_vgd(args, dir); }

fs::path with_document(const std::string& test) {
  const auto dir = vgd::test::scratch_dir("xvc_cli_" + test);
  save_file(full_document(), dir / "g.xvc");
  return dir;
}
}  // namespace

TEST(CliValidate, ValidDocumentExitsZero) {
  const auto dir = with_document("validate_ok");
  const auto r = vgd_run(dir, "validate g.xvc");
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("valid"), std::string::npos) << r.err;
}

TEST(CliValidate, InvalidDocumentExitsThreeWithOneLinePerProblem) {
  const auto dir = with_document("validate_bad");
  std::string xml = slurp(dir / "g.xvc");
  xml.replace(xml.find("from=\"seq2\""), 11, "from=\"seq999\"");
  xml.replace(xml.find("quantity=\"2\""), 12, "quantity=\"-2\"");
  vgd::write_file_atomic(dir / "bad.xvc", xml);
  const auto r = vgd_run(dir, "validate bad.xvc");
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  // file:line: entity: message
  EXPECT_NE(r.out.find("bad.xvc:8: pattern1: quantity \"-2\" is negative"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(": hem1: from names seq999"), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r.out;
}

TEST(CliValidate, JsonOutputListsDiagnostics) {
  const auto dir = with_document("validate_json");
  std::string xml = slurp(dir / "g.xvc");
  xml.replace(xml.find("quantity=\"2\""), 12, "quantity=\"x\"");
  vgd::write_file_atomic(dir / "bad.xvc", xml);
  const auto r = vgd_run(dir, "validate bad.xvc --json");
  EXPECT_EQ(r.code, 3);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["valid"], false);
  EXPECT_EQ(j["errors"], 1);
  EXPECT_EQ(j["diagnostics"][0]["entity"], "pattern1");
  EXPECT_EQ(j["diagnostics"][0]["line"], 8);
}

TEST(CliValidate, MalformedXmlIsInvalidNotACrash) {
  const auto dir = vgd::test::scratch_dir("xvc_cli_malformed");
  vgd::write_file_atomic(dir / "m.xvc", "<GARMENT id=\"g\" version=\"1.0\">\n<PATTERNS>\n");
  const auto r = vgd_run(dir, "validate m.xvc");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.out.find("m.xvc:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("malformed XML"), std::string::npos) << r.out;
}

TEST(CliValidate, MissingFileExitsOne) {
  const auto dir = vgd::test::scratch_dir("xvc_cli_missing");
  EXPECT_EQ(vgd_run(dir, "validate nope.xvc").code, 1);
}

TEST(CliEdit, AppliesEditsInCommandLineOrder) {
  const auto dir = with_document("edit_order");
  const auto r = vgd_run(dir, "edit g.xvc -o out.xvc --copy-pattern pattern1 --set-parameter mesh.spacing=5mm "
                              "--mirror-pattern pattern1:vertical --delete-pattern pattern2 --copy-pattern pattern3 "
                              "--set-parameter mesh.max_area=20cm2");
  ASSERT_EQ(r.code, 0) << r.err;
  const Document out = load_file(dir / "out.xvc");
  EXPECT_EQ(out.find("pattern2"), nullptr);
  EXPECT_EQ(out.patterns().size(), 6u);  // 5 + 2 copies - 1
  EXPECT_EQ(get_parameter(out, "mesh.spacing"), 0.005);
  EXPECT_NEAR(*get_parameter(out, "mesh.max_area"), 0.002, 1e-15);
  // The same edits through the library, in the same order, give the same bytes.
  Document doc = load_file(dir / "g.xvc");
  CopyPattern c1("pattern1");
  execute(doc, c1);
  SetParameter p1("mesh.spacing", 0.005);
  execute(doc, p1);
  MirrorPattern m("pattern1", MirrorAxis::vertical);
  execute(doc, m);
  DeletePattern d("pattern2");
  execute(doc, d);
  CopyPattern c2("pattern3");
  execute(doc, c2);
  SetParameter p2("mesh.max_area", 20 * 0.01 * 0.01);
  execute(doc, p2);
  EXPECT_EQ(save_string(out), save_string(doc));
  EXPECT_EQ(slurp(dir / "g.xvc"), save_string(full_document())) << "the input is untouched";
}

TEST(CliEdit, NodeEditsWork) {
  const auto dir = with_document("edit_nodes");
  const auto r = vgd_run(dir, "edit g.xvc -o out.xvc --copy-node seam1 --delete-node material1");
  ASSERT_EQ(r.code, 0) << r.err;
  const Document out = load_file(dir / "out.xvc");
  EXPECT_EQ(out.container("SEAMS")->children.size(), 2u);
  EXPECT_EQ(out.find("material1"), nullptr);
}

TEST(CliEdit, RefusedEditWritesNothing) {
  const auto dir = with_document("edit_refused");
  const auto r = vgd_run(dir, "edit g.xvc -o out.xvc --delete-pattern pattern1 --mirror-pattern material1");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("material1 is a MATERIAL, not a PATTERN"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.xvc"));
  const auto unit = vgd_run(dir, "edit g.xvc -o out.xvc --set-parameter mesh.spacing=3deg");
  EXPECT_EQ(unit.code, 1);
  EXPECT_NE(unit.err.find("mesh.spacing is in m, not deg"), std::string::npos) << unit.err;
}

// --pin PATTERN=X,Y[UNIT]: a pin at the point, in metres or the unit given;
// a point off the piece or no point at all is refused and nothing written.
TEST(CliEdit, PinsAPieceAtAPointInTheUnitGiven) {
  const auto dir = with_document("edit_pin");
  const auto piece = to_piece(full_document(), "pattern1");
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : piece.boundary) c += p.p;
  c /= static_cast<double>(piece.boundary.size());
  const std::string cm = std::to_string(100 * c.x()) + "," + std::to_string(100 * c.y()) + "cm";
  const auto r = vgd_run(dir, "edit g.xvc -o out.xvc --pin pattern1=" + cm);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto pins = pins_of(*load_file(dir / "out.xvc").find("pattern1"));
  ASSERT_EQ(pins.size(), 1u);
  EXPECT_NEAR(pins[0].x, c.x(), 1e-6);
  EXPECT_NEAR(pins[0].y, c.y(), 1e-6);
  const auto off = vgd_run(dir, "edit g.xvc -o off.xvc --pin pattern1=" + std::to_string(c.x() + 5) + ",0");
  EXPECT_EQ(off.code, 1);
  EXPECT_NE(off.err.find("outside the piece pattern1"), std::string::npos) << off.err;
  EXPECT_FALSE(fs::exists(dir / "off.xvc"));
  const auto bad = vgd_run(dir, "edit g.xvc -o bad.xvc --pin pattern1=here");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("PATTERN=X,Y[UNIT]"), std::string::npos) << bad.err;
  const auto unit = vgd_run(dir, "edit g.xvc -o bad.xvc --pin pattern1=0,0deg");
  EXPECT_EQ(unit.code, 1);
  EXPECT_NE(unit.err.find("is not a length"), std::string::npos) << unit.err;
}

TEST(CliEdit, OutputIsRequiredAndMayBeTheInput) {
  const auto dir = with_document("edit_output");
  EXPECT_EQ(vgd_run(dir, "edit g.xvc --delete-pattern pattern1").code, 2);
  EXPECT_EQ(slurp(dir / "g.xvc"), save_string(full_document()));
  EXPECT_EQ(vgd_run(dir, "edit g.xvc -o g.xvc --delete-pattern pattern1").code, 0);
  EXPECT_EQ(load_file(dir / "g.xvc").find("pattern1"), nullptr);
}

TEST(CliSvg, WritesADrawing) {
  const auto dir = with_document("svg");
  const auto r = vgd_run(dir, "svg g.xvc -o g.svg");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string svg = slurp(dir / "g.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  std::size_t outlines = 0;
  for (auto p = svg.find("class=\"outline\""); p != std::string::npos; p = svg.find("class=\"outline\"", p + 1)) ++outlines;
  EXPECT_EQ(outlines, 5u);
}

TEST(Cli, EachCommandHasHelp) {
  const auto dir = vgd::test::scratch_dir("xvc_cli_help");
  for (const char* cmd : {"validate", "edit", "svg"}) {
    const auto r = vgd_run(dir, std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd << ": " << r.out;
  }
}
