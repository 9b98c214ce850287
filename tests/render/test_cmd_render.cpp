// `vgd render` end to end: a drape folder and a garment OBJ with --avatar give
// one PNG per view at the asked size; bad views, sizes, colours and inputs
// are refused with the usual exit codes; a trajectory's frame is drawn.
#include <gtest/gtest.h>

#include "render/synthetic_scene.hpp"
#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/render/image.hpp"

using namespace vgd;
namespace fs = std::filesystem;

namespace {

// OBJ text of meshes, one `g` group each (as `vgd drape` writes garment.obj).
std::string obj_text(const std::vector<render::Mesh>& meshes) {
  std::string s, faces;
  int base = 1;
  for (const auto& m : meshes) {
    for (const auto& p : m.positions)
      s += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
    faces += "g " + m.name + "\n";
    for (const auto& t : m.triangles)
      faces += "f " + std::to_string(t[0] + base) + " " + std::to_string(t[1] + base) + " " +
               std::to_string(t[2] + base) + "\n";
    base += static_cast<int>(m.positions.size());
  }
  return s + faces;
}

// A drape folder: garment.obj (two pieces) and avatar.obj.
fs::path drape_folder(const std::string& name) {
  const auto dir = test::scratch_dir(name);
  const auto scene = test::dressed_cylinder();
  render::Mesh front = test::tube(0.2f, 0.6f, 1.0f), back = test::tube(0.21f, 0.6f, 1.0f);
  front.name = "FRONT", back.name = "BACK";
  write_file_atomic(dir / "garment.obj", obj_text({front, back}));
  write_file_atomic(dir / "avatar.obj", obj_text({scene.meshes[0]}));
  return dir;
}

}  // namespace

TEST(CmdRender, ADrapeFolderGivesOnePngPerView) {
  const auto dir = drape_folder("cmd_render_folder");
  const auto out = dir / "previews";
  const auto r = test::run_vgd({"-q", "render", dir.string(), "--views", "front,left,three-quarter", "--size",
                                "64x48", "-o", out.string(), "--piece-colours"});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* v : {"front", "left", "three-quarter"}) {
    const auto im = render::read_png(out / (std::string(v) + ".png"));
    EXPECT_EQ(im.width, 64) << v;
    EXPECT_EQ(im.height, 48) << v;
    EXPECT_NE(r.out.find(std::string(v) + ".png"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(fs::exists(out / "back.png"));
}

TEST(CmdRender, AGarmentObjWithAnAvatarAndAColour) {
  const auto dir = drape_folder("cmd_render_obj");
  const auto r = test::run_vgd({"-q", "render", (dir / "garment.obj").string(), "--avatar",
                                (dir / "avatar.obj").string(), "--views", "front", "--size", "48", "--colour",
                                "#20c020", "-o", (dir / "out").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto im = render::read_png(dir / "out" / "front.png");
  const auto* p = im.pixel(24, 25);  // the garment, in the middle
  EXPECT_GT(p[1], p[0] + 40) << "green expected";
}

// --avatar goes through the importer as vgd drape's does: its decisions are
// printed, --unit/--up/--facing override them, and a unit that makes no
// human of the body is refused with the file named.
TEST(CmdRender, AnAvatarsImportIsSaidAndCanBeOverridden) {
  const auto dir = drape_folder("cmd_render_avatar_notes");
  const auto avatar = (dir / "avatar.obj").string();
  const auto r = test::run_vgd({"render", (dir / "garment.obj").string(), "--avatar", avatar, "--unit", "m", "--up",
                                "y", "--views", "front", "--size", "48", "-o", (dir / "out").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("avatar.obj: unit m (given)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("avatar.obj: up y (given)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("avatar.obj: facing +z ("), std::string::npos) << r.err;
  const auto bad = test::run_vgd({"render", (dir / "garment.obj").string(), "--avatar", avatar, "--unit", "mm",
                                  "--views", "front", "--size", "48", "-o", (dir / "out2").string()});
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("avatar.obj"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("not a human body"), std::string::npos) << bad.err;
}

TEST(CmdRender, BadViewsSizesColoursAndInputsAreRefused) {
  const auto dir = drape_folder("cmd_render_bad");
  const auto out = (dir / "o").string();
  EXPECT_EQ(test::run_vgd({"render", dir.string(), "--views", "top", "-o", out}).code, 2);
  EXPECT_EQ(test::run_vgd({"render", dir.string(), "--size", "10x10", "-o", out}).code, 2);
  EXPECT_EQ(test::run_vgd({"render", dir.string(), "--colour", "ultraviolet", "-o", out}).code, 2);
  const auto missing = test::run_vgd({"render", (dir / "nothing").string(), "-o", out});
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.err.find("nothing"), std::string::npos) << missing.err;
  const auto not_drape = test::run_vgd({"render", (dir / "o").parent_path().parent_path().string(), "-o", out});
  EXPECT_EQ(not_drape.code, 1) << "a folder without garment.obj";
  EXPECT_EQ(test::run_vgd(std::vector<std::string>{"render", "--help"}).code, 0);
}

TEST(CmdRender, ATrajectoryFrameIsDrawnWithItsPieces) {
  // Two frames of a two-piece tube: the second one 0.3 m lower.
  const auto dir = drape_folder("cmd_render_trj");
  const render::Mesh tube = test::tube(0.2f, 0.6f, 1.0f);
  io::trj::Topology topo;
  topo.num_particles = static_cast<int>(tube.positions.size());
  topo.triangles = tube.triangles;
  topo.pieces = {"FRONT", "BACK"};
  for (std::size_t t = 0; t < tube.triangles.size(); ++t) topo.triangle_piece.push_back(t % 2 == 0 ? 0 : 1);
  std::vector<float> x0, x1;
  for (const auto& p : tube.positions) {
    x0.insert(x0.end(), {p[0], p[1], p[2]});
    x1.insert(x1.end(), {p[0], p[1] - 0.3f, p[2]});
  }
  {
    io::trj::TrjWriter w(dir / "run.trj");
    w.begin(topo);
    w.add_frame(0.0, x0);
    w.add_frame(0.5, x1);
    w.finish();
  }
  const auto avatar = (dir / "avatar.obj").string();
  auto run = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args{"-q", "render", (dir / "run.trj").string(), "--avatar", avatar, "--views", "front",
                                  "--size", "64", "-o", (dir / out).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return test::run_vgd(args);
  };
  ASSERT_EQ(run("first", {"--frame", "0"}).code, 0);
  ASSERT_EQ(run("last", {}).code, 0);
  const auto first = render::read_png(dir / "first" / "front.png"), last = render::read_png(dir / "last" / "front.png");
  EXPECT_NE(first.rgba, last.rgba) << "the last frame is the default";
  EXPECT_EQ(run("none", {"--frame", "2"}).code, 1) << "frame 2 of 2";
  EXPECT_EQ(test::run_vgd({"render", dir.string(), "--frame", "1", "-o", (dir / "x").string()}).code, 1)
      << "--frame needs a .trj";
}
