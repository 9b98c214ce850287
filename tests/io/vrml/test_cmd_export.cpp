// `vgd export` end to end: a trajectory to every format, the flag alone, a
// drape folder without a trajectory, the web catalogue, and usage errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "tube_skirt.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/io/vrml/gltf.hpp"
#include "vrml_tokens.hpp"

using namespace vgd;
namespace fs = std::filesystem;

namespace {

test::CliResult run(const std::vector<std::string>& args) { return test::run_vgd(args); }

// The tube skirt as a .trj (its merges from frame 0 on) and its body as an OBJ.
fs::path write_skirt(const fs::path& dir) {
  const auto g = test::tube_skirt();
  io::trj::Trajectory t;
  t.topology.num_particles = g.cloth.num_particles();
  t.topology.triangles = g.cloth.triangles;
  t.topology.triangle_piece = g.cloth.triangle_piece;
  t.topology.pieces = g.cloth.pieces;
  t.topology.uv = g.cloth.uv;
  for (int i = 0; i < g.cloth.num_particles(); ++i)
    if (g.cloth.representative[i] != i) t.topology.merges.push_back({0, i, g.cloth.representative[i]});
  t.times = g.frames.times;
  t.frames = g.frames.positions;
  io::trj::write_trj(dir / "skirt.trj", t);
  std::string obj = "# the tube skirt's body\n";
  for (const auto& v : g.body->vertices)
    obj += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  for (const auto& f : g.body->triangles)
    obj += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " + std::to_string(f[2] + 1) + "\n";
  write_file_atomic(dir / "avatar.obj", obj);
  return dir / "skirt.trj";
}

}  // namespace

TEST(CmdExport, HelpNamesEveryFormat) {
  const auto r = run({"export", "--help"});
  EXPECT_EQ(r.code, 0);
  for (const char* w : {"--vrml", "--gltf", "--obj", "--web", "--live-flag", "--decimate", "--precision", "--x-ite"})
    EXPECT_NE(r.out.find(w), std::string::npos) << w;
}

