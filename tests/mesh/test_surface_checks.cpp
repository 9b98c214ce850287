// Exact penetration depths and triangle–triangle crossings (surface_checks.hpp).
#include <gtest/gtest.h>

#include "vgd/mesh/surface_checks.hpp"

namespace vgd::mesh {
namespace {

SurfaceMesh cube(double h) {  // [-h, h]³, outward
  SurfaceMesh m;
  for (int k = 0; k < 8; ++k) m.vertices.emplace_back(k & 1 ? h : -h, k & 2 ? h : -h, k & 4 ? h : -h);
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

TEST(SurfaceChecks, PenetrationDepthOfPointsInsideACube) {
  const auto d = penetration_depths(cube(0.1), {Vec3(0.098, 0, 0), Vec3(0.2, 0, 0), Vec3(0, 0, 0), Vec3(0.1, 0.0, 0.0),
                                                Vec3(-0.05, 0.095, 0.0)});
  ASSERT_EQ(d.size(), 5u);
  EXPECT_NEAR(d[0], 0.002, 1e-12);  // 2 mm inside
  EXPECT_EQ(d[1], 0.0);             // outside
  EXPECT_NEAR(d[2], 0.1, 1e-12);    // centre
  EXPECT_EQ(d[3], 0.0);             // on the surface
  EXPECT_NEAR(d[4], 0.005, 1e-12);
}

TEST(SurfaceChecks, TwoCrossingTrianglesAreOneIntersection) {
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, -0.5}, {0.3, 0.2, 0.5}, {0.2, 0.3, 0.5}};
  EXPECT_EQ(count_triangle_intersections(v, {{0, 1, 2}, {3, 4, 5}}), 1);
  // Moved apart: none.
  std::vector<Vec3> w = v;
  for (int i = 3; i < 6; ++i) w[i].z() += 1.0;
  EXPECT_EQ(count_triangle_intersections(w, {{0, 1, 2}, {3, 4, 5}}), 0);
}

TEST(SurfaceChecks, FlatGridHasNoIntersectionsAndIsFast) {
  // 101 × 101 grid: 20 000 triangles; neighbours share vertices and are not counted.
  const int n = 101;
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> t;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) v.emplace_back(0.01 * i, 0.01 * j, 0.0);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      t.push_back({a, a + 1, a + n + 1});
      t.push_back({a, a + n + 1, a + n});
    }
  EXPECT_EQ(count_triangle_intersections(v, t), 0);
  // A fold pushed through the sheet: a second grid crossing it is counted.
  std::vector<Vec3> v2 = v;
  std::vector<std::array<int, 3>> t2 = t;
  const int off = static_cast<int>(v.size());
  for (const auto& p : v) v2.emplace_back(p.x(), 0.5, p.y() - 0.5);  // vertical sheet through y = 0.5
  for (const auto& tr : t) t2.push_back({tr[0] + off, tr[1] + off, tr[2] + off});
  EXPECT_GT(count_triangle_intersections(v2, t2), 0);
}

}  // namespace
}  // namespace vgd::mesh
