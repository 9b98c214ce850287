// The benchmark colliders are closed, outward-facing and of the stated size.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "vgd/core/diagnostics.hpp"
#include "vgd/mesh/primitives.hpp"

namespace vgd::mesh {
namespace {

// Signed volume (divergence theorem) and whether every directed edge appears
// once with its reverse once: closed and consistently oriented.
double enclosed_volume(const SurfaceMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

bool closed_and_oriented(const SurfaceMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    if (n != 1) return false;
    const auto r = directed.find({e.second, e.first});
    if (r == directed.end() || r->second != 1) return false;
  }
  return true;
}

TEST(Primitives, BenchmarkSphereHasBlendersTriangleCountAndEnclosesItsVolume) {
  const SurfaceMesh s = uv_sphere(Vec3(0.1, 0.2, 0.3), 0.3, 64, 40);
  EXPECT_EQ(s.num_triangles(), 4992);
  EXPECT_TRUE(closed_and_oriented(s));
  const double exact = 4.0 / 3.0 * std::numbers::pi * 0.027;
  // An inscribed polyhedron: a little less than the ball, never more.
  EXPECT_LT(enclosed_volume(s), exact);
  EXPECT_GT(enclosed_volume(s), 0.99 * exact);
  for (const auto& v : s.vertices) EXPECT_NEAR((v - Vec3(0.1, 0.2, 0.3)).norm(), 0.3, 1e-12);
}

TEST(Primitives, CylinderAndBoxAreClosedAndOutwardFacing) {
  const SurfaceMesh c = cylinder(Vec3(0, 0.5, 0), 0.15, 0.8, 48, 4);
  EXPECT_EQ(c.num_triangles(), 4 * 48 + 2 * 48 * 3);
  EXPECT_TRUE(closed_and_oriented(c));
  const double exact = std::numbers::pi * 0.15 * 0.15 * 0.8;
  EXPECT_GT(enclosed_volume(c), 0.99 * exact);
  EXPECT_LT(enclosed_volume(c), exact);
  const SurfaceMesh b = box(Vec3(-1, 0, 2), Vec3(1, 0.5, 3));
  EXPECT_TRUE(closed_and_oriented(b));
  EXPECT_NEAR(enclosed_volume(b), 2 * 0.5 * 1, 1e-12);
}

TEST(Primitives, DegenerateParametersAreRefused) {
  EXPECT_THROW(uv_sphere(Vec3::Zero(), 0.3, 2, 10), Error);
  EXPECT_THROW(cylinder(Vec3::Zero(), -1, 1, 8), Error);
}

}  // namespace
}  // namespace vgd::mesh
