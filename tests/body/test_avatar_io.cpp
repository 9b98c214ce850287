// Avatar import/export (assimp): round trips through every export format,
// unit and up-axis normalisation, and the errors a user sees for bad files.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/body/avatar_io.hpp"
#include "vgd/body/mannequin.hpp"

using namespace vgd;
using namespace vgd::body;

namespace {

const Avatar& mannequin_body() {
  static const Avatar a = [] {
    MannequinOptions o;
    o.target_triangles = 5000;
    return make_mannequin(BodyMeasurements{}, o);
  }();
  return a;
}

std::string error_of(const std::filesystem::path& p, const AvatarImportOptions& o = {}) {
  try {
    import_avatar(p, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

class AvatarRoundTrip : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(AvatarRoundTrip, ExportThenImportKeepsTheMesh) {
  const auto dir = test::scratch_dir("avatar_io_" + GetParam().substr(1));
  const auto path = dir / ("body" + GetParam());
  export_avatar(mannequin_body(), path);
  ASSERT_TRUE(std::filesystem::exists(path));
  AvatarReport r;
  AvatarImportOptions o;
  o.unit = "m";  // the round trip checks geometry, not guessing (tested below)
  o.up = "y";
  const Avatar back = import_avatar(path, o, &r);
  EXPECT_EQ(back.surface.num_vertices(), mannequin_body().surface.num_vertices());
  EXPECT_EQ(back.surface.num_triangles(), mannequin_body().surface.num_triangles());
  const auto a = mesh::bounding_box(mannequin_body().surface), b = mesh::bounding_box(back.surface);
  EXPECT_LT((a.min - b.min).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((a.max - b.max).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_TRUE(r.watertight) << GetParam();
  EXPECT_NEAR(mesh::signed_volume(back.surface), mesh::signed_volume(mannequin_body().surface), 1e-6);
  // No temporary export folder is left behind.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().rfind(".vgd-export-", 0), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Formats, AvatarRoundTrip, ::testing::Values(".obj", ".ply", ".stl", ".glb", ".gltf", ".dae", ".fbx"),
                         [](const auto& p) { return p.param.substr(1); });

TEST(AvatarImport, CentimetresZUpAreNormalisedAutomatically) {
  const auto dir = test::scratch_dir("avatar_io_cm_zup");
  Avatar a = mannequin_body();
  // To Z-up the way Blender stores it (front = -Y), in centimetres, off-centre.
  Eigen::Matrix3d to_z;
  to_z << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // (x, y, z) -> (x, -z, y)
  mesh::transform(a.surface, 100.0 * to_z, Vec3(12, -30, 7));
  export_avatar(a, dir / "cm-zup.obj");
  AvatarReport r;
  const Avatar back = import_avatar(dir / "cm-zup.obj", {}, &r);
  EXPECT_EQ(r.unit, "cm");
  EXPECT_TRUE(r.unit_guessed);
  EXPECT_EQ(r.up, "z");
  EXPECT_TRUE(r.up_guessed);
  const auto want = mesh::bounding_box(mannequin_body().surface), got = mesh::bounding_box(back.surface);
  EXPECT_LT((want.min - got.min).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_LT((want.max - got.max).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_NEAR(r.height, want.size().y(), 1e-5);
  EXPECT_TRUE(r.watertight);
  // Facing is preserved: the feet (which point forward) are on +Z.
  double foot_z = -1;
  for (const auto& v : back.surface.vertices)
    if (v.y() < 0.01) foot_z = std::max(foot_z, v.z());
  EXPECT_GT(foot_z, 0.1);
  // Best-effort segments from slices.
  EXPECT_NE(back.segment("hips"), nullptr);
  EXPECT_NE(back.segment("torso"), nullptr);
  EXPECT_NE(back.segment("left-leg"), nullptr);
  EXPECT_NE(back.segment("right-leg"), nullptr);
  const auto j = nlohmann::json::parse(to_json(r));
  EXPECT_EQ(j.at("unit").at("value"), "cm");
  EXPECT_EQ(j.at("triangles"), mannequin_body().surface.num_triangles());
}

TEST(AvatarImport, StlIsWelded) {
  const auto dir = test::scratch_dir("avatar_io_stl");
  export_avatar(mannequin_body(), dir / "b.stl");
  AvatarReport r;
  import_avatar(dir / "b.stl", {}, &r);
  EXPECT_EQ(r.vertices, mannequin_body().surface.num_vertices());
  EXPECT_TRUE(r.watertight);
  EXPECT_EQ(r.unit, "m");
}

TEST(AvatarImport, BadFilesSayWhatIsWrong) {
  const auto dir = test::scratch_dir("avatar_io_bad");
  EXPECT_NE(error_of(dir / "missing.obj").find("no such file"), std::string::npos);
  write_file_atomic(dir / "empty.obj", "");
  EXPECT_NE(error_of(dir / "empty.obj").find("empty"), std::string::npos);
  static const char kGarbage[] = "\x01\x02 this is not a model \xff\xfe";
  write_file_atomic(dir / "garbage.glb", std::string(kGarbage, sizeof kGarbage - 1));
  const std::string garbage = error_of(dir / "garbage.glb");
  EXPECT_NE(garbage.find("not a 3-D model"), std::string::npos) << garbage;
  EXPECT_NE(garbage.find("garbage.glb"), std::string::npos) << garbage;
  // A file in a format vgd reads that holds no surface is empty, not unreadable.
  write_file_atomic(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string points = error_of(dir / "points.obj");
  EXPECT_NE(points.find("holds no triangles"), std::string::npos) << points;
  EXPECT_EQ(points.find("not a 3-D model"), std::string::npos) << points;
  write_file_atomic(dir / "facetless.stl", "solid x\nendsolid x\n");
  const std::string facetless = error_of(dir / "facetless.stl");
  EXPECT_NE(facetless.find("facetless.stl: the file holds no triangles"), std::string::npos) << facetless;
  write_file_atomic(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 1 0 1\nf 1 2 3\nf 2 4 3\n");
  AvatarImportOptions up_y;
  up_y.up = "y";
  EXPECT_NE(error_of(dir / "flat.obj", up_y).find("flat"), std::string::npos) << error_of(dir / "flat.obj", up_y);
  AvatarImportOptions bad_unit;
  bad_unit.unit = "furlong";
  write_file_atomic(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(error_of(dir / "tri.obj", bad_unit).find("unknown unit"), std::string::npos);
  EXPECT_THROW(export_avatar(mannequin_body(), dir / "body.xyz"), Error);
}