TEST(CmdExport, TheSeedsFlagAloneIsAFewKilobytes) {
  const auto dir = test::scratch_dir("cmd_export_flag");
  const auto r = run({"export", "--live-flag", "-o", (dir / "flag.wrl").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string s = read_file(dir / "flag.wrl");
  EXPECT_EQ(s.rfind("#VRML V2.0 utf8", 0), 0u);
  EXPECT_LT(s.size(), 12000u);
  EXPECT_NE(s.find("PROTO SimulationScript"), std::string::npos);
}

TEST(CmdExport, ATrajectoryGoesToEveryFlavourGltfAndObj) {
  const auto dir = test::scratch_dir("cmd_export_trj");
  const auto trj = write_skirt(dir);
  const auto avatar = (dir / "avatar.obj").string();
  auto r = run({"export", trj.string(), "--vrml", "static", "-o", (dir / "s.wrl").string(), "--avatar",
                          avatar, "--gltf", (dir / "s.glb").string(), "--obj", (dir / "s.obj").string(), "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["written"].size(), 4u);  // .wrl, .glb, .obj, .mtl
  // The static file welds the seams the trajectory merged: 108 vertices, and shows the body.
  const auto t = test::vrml_tokens(read_file(dir / "s.wrl"));
  EXPECT_EQ(test::numbers_after(t, test::find_seq(t, {"DEF", "GarmentCoord", "Coordinate", "{", "point"})).size(),
            3u * 108);
  EXPECT_EQ(test::count_token(t, "Shape"), 3);
  EXPECT_EQ(read_file(dir / "s.glb").substr(0, 4), "glTF");
  EXPECT_NE(read_file(dir / "s.obj").find("mtllib s.mtl"), std::string::npos);
  EXPECT_TRUE(fs::is_regular_file(dir / "s.mtl"));

  // Animated: every frame, or every second one with fewer decimals: a smaller file.
  r = run({"export", trj.string(), "--vrml", "animated", "-o", (dir / "a.wrl").string(), "--precision", "4"});
  ASSERT_EQ(r.code, 0) << r.err;
  r = run({"export", trj.string(), "--vrml", "animated", "-o", (dir / "a2.wrl").string(), "--decimate", "2",
                     "--precision", "2"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LT(fs::file_size(dir / "a2.wrl"), 0.7 * fs::file_size(dir / "a.wrl"));  // 6 of 11 frames, 1 cm

  // Live: the PROTOs, the waist pinned, the body's colliders.
  r = run({"export", trj.string(), "--vrml", "live", "-o", (dir / "l.wrl").string(), "--avatar", avatar});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string live = read_file(dir / "l.wrl");
  EXPECT_NE(live.find("DEF Cloth Garment"), std::string::npos);
  EXPECT_NE(live.find("DEF Collider1 ObjectCollider"), std::string::npos);
  EXPECT_NE(live.find("maxStrain 0.03"), std::string::npos);
}

TEST(CmdExport, ADrapeFolderWithoutATrajectoryGivesTheFinalDrape) {
  const auto dir = test::scratch_dir("cmd_export_folder");
  const auto g = test::tube_skirt();
  // What vgd drape writes: garment.obj (one group per piece, seam copies at one place) and avatar.obj.
  write_file_atomic(dir / "drape" / "garment.obj", io::vrml::obj_text([&] {
                      auto u = g;
                      u.cloth.representative.clear();
                      u.body.reset();
                      return u;
                    }(), ""));
  write_skirt(dir / "drape");
  const auto r = run({"export", (dir / "drape").string(), "-o", (dir / "d.wrl").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto t = test::vrml_tokens(read_file(dir / "d.wrl"));
  // The seams' copies are welded again (108 vertices), the body comes from the folder's avatar.obj.
  EXPECT_EQ(test::numbers_after(t, test::find_seq(t, {"DEF", "GarmentCoord", "Coordinate", "{", "point"})).size(),
            3u * 108);
  EXPECT_EQ(test::count_token(t, "Shape"), 3);
  EXPECT_NE(test::find_seq(t, {"DEF", "Piece_FRONT", "Shape"}), std::string::npos);
}

TEST(CmdExport, TheWebCatalogueHasAPagePerGarmentAndXIte) {
  const fs::path x_ite = VGD_X_ITE_TEST_DIR;
  if (!fs::is_regular_file(x_ite / "x_ite.min.js"))
    GTEST_SKIP() << "SKIPPED: X_ITE not installed at " << x_ite << " (run .ci/install-deps)";
  const auto dir = test::scratch_dir("cmd_export_web");
  const auto trj = write_skirt(dir);
  fs::copy_file(trj, dir / "second.trj");
  const auto r = run({"export", trj.string(), (dir / "second.trj").string(), "--web",
                                (dir / "site").string(), "--live-flag", "--avatar", (dir / "avatar.obj").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"index.html", "skirt.html", "skirt.wrl", "skirt.glb", "skirt.obj", "second.html", "second.wrl",
                        "flag.html", "flag.wrl", "x_ite/x_ite.min.js"})
    EXPECT_TRUE(fs::is_regular_file(dir / "site" / f)) << f;
  const std::string index = read_file(dir / "site" / "index.html");
  for (const char* link : {"href=\"skirt.html\"", "href=\"second.html\"", "href=\"flag.html\""})
    EXPECT_NE(index.find(link), std::string::npos) << link;
  EXPECT_NE(read_file(dir / "site" / "skirt.html").find("<script src=\"x_ite/x_ite.min.js\"></script>"),
            std::string::npos);
}

TEST(CmdExport, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run({"export", "--live-flag"}).code, 2);                    // nothing to write
  EXPECT_EQ(run({"export", "-o", "x.wrl"}).code, 2);                    // no input
  EXPECT_EQ(run({"export", "a.trj", "b.trj", "-o", "x.wrl"}).code, 2);  // several inputs, one file
  EXPECT_EQ(run({"export", "--live-flag", "-o", "x.wrl", "--vrml", "fancy"}).code, 2);
  const auto r = run({"export", "missing.trj", "-o", "x.wrl"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.trj"), std::string::npos) << r.err;
}
