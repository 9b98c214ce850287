// OBJ frame sequences: what is written reads back (vertex and face counts,
// coordinates, pattern coordinates as `vt`), files are named frame_0000.obj,
// ..., and the files of a run that stopped early stay complete.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/obj/obj.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/run.hpp"

using namespace vgd;
namespace fs = std::filesystem;

namespace {

// A 4 x 3 grid in the x-y plane, 0.1 m apart.
sim::Model grid() { return sim::make_grid(4, 3, 0.1, 0.1, sim::Vec3::Zero(), sim::Vec3::UnitX(), sim::Vec3::UnitY(), 0.01); }

}  // namespace

TEST(ObjFrames, FileNamesHaveFourDigitsAndGrow) {
  EXPECT_EQ(io::obj::frame_file_name(0), "frame_0000.obj");
  EXPECT_EQ(io::obj::frame_file_name(42), "frame_0042.obj");
  EXPECT_EQ(io::obj::frame_file_name(12345), "frame_12345.obj");
}

TEST(ObjFrames, AFrameReadsBackWithItsVerticesFacesAndCoordinates) {
  const auto dir = test::scratch_dir("obj_frame");
  const sim::Model m = grid();
  sim::VecX x = m.x0;
  x[5] = -0.123456789;  // particle 1's z
  write_file_atomic(dir / "a.obj", io::obj::frame_text(m, 0.5, x));
  const auto r = io::obj::read_obj(dir / "a.obj");
  ASSERT_EQ(r.vertices.size(), 12u);
  ASSERT_EQ(r.faces.size(), m.triangles.size());
  for (int i = 0; i < 12; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.vertices[i][k], x[3 * i + k], 1e-9 * (1 + std::abs(x[3 * i + k])));
  // 1-based in the file, 0-based back: the same triangles in the same order (one piece).
  for (std::size_t t = 0; t < m.triangles.size(); ++t) EXPECT_EQ(r.faces[t], m.triangles[t]);
  ASSERT_EQ(r.groups.size(), 1u);
  EXPECT_EQ(r.groups[0], "grid");
}

TEST(ObjFrames, FacesAreGroupedByPiece) {
  sim::Model m = grid();
  m.pieces = {"front piece", "back"};
  for (std::size_t t = 0; t < m.triangle_piece.size(); ++t) m.triangle_piece[t] = static_cast<int>(t % 2);
  const auto dir = test::scratch_dir("obj_groups");
  write_file_atomic(dir / "g.obj", io::obj::frame_text(m, 0.0, m.x0));
  const auto r = io::obj::read_obj(dir / "g.obj");
  EXPECT_EQ(r.groups, (std::vector<std::string>{"front_piece", "back"}));
  EXPECT_EQ(r.faces.size(), m.triangles.size());
  EXPECT_EQ(r.faces[0], m.triangles[0]);  // piece 0's first
  EXPECT_EQ(r.faces[1], m.triangles[2]);  // piece 0's second
}

TEST(ObjFrames, ASequenceSinkWritesOneFilePerFrame) {
  const auto dir = test::scratch_dir("obj_sequence") / "frames";
  sim::Model m = grid();
  sim::System sys(m, [] {
    std::vector<std::unique_ptr<sim::Effect>> e;
    e.push_back(sim::make_gravity({}));
    return e;
  }());
  auto integ = sim::make_integrator({});
  sim::State s = sim::initial_state(sys.model());
  io::obj::ObjSequenceSink sink(dir);
  const auto r = sim::run(sys, *integ, s, {10.0, 0.5}, {&sink});
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(sink.files_written(), 6);
  for (int k = 0; k <= 5; ++k) EXPECT_TRUE(fs::exists(dir / io::obj::frame_file_name(k))) << k;
  EXPECT_FALSE(fs::exists(dir / "frame_0006.obj"));
  // Free fall: the last frame is ½ g t² below the first.
  const auto first = io::obj::read_obj(dir / "frame_0000.obj"), last = io::obj::read_obj(dir / "frame_0005.obj");
  EXPECT_NEAR(first.vertices[0][1] - last.vertices[0][1], 0.5 * 9.81 * 0.25, 0.02);
  // No temporary files left behind.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.path().extension() == ".obj";
  EXPECT_EQ(files, 6);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 6);
}

