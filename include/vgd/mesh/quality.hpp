#pragma once
// Quality and validity of a piece mesh: what tests assert and what the engine
// checks before it trusts a mesh. Pure arithmetic on the PieceMesh, no CGAL.
//
// Units: degrees, m². Orientation and degeneracy use the exact sign of the
// floating-point cross product relative to the triangle's size (tolerance
// 1e-12 of the longest edge squared).
#include <cstddef>
#include <string>
#include <vector>

#include "vgd/mesh/mesh.hpp"

namespace vgd::mesh {

struct QualityReport {
  std::size_t nodes = 0;
  std::size_t triangles = 0;
  std::size_t boundary_edges = 0;

  // Angles, degrees.
  double min_angle_deg = 0.0;        // smallest angle of any triangle
  double max_angle_deg = 0.0;        // largest angle of any triangle
  // Smallest angle among triangles touching no sharp contour corner: the number
  // Delaunay refinement guarantees (180 when every triangle touches one).
  double min_angle_away_from_sharp_deg = 0.0;
  int sharp_corners = 0;             // contour vertices whose angle inside the piece < sharp_corner_deg

  // Areas, m².
  double min_area_m2 = 0.0;
  double max_area_m2 = 0.0;
  double mesh_area_m2 = 0.0;         // sum of the triangle areas
  double polygon_area_m2 = 0.0;      // |outline| minus |cutouts| (shoelace)
  double area_rel_error = 0.0;       // |mesh − polygon| / polygon

  // Contour and boundary.
  int missing_contour_vertices = 0;  // contour vertices with no node at exactly their position
  int boundary_steiner_nodes = 0;    // boundary nodes that are not contour vertices

  // Validity counters (all 0 for a valid mesh).
  int bad_indices = 0;               // triangle or edge indices outside the node list
  int degenerate_triangles = 0;      // zero area (collinear corners or a repeated node)
  int clockwise_triangles = 0;
  int non_manifold_edges = 0;        // used by more than two triangles, or twice the same way
  int boundary_mismatches = 0;       // edges used once that are not in PieceMesh::boundary, or vice versa
  int duplicate_nodes = 0;           // nodes at exactly the position of an earlier node
  int unused_nodes = 0;              // nodes no triangle uses

  // One sentence per failed check (validity, contour vertices, area within 1e-9).
  std::vector<std::string> problems;
  bool valid() const { return problems.empty(); }
};

// Measures `mesh`. Contour corners whose angle inside the piece is below
// sharp_corner_deg (normally the min-angle bound used for meshing) are counted,
// and triangles touching them are left out of min_angle_away_from_sharp_deg.
QualityReport check_mesh(const PieceMesh& mesh, double sharp_corner_deg = 20.7);

// Angle inside the piece at each vertex of contour c of the mesh, degrees in (0, 360).
std::vector<double> interior_angles_deg(const PieceMesh& mesh, std::size_t c);

}  // namespace vgd::mesh
