// The restructured mesh after seam merges (seed 002 §3.3): triangles
// re-pointed, collapsed ones removed, duplicate edges removed, and the checks
// that find non-manifold edges and degenerate triangles.
#include <gtest/gtest.h>

#include "vgd/sim/topology.hpp"

using namespace vgd::sim;

namespace {
// Two 3 × 3 grids (0.1 m cells) side by side; piece B's particles follow A's.
Model two_grids() {
  Model a = make_grid(3, 3, 0.1, 0.1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 0.01);
  Model b = make_grid(3, 3, 0.1, 0.1, Vec3(0.25, 0, 0), Vec3::UnitX(), Vec3::UnitY(), 0.01);
  Model m = a;
  const int na = a.num_particles();
  m.x0.conservativeResize(3 * (na + b.num_particles()));
  m.x0.tail(b.num_dofs()) = b.x0;
  m.v0 = VecX::Zero(m.x0.size());
  m.mass = VecX::Constant(na + b.num_particles(), 0.01);
  m.uv.insert(m.uv.end(), b.uv.begin(), b.uv.end());
  for (auto t : b.triangles) m.triangles.push_back({t[0] + na, t[1] + na, t[2] + na});
  m.triangle_piece.assign(m.triangles.size(), 0);
  for (std::size_t t = a.triangles.size(); t < m.triangles.size(); ++t) m.triangle_piece[t] = 1;
  m.pieces = {"A", "B"};
  return m;
}
}  // namespace

TEST(Topology, IdentityKeepsTheMeshAndAGridIsAManifoldWithBoundary) {
  const Model m = two_grids();
  const MergedMesh mm = merged_topology(m, identity_representative(m.num_particles()));
  EXPECT_EQ(mm.particles, 18);
  EXPECT_EQ(mm.triangles, m.triangles);
  EXPECT_EQ(mm.collapsed_triangles, 0);
  EXPECT_EQ(mm.merged_edges, 0);
  const MeshCheck c = check_merged_mesh(mm);
  EXPECT_TRUE(c.ok());
  EXPECT_EQ(c.triangles, 16);
  EXPECT_EQ(c.boundary_edges, 2 * 8);   // 8 boundary edges per 3 × 3 grid
  EXPECT_EQ(c.interior_edges, 2 * 8);   // 16 edges per grid, 8 inside
}

TEST(Topology, SewingTwoEdgesTurnsTheirBoundaryEdgesIntoInteriorOnes) {
  const Model m = two_grids();
  // A's right column (2, 5, 8) onto B's left column (9, 12, 15).
  std::vector<int> rep(18);
  int next = 0;
  for (int i = 0; i < 18; ++i) {
    if (i == 9 || i == 12 || i == 15) continue;
    rep[i] = next++;
  }
  rep[9] = rep[2], rep[12] = rep[5], rep[15] = rep[8];
  const MergedMesh mm = merged_topology(m, rep);
  EXPECT_EQ(mm.particles, 15);
  EXPECT_EQ(mm.triangles.size(), 16u);
  EXPECT_EQ(mm.merged_edges, 2);  // the two seam edges of B became A's
  const MeshCheck c = check_merged_mesh(mm);
  EXPECT_TRUE(c.ok());
  EXPECT_EQ(c.boundary_edges, 16 - 4);
  EXPECT_EQ(c.interior_edges, 16 + 2);
  EXPECT_EQ(c.edges, 30);
}

TEST(Topology, MergingTwoCornersOfATriangleCollapsesIt) {
  const Model m = make_grid(2, 2, 0.1, 0.1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 0.01);
  // Triangles (0, 1, 3) and (0, 3, 2); merge 1 into 3: the first collapses.
  const MergedMesh mm = merged_topology(m, {0, 1, 2, 1});
  EXPECT_EQ(mm.collapsed_triangles, 1);
  ASSERT_EQ(mm.triangles.size(), 1u);
  EXPECT_EQ(mm.source_triangle[0], 1);
  EXPECT_TRUE(check_merged_mesh(mm).ok());
}

TEST(Topology, TheCheckFindsNonManifoldEdgesDegenerateAndDuplicateTriangles) {
  // Three triangles on the edge (0, 1), one with a repeated corner, one repeated.
  const MeshCheck c = check_mesh({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {5, 5, 6}, {2, 1, 0}});
  EXPECT_EQ(c.non_manifold_edges, 1);
  ASSERT_EQ(c.non_manifold.size(), 1u);
  EXPECT_EQ(c.non_manifold[0], (std::array<int, 2>{0, 1}));
  EXPECT_EQ(c.degenerate_triangles, 1);
  EXPECT_EQ(c.duplicate_triangles, 1);
  EXPECT_FALSE(c.ok());
}
