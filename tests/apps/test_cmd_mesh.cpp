// `vgd mesh` end to end: document parameters, overrides, JSON, Triangle files, errors.
// A separate executable (it needs the vgd program and the xvc stage).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "support/test_paths.hpp"
#include "mesh/synthetic.hpp"
#include "support/run_vgd.hpp"
#include "vgd/mesh/triangle_io.hpp"
#include "vgd/xvc/document.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

using namespace vgd;

namespace {

// Runs `vgd -q ARGS`.
test::CliResult vgd_run(const std::string& args) { return test::run_vgd("-q " + args); }

// A two-piece style, sample size M, saved with mesh.spacing = 2 cm.
std::filesystem::path make_document(const std::filesystem::path& dir) {
  pattern::Style s;
  s.name = "TEST";
  s.sample_size = "M";
  s.sizes = {"S", "M"};
  s.pieces.push_back(test::piece("FRONT_M", test::l_shape()));
  s.pieces.push_back(test::piece("BACK_M", test::square(0.3)));
  s.pieces.back().name = "BACK";
  s.pieces.back().cutouts.push_back({test::circle({0.15, 0.15}, 0.05, 24), true});
  s.pieces.push_back(test::piece("FRONT_S", test::l_shape()));
  s.pieces.back().size = "S";
  s.pieces[0].name = s.pieces[2].name = "FRONT";
  xvc::Document doc = xvc::from_style(s);
  xvc::set_parameter(doc, "mesh.spacing", 0.02);
  const auto path = dir / "style.xvc";
  xvc::save_file(doc, path);
  return path;
}

}  // namespace

TEST(CmdMesh, UsesDocumentParametersAndPrintsJson) {
  const auto dir = test::scratch_dir("cmd_mesh_json");
  const auto doc = make_document(dir);
  const auto r = vgd_run("mesh " + doc.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("size"), "M");
  EXPECT_DOUBLE_EQ(j.at("options").at("spacing_m").get<double>(), 0.02);
  ASSERT_EQ(j.at("pieces").size(), 2u);
  for (const auto& p : j.at("pieces")) {
    EXPECT_TRUE(p.at("valid").get<bool>());
    EXPECT_GE(p.at("min_angle_deg").get<double>(), 25.0);
  }
  EXPECT_EQ(j.at("pieces")[1].at("cutouts"), 1);
}

TEST(CmdMesh, OptionsOverrideTheDocument) {
  const auto dir = test::scratch_dir("cmd_mesh_override");
  const auto doc = make_document(dir);
  const auto r = vgd_run("mesh " + doc.string() + " --json --spacing 0.05 --min-angle 30 --size S --piece FRONT");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(j.at("options").at("spacing_m").get<double>(), 0.05);
  ASSERT_EQ(j.at("pieces").size(), 1u);
  EXPECT_EQ(j.at("pieces")[0].at("block"), "FRONT_S");
  EXPECT_GE(j.at("pieces")[0].at("min_angle_deg").get<double>(), 30.0);
}

TEST(CmdMesh, WritesTriangleFilesAndATable) {
  const auto dir = test::scratch_dir("cmd_mesh_files");
  const auto doc = make_document(dir);
  const auto r = vgd_run("mesh " + doc.string() + " --triangle-files " + (dir / "tri").string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("FRONT_M"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 pieces of size M"), std::string::npos) << r.out;
  const mesh::TriangleData d = mesh::read_triangle_files(dir / "tri" / "BACK_M.1");
  EXPECT_GT(d.triangles.size(), 100u);
  EXPECT_EQ(d.holes.size(), 1u);
}

TEST(CmdMesh, UnknownPieceOrSizeFails) {
  const auto dir = test::scratch_dir("cmd_mesh_errors");
  const auto doc = make_document(dir);
  EXPECT_EQ(vgd_run("mesh " + doc.string() + " --piece NOPE").code, 1);
  EXPECT_EQ(vgd_run("mesh " + doc.string() + " --size XXL").code, 1);
  EXPECT_EQ(vgd_run("mesh " + doc.string() + " --min-angle 50").code, 2);  // usage
}
