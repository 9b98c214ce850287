#pragma once
// Meshing a closed surface given implicitly: { p : f(p) = 0 }, f < 0 inside.
//
// Used for the parametric mannequin (scene/mannequin.hpp), whose body is a
// smooth signed-distance function. The mesher is CGAL's Mesh_3 surface
// Delaunay refinement (Boissonnat & Oudot) with the manifold criterion: the
// result is a closed, oriented 2-manifold whose vertices lie on the surface
// (to relative_error of the box), with near-equilateral triangles (every
// angle ≥ angle_deg except where the manifold criterion forced a facet).
// Deterministic: the random seed is fixed, the run sequential.
#include <functional>
#include <vector>

#include "vgd/mesh/surface.hpp"

namespace vgd::mesh {

struct ImplicitSurfaceCriteria {
  double facet_size = 0.02;         // m, upper bound on a facet's surface Delaunay ball radius
  double facet_distance = 0.001;    // m, upper bound on the facet-to-surface distance
  double angle_deg = 25.0;          // lower bound on facet angles (≤ 30 for termination)
  double relative_error = 1e-7;     // surface point accuracy, relative to the bounding-sphere radius
};

// Meshes the zero level set of f inside `box` (f must be > 0 on and outside
// the box's bounding sphere). `inside` are optional points where f < 0, one per
// thin part (a wrist, an ankle): the meshing starts with a surface point near
// each, so no part is missed. Triangles are counter-clockwise seen from outside.
// Throws vgd::Error when the result is empty.
SurfaceMesh mesh_implicit_surface(const std::function<double(const Vec3&)>& f, const Box3& box,
                                  const ImplicitSurfaceCriteria& criteria = {},
                                  const std::vector<Vec3>& inside = {});

}  // namespace vgd::mesh
