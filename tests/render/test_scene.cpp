// Scenes: colours from text, bounds, smooth normals that agree across a seam
// whatever the winding, and malformed meshes refused by name.
#include <gtest/gtest.h>

#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/render/scene.hpp"

using namespace vgd;

namespace {

// A unit square in the x-z plane (y = 0) split into two triangles, wound so
// its normal is +Y (or -Y when flipped), shifted by dx along x.
render::Mesh square(float dx, bool flipped) {
  render::Mesh m;
  m.positions = {{dx, 0, 0}, {dx + 1, 0, 0}, {dx + 1, 0, 1}, {dx, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}};  // counter-clockwise seen from +Y
  if (flipped)
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

}  // namespace

TEST(Colour, HexShortHexAndNamesParse) {
  const auto c = render::parse_colour("#ff8000");
  ASSERT_TRUE(c);
  EXPECT_FLOAT_EQ(c->r, 1.0f);
  EXPECT_NEAR(c->g, 128 / 255.0, 1e-6);
  EXPECT_FLOAT_EQ(c->b, 0.0f);
  EXPECT_EQ(render::to_hex(*render::parse_colour("F80")), "#ff8800");
  EXPECT_TRUE(render::parse_colour(" Red "));
  EXPECT_FALSE(render::parse_colour("#12345"));
  EXPECT_FALSE(render::parse_colour("#gg0000"));
  EXPECT_FALSE(render::parse_colour("reddish"));
  EXPECT_EQ(render::to_hex(render::piece_colour(0)), render::to_hex(render::piece_colour(8)));  // the palette cycles
  EXPECT_NE(render::to_hex(render::piece_colour(0)), render::to_hex(render::piece_colour(1)));
}

TEST(Scene, BoundsCoverTheMeshesOfTheAskedKind) {
  render::Scene s;
  s.meshes.push_back(square(0, false));
  s.meshes.push_back(square(5, false));
  s.meshes.back().kind = render::MeshKind::body;
  const auto all = render::bounds(s);
  EXPECT_DOUBLE_EQ(all.min[0], 0);
  EXPECT_DOUBLE_EQ(all.max[0], 6);
  const auto body = render::bounds(s, render::MeshKind::body);
  EXPECT_DOUBLE_EQ(body.min[0], 5);
  EXPECT_TRUE(render::bounds(render::Scene{}).empty());
}

TEST(Normals, AFlatSheetHasItsPlaneNormal) {
  render::Scene s;
  s.meshes.push_back(square(0, false));
  render::compute_normals(s);
  for (const auto& n : s.meshes[0].normals) {
    EXPECT_NEAR(n[0], 0, 1e-6);
    EXPECT_NEAR(n[1], 1, 1e-6);
    EXPECT_NEAR(n[2], 0, 1e-6);
  }
}

TEST(Normals, SeamVerticesOfPiecesWoundOppositeWaysShareOneDirection) {
  // Two pieces meeting along x = 1, one wound the other way, the second one
  // tilted so the shared normal is a blend: both sides must agree up to sign.
  render::Scene s;
  s.meshes.push_back(square(0, false));
  render::Mesh b = square(1, true);
  b.positions[1][1] = b.positions[2][1] = 0.5f;  // lift the far edge
  s.meshes.push_back(b);
  render::compute_normals(s);
  const auto& na = s.meshes[0].normals;
  const auto& nb = s.meshes[1].normals;
  // Vertex 1 of a = vertex 0 of b (1, 0, 0); vertex 2 of a = vertex 3 of b (1, 0, 1).
  for (const auto& [ia, ib] : {std::pair{1, 0}, std::pair{2, 3}}) {
    const double d = na[ia][0] * nb[ib][0] + na[ia][1] * nb[ib][1] + na[ia][2] * nb[ib][2];
    EXPECT_NEAR(std::abs(d), 1.0, 1e-6);                        // the same line
    EXPECT_LT(std::abs(na[ia][0]), 0.99) << "not blended";      // between +Y and the tilted piece's normal
    EXPECT_GT(std::abs(na[ia][0]), 0.05) << "not blended";
    EXPECT_GT(na[ia][1], 0) << "a keeps its own orientation (+Y side)";
    EXPECT_LT(nb[ib][1], 0) << "b keeps its own orientation (flipped)";
  }
  // Far from the seam, a's normal is its own plane's.
  EXPECT_NEAR(na[0][1], 1, 1e-6);
}

TEST(Scene, MalformedMeshesAreRefusedByName) {
  render::Scene s;
  s.meshes.push_back(square(0, false));
  s.meshes[0].name = "FRONT";
  s.meshes[0].triangles.push_back({0, 1, 9});
  try {
    render::check_scene(s);
    FAIL() << "expected vgd::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("FRONT"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
  s.meshes[0].triangles.pop_back();
  s.meshes[0].positions[0][1] = std::nanf("");
  EXPECT_THROW(render::check_scene(s), Error);
}