TEST(ObjFrames, FramesWrittenBeforeABlowUpStayComplete) {
  // A force that turns infinite at t > 0.25 s stops the run; frames 0..2 (0, 0.1, 0.2 s) are whole files.
  class Bomb final : public sim::Effect {
   public:
    const char* name() const override { return "bomb"; }
    void add_forces(const sim::Eval& e, sim::VecX& f) override {
      if (e.t > 0.25) f[0] = std::numeric_limits<double>::infinity();
    }
  };
  const auto dir = test::scratch_dir("obj_blowup");
  std::vector<std::unique_ptr<sim::Effect>> e;
  e.push_back(std::make_unique<Bomb>());
  sim::System sys(grid(), std::move(e));
  auto integ = sim::make_integrator({});
  sim::State s = sim::initial_state(sys.model());
  io::obj::ObjSequenceSink sink(dir);
  const auto r = sim::run(sys, *integ, s, {10.0, 1.0}, {&sink});
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(sink.files_written(), 3);
  for (int k = 0; k < 3; ++k) {
    const auto m = io::obj::read_obj(dir / io::obj::frame_file_name(k));
    EXPECT_EQ(m.vertices.size(), 12u);
    for (const auto& v : m.vertices) EXPECT_TRUE(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]));
  }
  EXPECT_FALSE(fs::exists(dir / "frame_0003.obj"));
}

TEST(ObjFrames, TheReaderNamesTheLineOfAMalformedFile) {
  const auto dir = test::scratch_dir("obj_bad");
  write_file_atomic(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  try {
    io::obj::read_obj(dir / "bad.obj");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().line, 4);
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
}

TEST(ObjFrames, PatternCoordinatesRoundTripAsVt) {
  // garment.obj: the model's uv (m) as `vt`, one per vertex with its index, faces `f a/a b/b c/c`.
  sim::Model m = grid();
  m.pieces = {"FRONT", "BACK"};
  for (std::size_t t = 0; t < m.triangle_piece.size(); ++t) m.triangle_piece[t] = static_cast<int>(t % 2);
  m.uv[7] = sim::Vec2(0.123456789, -0.5);
  const auto dir = test::scratch_dir("obj_vt");
  const std::string text = io::obj::frame_text(m, 0.0, m.x0);
  EXPECT_NE(text.find("\nvt 0.123456789 -0.5\n"), std::string::npos);
  write_file_atomic(dir / "vt.obj", text);
  const auto r = io::obj::read_obj(dir / "vt.obj");
  ASSERT_EQ(r.texcoords.size(), m.uv.size());
  for (std::size_t i = 0; i < m.uv.size(); ++i) {
    EXPECT_NEAR(r.texcoords[i][0], m.uv[i].x(), 1e-12) << i;
    EXPECT_NEAR(r.texcoords[i][1], m.uv[i].y(), 1e-12) << i;
  }
  ASSERT_EQ(r.faces.size(), m.triangles.size());
  ASSERT_EQ(r.face_texcoords.size(), r.faces.size());
  for (std::size_t f = 0; f < r.faces.size(); ++f) EXPECT_EQ(r.face_texcoords[f], r.faces[f]) << f;
  EXPECT_EQ(r.groups, (std::vector<std::string>{"FRONT", "BACK"}));
  EXPECT_EQ(r.face_group.front(), 0);
  EXPECT_EQ(r.face_group.back(), 1);
}

TEST(ObjFrames, FilesWithoutVtReadAsBefore) {
  // Frame sequences stay without vt (the sink keeps no uv); faces then have no texture coordinates.
  const auto dir = test::scratch_dir("obj_no_vt");
  sim::Model m = grid();
  m.uv.clear();
  write_file_atomic(dir / "plain.obj", io::obj::frame_text(m, 0.0, m.x0));
  const auto r = io::obj::read_obj(dir / "plain.obj");
  EXPECT_TRUE(r.texcoords.empty());
  ASSERT_EQ(r.faces.size(), m.triangles.size());
  for (std::size_t f = 0; f < r.faces.size(); ++f) {
    EXPECT_EQ(r.faces[f], m.triangles[f]);
    EXPECT_EQ(r.face_texcoords[f], (std::array<int, 3>{-1, -1, -1}));
  }
  // Other writers' forms: v/vt/vn, v//vn, negative indices, a third vt value.
  write_file_atomic(dir / "forms.obj",
                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
                    "f 1/1/1 2/2/1 3/3/1\nf -3//1 -2//1 -1//1\nf 1/-3 2/-2 3/-1\n");
  const auto forms = io::obj::read_obj(dir / "forms.obj");
  ASSERT_EQ(forms.faces.size(), 3u);
  EXPECT_EQ(forms.faces[1], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(forms.face_texcoords[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(forms.face_texcoords[1], (std::array<int, 3>{-1, -1, -1}));
  EXPECT_EQ(forms.face_texcoords[2], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(forms.face_group, (std::vector<int>{-1, -1, -1}));
}

TEST(ObjFrames, ATextureIndexOutOfRangeOrOnSomeCornersIsRefused) {
  const auto dir = test::scratch_dir("obj_bad_vt");
  write_file_atomic(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n");
  EXPECT_THROW(io::obj::read_obj(dir / "range.obj"), Error);
  write_file_atomic(dir / "some.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n");
  try {
    io::obj::read_obj(dir / "some.obj");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().line, 5);
    EXPECT_NE(std::string(e.what()).find("some corners"), std::string::npos) << e.what();
  }
}
