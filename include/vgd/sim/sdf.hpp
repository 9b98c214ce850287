#pragma once
// Distance queries against a static closed triangle mesh (the avatar, a
// mannequin, any collider): the acceleration structures of body collisions.
//
// Two paths answer the same question — signed distance (m, negative inside)
// and the outward unit normal at the query point:
//
//  - SignedDistanceGrid: a regular grid of signed distances in a narrow band
//    around the surface (exact point–triangle distances there, ±band beyond),
//    sampled trilinearly. O(1) per query, a few tens of ns; the error is the
//    trilinear interpolation error (≈ spacing²/(8R) on a surface of radius R)
//    plus float rounding. What the body-collision effect uses by default.
//  - TriangleBvh: an AABB tree over the triangles giving the exact closest
//    point. O(log n) per query, a few hundred ns to µs; the reference and the
//    choice where the surface has features smaller than the grid spacing.
//
// Sign: angle-weighted pseudo-normals of the closest feature (Bærentzen and
// Aanæs 2005), exact on a watertight, consistently oriented mesh. The grid's
// far field (beyond the band) takes its sign from a flood fill of the grid
// from its boundary, blocked by the band, so no ray is ever cast.
// docs/collisions.md gives the measured costs and errors.
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "vgd/mesh/surface.hpp"
#include "vgd/sim/types.hpp"

namespace vgd::sim {

struct SdfOptions {
  double spacing = 0.005;  // m: grid node spacing (5 mm: error < 0.1 mm on a 0.3 m sphere, docs/collisions.md)
  double band = 0.02;      // m: half-width of the exact band; beyond it the grid holds ±band.
                           // Must exceed the collision clearance plus the largest step v·h.
};

// The closest-feature normals of a closed mesh: face normals, edge and vertex
// angle-weighted pseudo-normals (unit, outward). Shared by both query paths.
class MeshNormals {
 public:
  explicit MeshNormals(const mesh::SurfaceMesh& m);
  // The pseudo-normal of the feature of triangle t nearest a point whose
  // barycentric coordinates (on t) of its closest point are b: the face
  // normal inside, an edge's on an edge, a vertex's at a corner.
  Vec3 pseudo_normal(int t, const Vec3& b) const;
  const Vec3& face_normal(int t) const { return face_[t]; }
  // Vertex v's angle-weighted pseudo-normal (zero for a vertex of no triangle).
  const Vec3& vertex_normal(int v) const { return vertex_[v]; }

 private:
  std::vector<Vec3> face_, vertex_;
  std::vector<std::array<Vec3, 3>> edge_;  // per triangle: edges (0,1), (1,2), (2,0)
  std::vector<std::array<int, 3>> vtri_;   // the triangles' corners
};

// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision
// Detection §5.1.5); writes its barycentric coordinates into bary.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& bary);

class SignedDistanceGrid {
 public:
  SignedDistanceGrid(const mesh::SurfaceMesh& m, const SdfOptions& options = {});

  // Signed distance (m, < 0 inside) at p, trilinear. Outside the grid box
  // (beyond the band by construction) returns +band.
  double distance(const Vec3& p) const;
  // Signed distance and its gradient (unit length where the surface is near;
  // zero far outside the grid box). The gradient is the outward normal.
  double sample(const Vec3& p, Vec3& gradient) const;

  double spacing() const { return h_; }
  double band() const { return band_; }
  std::array<int, 3> dims() const { return {nx_, ny_, nz_}; }
  std::size_t memory_bytes() const { return phi_.size() * sizeof(float); }
  int band_nodes() const { return band_nodes_; }  // nodes with an exact distance

 private:
  float node(int i, int j, int k) const { return phi_[(static_cast<std::size_t>(k) * ny_ + j) * nx_ + i]; }
  double h_, inv_h_, band_;
  Vec3 origin_;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  int band_nodes_ = 0;
  std::vector<float> phi_;  // float: half the memory, 1e-7 relative rounding (0.1 µm at 1 m)
};

class TriangleBvh {
 public:
  explicit TriangleBvh(const mesh::SurfaceMesh& m);

  struct Closest {
    double distance = std::numeric_limits<double>::infinity();  // m, signed (< 0 inside)
    Vec3 point = Vec3::Zero();   // closest point on the surface
    Vec3 normal = Vec3::Zero();  // outward unit normal: (p − point)/|p − point| signed, or the pseudo-normal on the surface
    int triangle = -1;
  };
  // The closest surface point to p. Triangles farther than max_distance are
  // not searched; then triangle is -1 and distance is +inf.
  Closest closest(const Vec3& p, double max_distance = std::numeric_limits<double>::infinity()) const;

  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  const MeshNormals& normals() const { return normals_; }

 private:
  struct Node {
    std::array<float, 3> lo{}, hi{};  // box (rounded outward)
    int first = 0, count = 0;        // leaf: triangle range in order_; inner: count = 0, children first, first + 1
  };
  std::vector<Vec3> v_;
  std::vector<std::array<int, 3>> t_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
  MeshNormals normals_;
};

}  // namespace vgd::sim
