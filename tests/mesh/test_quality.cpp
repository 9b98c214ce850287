// The mesh checker finds each kind of defect on small hand-made meshes.
#include <gtest/gtest.h>

#include "vgd/mesh/quality.hpp"

using namespace vgd::mesh;

namespace {

// The unit square as two triangles, with its boundary listed as the mesher would.
PieceMesh two_triangles() {
  PieceMesh m;
  m.piece = "UNIT";
  m.contours = {Contour{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {0, 1, 2, 3}, -1}};
  m.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.node_markers = {1, 1, 1, 1};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  for (int i = 0; i < 4; ++i) m.boundary.push_back({i, (i + 1) % 4, 0, i, i, kOutlineMarker});
  m.contour_nodes = {{0, 1, 2, 3}};
  return m;
}

}  // namespace

TEST(CheckMesh, TwoTrianglesMakeAValidSquare) {
  const QualityReport q = check_mesh(two_triangles());
  EXPECT_TRUE(q.valid()) << (q.problems.empty() ? "" : q.problems.front());
  EXPECT_DOUBLE_EQ(q.min_angle_deg, 45.0);
  EXPECT_DOUBLE_EQ(q.max_angle_deg, 90.0);
  EXPECT_DOUBLE_EQ(q.mesh_area_m2, 1.0);
  EXPECT_DOUBLE_EQ(q.polygon_area_m2, 1.0);
  EXPECT_DOUBLE_EQ(q.max_area_m2, 0.5);
  EXPECT_EQ(q.sharp_corners, 0);
  EXPECT_EQ(q.boundary_steiner_nodes, 0);
}

TEST(CheckMesh, FindsAClockwiseTriangle) {
  auto m = two_triangles();
  m.triangles[1] = {0, 3, 2};
  const QualityReport q = check_mesh(m);
  EXPECT_EQ(q.clockwise_triangles, 1);
  EXPECT_GT(q.non_manifold_edges, 0);  // edge 0-2 now used twice the same way
  EXPECT_FALSE(q.valid());
}

TEST(CheckMesh, FindsAMissingTriangleAsAHoleInTheBoundaryAndArea) {
  auto m = two_triangles();
  m.triangles.pop_back();
  const QualityReport q = check_mesh(m);
  EXPECT_GT(q.boundary_mismatches, 0);
  EXPECT_EQ(q.unused_nodes, 1);
  EXPECT_NEAR(q.area_rel_error, 0.5, 1e-15);
  EXPECT_FALSE(q.valid());
}

TEST(CheckMesh, FindsNonManifoldEdges) {
  auto m = two_triangles();
  m.nodes.push_back({2, 0.5});
  m.nodes.push_back({3, 0.5});
  m.node_markers.insert(m.node_markers.end(), {0, 0});
  m.triangles.push_back({2, 1, 4});  // edge 1-2 now has three triangles
  m.triangles.push_back({2, 1, 5});
  const QualityReport q = check_mesh(m);
  EXPECT_GT(q.non_manifold_edges, 0);
  EXPECT_FALSE(q.valid());
}

TEST(CheckMesh, FindsDuplicateAndDegenerate) {
  auto m = two_triangles();
  m.nodes.push_back({1, 1});  // same place as node 2
  m.node_markers.push_back(0);
  m.triangles.push_back({1, 2, 4});  // zero area
  const QualityReport q = check_mesh(m);
  EXPECT_EQ(q.duplicate_nodes, 1);
  EXPECT_EQ(q.degenerate_triangles, 1);
  EXPECT_FALSE(q.valid());
}

TEST(CheckMesh, FindsBadIndicesAndMissingContourVertices) {
  auto m = two_triangles();
  m.triangles.push_back({0, 1, 7});
  m.contour_nodes[0][2] = 0;  // points at the wrong node
  const QualityReport q = check_mesh(m);
  EXPECT_EQ(q.bad_indices, 1);
  EXPECT_EQ(q.missing_contour_vertices, 1);
  EXPECT_FALSE(q.valid());
}

TEST(CheckMesh, SharpCornersAreExemptFromTheAngleBound) {
  // A 10° wedge split into two triangles at its mid-height.
  PieceMesh m;
  const double t = std::tan(5.0 * 3.14159265358979323846 / 180.0);
  m.contours = {Contour{{{0, 0}, {1, -t}, {1, t}}, {}, -1}};
  m.nodes = {{0, 0}, {1, -t}, {1, t}, {1, 0}};
  m.node_markers = {1, 1, 1, 1};
  m.triangles = {{0, 1, 3}, {0, 3, 2}};
  m.boundary = {{0, 1, 0, 0, -1, 1}, {1, 3, 0, 1, -1, 1}, {3, 2, 0, 1, -1, 1}, {2, 0, 0, 2, -1, 1}};
  m.contour_nodes = {{0, 1, 2}};
  const QualityReport q = check_mesh(m, 20.7);
  EXPECT_TRUE(q.valid()) << (q.problems.empty() ? "" : q.problems.front());
  EXPECT_EQ(q.sharp_corners, 1);
  EXPECT_NEAR(q.min_angle_deg, 5.0, 1e-9);
  EXPECT_EQ(q.min_angle_away_from_sharp_deg, 180.0);  // every triangle touches the tip
  EXPECT_EQ(q.boundary_steiner_nodes, 1);
  const auto angles = interior_angles_deg(m, 0);
  EXPECT_NEAR(angles[0], 10.0, 1e-9);
  EXPECT_NEAR(angles[1] + angles[2], 170.0, 1e-9);
}

TEST(CheckMesh, InteriorAnglesOfAHoleAreSeenFromThePiece) {
  PieceMesh m;
  m.contours = {Contour{{{-1, -1}, {2, -1}, {2, 2}, {-1, 2}}, {}, -1},
                Contour{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}, 0}};  // hole given CCW
  for (double a : interior_angles_deg(m, 0)) EXPECT_NEAR(a, 90.0, 1e-12);
  for (double a : interior_angles_deg(m, 1)) EXPECT_NEAR(a, 270.0, 1e-12);
}
