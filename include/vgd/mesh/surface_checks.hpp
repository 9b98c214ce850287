#pragma once
// Exact geometric measurements on 3-D triangle surfaces, for tests and
// certificates (docs/collisions.md, "Tolerances"): how deep points are inside a
// closed body, and whether a cloth surface passes through itself. Exact
// predicates (CGAL, private to src/mesh/cgal_surface_checks.cpp).
#include <array>
#include <vector>

#include "vgd/mesh/surface.hpp"

namespace vgd::mesh {

// Per point: its distance (m) to the body's surface if it lies strictly inside
// the closed body, 0 if outside or on it. The body must be closed and
// consistently oriented (a SurfaceMesh collider).
std::vector<double> penetration_depths(const SurfaceMesh& body, const std::vector<Vec3>& points);

// The number of pairs of triangles that share no vertex and intersect
// (touching counts). Pairs sharing a vertex or an edge are neighbours of a
// mesh, not crossings, and are not tested. Box intersection (CGAL
// box_intersection_d) then exact triangle–triangle predicates.
int count_triangle_intersections(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles);
// The same pairs, each (smaller index, larger), sorted.
std::vector<std::array<int, 2>> find_triangle_intersections(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles);

}  // namespace vgd::mesh
