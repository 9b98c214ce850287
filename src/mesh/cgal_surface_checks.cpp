// Exact surface measurements (include/vgd/mesh/surface_checks.hpp): the second
// CGAL translation unit of vgd, kept apart from the mesher so that each
// compiles once.
#include <algorithm>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "vgd/mesh/surface_checks.hpp"

namespace vgd::mesh {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

Point pt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

std::vector<double> penetration_depths(const SurfaceMesh& body, const std::vector<Vec3>& points) {
  Mesh m;
  std::vector<Mesh::Vertex_index> vi;
  vi.reserve(body.vertices.size());
  for (const auto& v : body.vertices) vi.push_back(m.add_vertex(pt(v)));
  for (const auto& t : body.triangles)
    if (m.add_face(vi[t[0]], vi[t[1]], vi[t[2]]) == Mesh::null_face())
      throw std::invalid_argument("penetration_depths: the body is not a valid oriented surface");
  Tree tree(faces(m).first, faces(m).second, m);
  tree.accelerate_distance_queries();
  const CGAL::Side_of_triangle_mesh<Mesh, K> side(tree);
  std::vector<double> out(points.size(), 0.0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point p = pt(points[i]);
    if (side(p) == CGAL::ON_BOUNDED_SIDE) out[i] = std::sqrt(CGAL::to_double(tree.squared_distance(p)));
  }
  return out;
}

std::vector<std::array<int, 2>> find_triangle_intersections(const std::vector<Vec3>& vertices,
                                                            const std::vector<std::array<int, 3>>& triangles) {
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, std::size_t,
                                                          CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<K::Triangle_3> tri;
  std::vector<Box> boxes;
  tri.reserve(triangles.size());
  boxes.reserve(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tr = triangles[t];
    tri.emplace_back(pt(vertices[tr[0]]), pt(vertices[tr[1]]), pt(vertices[tr[2]]));
    boxes.emplace_back(tri.back().bbox(), t);
  }
  std::vector<std::array<int, 2>> out;
  auto report = [&](const Box& a, const Box& b) {
    const auto &ta = triangles[a.handle()], &tb = triangles[b.handle()];
    for (int i : ta)
      for (int j : tb)
        if (i == j) return;  // neighbours
    if (CGAL::do_intersect(tri[a.handle()], tri[b.handle()]))
      out.push_back({static_cast<int>(std::min(a.handle(), b.handle())), static_cast<int>(std::max(a.handle(), b.handle()))});
  };
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), report);
  std::sort(out.begin(), out.end());
  return out;
}

int count_triangle_intersections(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  return static_cast<int>(find_triangle_intersections(vertices, triangles).size());
}

}  // namespace vgd::mesh
