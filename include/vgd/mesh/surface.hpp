#pragma once
// Closed 3-D triangle surfaces: avatars, the parametric mannequin, colliders.
//
// Units: metres. vgd's world frame: +Y up, the body facing +Z, feet on y = 0.
// A SurfaceMesh is plain data (libigl's V/F): the stages that make one (the
// mannequin generator, the assimp importer) and the ones that use one (body
// collisions, penetration checks) agree on nothing else.
//
// The helpers below are plain C++ (no CGAL): measuring (box, area, volume,
// edge statistics, watertightness), transforming, welding (STL stores every
// triangle's corners separately) and horizontal slicing (what a tape measure
// sees: girths are convex-hull perimeters of slices).
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vgd::mesh {

using Vec3 = Eigen::Vector3d;

struct SurfaceMesh {
  std::vector<Vec3> vertices;                 // m
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside (normals point out)

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
};

// Axis-aligned bounding box, m. Empty (min > max) for a mesh without vertices.
struct Box3 {
  Vec3 min = Vec3::Constant(1e300);
  Vec3 max = Vec3::Constant(-1e300);
  bool empty() const { return (min.array() > max.array()).any(); }
  Vec3 size() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
  Vec3 centre() const { return 0.5 * (min + max); }
  void extend(const Vec3& p) { min = min.cwiseMin(p), max = max.cwiseMax(p); }
};

// Box of the vertices referenced or not (every vertex counts).
Box3 bounding_box(const SurfaceMesh& m);
// Sum of triangle areas, m².
double surface_area(const SurfaceMesh& m);
// Signed volume enclosed (divergence theorem), m³: positive for a closed mesh
// whose triangles are counter-clockwise seen from outside.
double signed_volume(const SurfaceMesh& m);

// Edge and triangle statistics: what makes a surface usable as a collider.
struct SurfaceCheck {
  int vertices = 0, triangles = 0;
  int edges = 0;                  // distinct undirected edges
  int boundary_edges = 0;         // used by one triangle (a hole's rim)
  int non_manifold_edges = 0;     // used by three or more triangles
  int inconsistent_edges = 0;     // two triangles traverse it the same way (flipped neighbour)
  int degenerate_triangles = 0;   // a repeated corner or area ≤ degenerate_area
  int invalid_indices = 0;        // corners out of range (such triangles are otherwise ignored)
  int unused_vertices = 0;        // referenced by no triangle
  double area = 0.0;              // m²
  double volume = 0.0;            // m³, signed
  double min_edge = 0.0, max_edge = 0.0, mean_edge = 0.0;  // m, over distinct edges
  bool consistently_oriented() const { return inconsistent_edges == 0; }
  // A closed 2-manifold, consistently oriented, enclosing a positive volume.
  bool watertight() const {
    return triangles > 0 && boundary_edges == 0 && non_manifold_edges == 0 && inconsistent_edges == 0 &&
           invalid_indices == 0 && volume > 0.0;
  }
};

// degenerate_area: m²; triangles at or below it count as degenerate.
SurfaceCheck check_surface(const SurfaceMesh& m, double degenerate_area = 0.0);
inline bool is_watertight(const SurfaceMesh& m) { return check_surface(m).watertight(); }

// Area-weighted unit vertex normals (zero for unused vertices).
std::vector<Vec3> vertex_normals(const SurfaceMesh& m);

// p -> linear · p + translation for every vertex. A reflection (det < 0)
// reverses every triangle so the normals still point out.
void transform(SurfaceMesh& m, const Eigen::Matrix3d& linear, const Vec3& translation = Vec3::Zero());
inline void translate(SurfaceMesh& m, const Vec3& t) { transform(m, Eigen::Matrix3d::Identity(), t); }
inline void scale(SurfaceMesh& m, double s) { transform(m, s * Eigen::Matrix3d::Identity()); }

// Merges vertices closer than `tolerance` (m) into the first of them (in index
// order, so the result is deterministic), drops triangles that lose a corner
// and vertices no triangle uses. Returns the number of vertices removed.
int weld_vertices(SurfaceMesh& m, double tolerance);

// Removes vertices no triangle uses, renumbering the rest in order.
int remove_unused_vertices(SurfaceMesh& m);

// The closed loops where the plane y = height cuts the surface, as (x, z)
// polygons, m. Open chains (a holed mesh) are returned as they are.
using Vec2d = Eigen::Vector2d;
std::vector<std::vector<Vec2d>> slice_horizontal(const SurfaceMesh& m, double height);

// Convex hull of points in the plane (counter-clockwise) and its perimeter, m:
// a tape measure's reading around a slice.
std::vector<Vec2d> convex_hull(std::vector<Vec2d> points);
double convex_hull_perimeter(const std::vector<Vec2d>& points);
// The area a closed polygon encloses, m² (either orientation).
double loop_area(const std::vector<Vec2d>& loop);
// Whether p lies inside the closed polygon (even-odd rule).
bool point_in_polygon(const std::vector<Vec2d>& polygon, const Vec2d& p);

}  // namespace vgd::mesh
