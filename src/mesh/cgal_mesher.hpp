#pragma once
// Internal seam between the mesh stage and CGAL. cgal_mesher.cpp is the only
// translation unit that includes CGAL (it is slow to compile, and CGAL stays a
// private dependency of vgd_mesh); everything else works on these plain arrays.
#include <array>
#include <string>
#include <vector>

#include "vgd/mesh/mesh.hpp"

namespace vgd::mesh::detail {

// What the refinement produced, before boundary edges are attributed to contours.
struct RawMesh {
  std::vector<Vec2> nodes;                      // contour vertices first, then boundary Steiner, then interior
  std::vector<std::array<int, 3>> triangles;    // counter-clockwise
  std::vector<std::array<int, 2>> boundary;     // directed, piece on the left, in no particular order
  std::vector<std::vector<int>> contour_nodes;  // [c][i]: node of contours[c].points[i]
  std::vector<std::vector<int>> line_nodes;     // [k][i]: node of lines[k][i]
  int boundary_steiner_nodes = 0;
};

// Refinement bounds, already validated and converted.
struct Bounds {
  double min_sine2 = 0.125;  // squared sine of the smallest angle wanted (0.125 ≈ 20.7°)
  double max_area = 0.0;     // m², 0 = none
  double max_edge = 0.0;     // m, 0 = none
  bool split_boundary = true;
  std::size_t max_nodes = 2'000'000;
};

// Constrained Delaunay triangulation of the contours (contours[0] the outline,
// the rest holes), domain marked by nesting depth across the contours' edges,
// then Delaunay refinement.
// Throws vgd::Error naming `piece` when constraints cross (with the place) or the
// node guard trips.
// Open polylines `lines` inside the domain are constraints too (not borders
// of it): every point a node, no triangle across them.
RawMesh refine(const std::vector<Contour>& contours, const std::vector<std::vector<Vec2>>& lines,
               const Bounds& bounds, const std::string& piece);

}  // namespace vgd::mesh::detail
