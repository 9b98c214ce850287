// CGAL Mesh_3 surface meshing of an implicit function (implicit_surface.hpp).
// The second (and last) CGAL translation unit of the mesh stage: slow to compile,
// so nothing else lives here.
//
// Only facet criteria are given: the tetrahedra are never refined, so the cost
// is the surface Delaunay refinement alone. The manifold criterion makes the
// restricted Delaunay surface a closed 2-manifold; perturbation and exudation
// (which only improve tetrahedra) are switched off.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Random.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/refine_mesh_3.h>

#include <map>

#include "vgd/core/diagnostics.hpp"
#include "vgd/mesh/implicit_surface.hpp"

namespace vgd::mesh {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Function = std::function<K::FT(const Point&)>;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
namespace params = CGAL::parameters;

Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

SurfaceMesh mesh_implicit_surface(const std::function<double(const Vec3&)>& f, const Box3& box,
                                  const ImplicitSurfaceCriteria& criteria, const std::vector<Vec3>& inside) {
  VGD_ASSERT(!box.empty(), "mesh_implicit_surface needs a non-empty box");
  const Vec3 c = box.centre();
  const double r = 0.5 * box.size().norm() * 1.05;
  Function fn = [&f](const Point& p) { return f(to_vec(p)); };
  CGAL::Random rng(0);  // fixed seed: same function, same mesh
  Domain domain = Domain::create_implicit_mesh_domain(
      fn, K::Sphere_3(Point(c.x(), c.y(), c.z()), r * r), params::relative_error_bound = criteria.relative_error, params::p_rng = &rng);
  Criteria crit(params::facet_angle = criteria.angle_deg, params::facet_size = criteria.facet_size,
                params::facet_distance = criteria.facet_distance,
                params::facet_topology = CGAL::FACET_VERTICES_ON_SAME_SURFACE_PATCH);

  // Initial points: CGAL's random ones, plus one surface point per given inside
  // point (on the segment from it straight out along +Z to the sphere), so thin
  // parts are part of the first sample and cannot be missed.
  C3t3 c3t3;
  std::vector<std::pair<Point, Domain::Index>> initial;
  domain.construct_initial_points_object()(std::back_inserter(initial), 12);
  for (const Vec3& p : inside) {
    for (const Vec3& dir : {Vec3(Vec3::UnitZ()), Vec3(Vec3::UnitX()), Vec3(-Vec3::UnitX()), Vec3(-Vec3::UnitZ())}) {
      const Vec3 q = p + dir * (2.0 * r);
      const K::Segment_3 seg(Point(p.x(), p.y(), p.z()), Point(q.x(), q.y(), q.z()));
      if (const auto patch = domain.do_intersect_surface_object()(seg)) {
        const Point hit = std::get<0>(domain.construct_intersection_object()(seg));
        initial.emplace_back(hit, domain.index_from_surface_patch_index(*patch));
        break;
      }
    }
  }
  auto cwp = c3t3.triangulation().geom_traits().construct_weighted_point_3_object();
  for (const auto& [p, index] : initial) {
    const auto v = c3t3.triangulation().insert(cwp(p));
    if (v != Tr::Vertex_handle()) {
      c3t3.set_dimension(v, 2);
      c3t3.set_index(v, index);
    }
  }
  CGAL::refine_mesh_3(c3t3, domain, crit, params::manifold(), params::no_perturb(), params::no_exude());

  // Facets of the complex -> indexed triangles. The vertex of the facet's cell
  // opposite the facet tells the side: a facet is turned so that its normal
  // points away from the cell that lies inside (f < 0 at its circumcentre's
  // label), i.e. counter-clockwise seen from outside.
  SurfaceMesh out;
  std::map<Tr::Vertex_handle, int> index;
  const auto& tr = c3t3.triangulation();
  auto vertex_id = [&](Tr::Vertex_handle v) {
    const auto [it, fresh] = index.emplace(v, out.num_vertices());
    if (fresh) out.vertices.push_back(to_vec(tr.point(v).point()));
    return it->second;
  };
  for (auto it = c3t3.facets_in_complex_begin(); it != c3t3.facets_in_complex_end(); ++it) {
    auto cell = it->first;
    int i = it->second;
    // Use the cell that is inside the body (subdomain index 1), else its mirror's outside.
    if (!c3t3.is_in_complex(cell)) {
      const auto mirror = tr.mirror_facet(*it);
      if (c3t3.is_in_complex(mirror.first)) cell = mirror.first, i = mirror.second;
    }
    std::array<int, 3> t{vertex_id(cell->vertex((i + 1) & 3)), vertex_id(cell->vertex((i + 2) & 3)),
                         vertex_id(cell->vertex((i + 3) & 3))};
    const Vec3 &a = out.vertices[t[0]], &b = out.vertices[t[1]], &cc = out.vertices[t[2]];
    const Vec3 n = (b - a).cross(cc - a);
    Vec3 outward;
    if (c3t3.is_in_complex(cell) && !tr.is_infinite(cell->vertex(i))) {
      outward = (a + b + cc) / 3.0 - to_vec(tr.point(cell->vertex(i)).point());  // away from the inside cell
    } else {
      // No labelled cell (should not happen): the function's gradient decides.
      const Vec3 m = (a + b + cc) / 3.0;
      const double h = 1e-5;
      outward = Vec3(f(m + h * Vec3::UnitX()) - f(m - h * Vec3::UnitX()), f(m + h * Vec3::UnitY()) - f(m - h * Vec3::UnitY()),
                     f(m + h * Vec3::UnitZ()) - f(m - h * Vec3::UnitZ()));
    }
    if (n.dot(outward) < 0) std::swap(t[1], t[2]);
    out.triangles.push_back(t);
  }
  if (out.triangles.empty())
    throw Error("", "implicit surface", "the surface meshing produced no triangles (is f < 0 anywhere inside the box?)");
  return out;
}

}  // namespace vgd::mesh
