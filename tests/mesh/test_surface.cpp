// Closed-surface helpers: watertightness, volume, welding, slicing; and the
// implicit-surface mesher on a sphere.
#include <gtest/gtest.h>

#include <cmath>

#include "vgd/mesh/implicit_surface.hpp"
#include "vgd/mesh/surface.hpp"

using namespace vgd::mesh;

namespace {

// Unit cube [0,1]³, 12 triangles, counter-clockwise seen from outside.
SurfaceMesh cube() {
  SurfaceMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

}  // namespace

TEST(Surface, CubeIsWatertight) {
  const auto c = check_surface(cube());
  EXPECT_TRUE(c.watertight());
  EXPECT_EQ(c.edges, 18);
  EXPECT_EQ(c.boundary_edges, 0);
  EXPECT_NEAR(c.volume, 1.0, 1e-12);
  EXPECT_NEAR(c.area, 6.0, 1e-12);
  EXPECT_NEAR(c.max_edge, std::sqrt(2.0), 1e-12);
  const auto b = bounding_box(cube());
  EXPECT_EQ(b.min, Vec3::Zero());
  EXPECT_EQ(b.max, Vec3::Ones());
  for (const auto& n : vertex_normals(cube())) EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  EXPECT_GT(vertex_normals(cube())[7].minCoeff(), 0.5);  // the (1,1,1) corner's normal points out
}

TEST(Surface, OpenCubeHasBoundary) {
  auto m = cube();
  m.triangles.pop_back();
  m.triangles.pop_back();
  const auto c = check_surface(m);
  EXPECT_FALSE(c.watertight());
  EXPECT_EQ(c.boundary_edges, 4);
}

TEST(Surface, FlippedFaceIsInconsistent) {
  SurfaceMesh t;
  t.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  t.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_TRUE(check_surface(t).watertight());
  EXPECT_NEAR(signed_volume(t), 1.0 / 6.0, 1e-12);
  std::swap(t.triangles[3][1], t.triangles[3][2]);
  const auto c = check_surface(t);
  EXPECT_FALSE(c.watertight());
  EXPECT_EQ(c.inconsistent_edges, 3);
}

TEST(Surface, NonManifoldEdgeIsCounted) {
  auto m = cube();
  m.vertices.emplace_back(0.5, -1, 0.5);
  m.triangles.push_back({0, 1, 8});
  EXPECT_EQ(check_surface(m).non_manifold_edges, 1);
}

TEST(Surface, TransformKeepsOrientationUnderReflection) {
  auto m = cube();
  Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
  mirror(0, 0) = -2.0;
  transform(m, mirror, Vec3(1, 2, 3));
  EXPECT_TRUE(is_watertight(m));
  EXPECT_NEAR(signed_volume(m), 2.0, 1e-12);
  EXPECT_NEAR(bounding_box(m).min.x(), -1.0, 1e-12);
}

TEST(Surface, WeldJoinsStlStyleTriangles) {
  // Every triangle with its own corners, as STL stores them, with 1e-9 noise.
  const auto c = cube();
  SurfaceMesh soup;
  for (const auto& t : c.triangles) {
    const int base = soup.num_vertices();
    for (int k = 0; k < 3; ++k) soup.vertices.push_back(c.vertices[t[k]] + Vec3::Constant(1e-9 * k));
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  EXPECT_FALSE(is_watertight(soup));
  EXPECT_EQ(weld_vertices(soup, 1e-6), 36 - 8);
  EXPECT_EQ(soup.num_vertices(), 8);
  EXPECT_TRUE(is_watertight(soup));
}

TEST(Surface, SliceAndHull) {
  const auto loops = slice_horizontal(cube(), 0.5);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_NEAR(convex_hull_perimeter(loops[0]), 4.0, 1e-12);
  EXPECT_TRUE(point_in_polygon(loops[0], Vec2d(0.5, 0.5)));
  EXPECT_FALSE(point_in_polygon(loops[0], Vec2d(1.5, 0.5)));
  EXPECT_TRUE(slice_horizontal(cube(), 2.0).empty());
}

TEST(ImplicitSurface, SphereIsWatertightAndOnTheSurface) {
  const double R = 0.2;
  Box3 box;
  box.extend(Vec3::Constant(-0.25));
  box.extend(Vec3::Constant(0.25));
  ImplicitSurfaceCriteria c;
  c.facet_size = 0.02;
  c.facet_distance = 0.002;
  const auto m = mesh_implicit_surface([R](const Vec3& p) { return p.norm() - R; }, box, c);
  const auto check = check_surface(m);
  EXPECT_TRUE(check.watertight());
  EXPECT_GT(check.triangles, 300);
  for (const auto& v : m.vertices) EXPECT_NEAR(v.norm(), R, 1e-6);
  EXPECT_NEAR(check.volume, 4.0 / 3.0 * M_PI * R * R * R, 0.03 * 4.0 / 3.0 * M_PI * R * R * R);
}
