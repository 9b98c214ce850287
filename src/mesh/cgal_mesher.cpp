// The only CGAL translation unit of vgd: constrained Delaunay triangulation and
// Delaunay refinement (CGAL 2D Conforming Triangulations and Meshes, Mesh_2).
//
// Kernel: exact predicates, inexact constructions. Input points are doubles and
// stay bit for bit; only new points (circumcentres, edge midpoints) are rounded.
// Refinement (Shewchuk 1997; CGAL's Delaunay_mesher_2 with clusters for small
// input angles) ends with every triangle's smallest angle >= the bound — proven for
// bounds up to 20.7° — except near input angles smaller than the bound.
#include "cgal_mesher.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Unique_hash_map.h>

#include <algorithm>
#include <cstdio>
#include <list>
#include <set>

#include "vgd/core/diagnostics.hpp"

namespace vgd::mesh::detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct VertexInfo {
  int node = -1;  // node index once numbered; -1 not yet, -2 used by the domain but unnumbered
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K, CGAL::Delaunay_mesh_vertex_base_2<K>>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact_predicates_tag: crossing constraints are split (not fatal), which lets us
// detect them and name the place instead of failing inside CGAL.
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using VH = CDT::Vertex_handle;
using FH = CDT::Face_handle;
using Point = CDT::Point;

// Mesh_2 criteria: a face is bad when its smallest angle is below the bound, or
// "imperatively bad" when it is too big (longest edge or area). Same priority
// order as CGAL's Delaunay_mesh_size_criteria_2: biggest first, then worst shaped.
class Criteria {
 public:
  explicit Criteria(const Bounds& b) : b_(b) {}

  struct Quality {
    double sine2 = 0.0;  // squared sine of the smallest angle
    double size = 0.0;   // max(edge² / max_edge², area / max_area): above 1 is too big
    bool operator<(const Quality& q) const {
      if (size > 1) return q.size > 1 ? size > q.size : true;
      if (q.size > 1) return false;
      return sine2 < q.sine2;
    }
  };

  class Is_bad {
   public:
    explicit Is_bad(const Bounds& b) : b_(b) {}
    CGAL::Mesh_2::Face_badness operator()(const Quality& q) const {
      if (q.size > 1) return CGAL::Mesh_2::IMPERATIVELY_BAD;
      return q.sine2 < b_.min_sine2 ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }
    CGAL::Mesh_2::Face_badness operator()(const FH& fh, Quality& q) const {
      const Point& pa = fh->vertex(0)->point();
      const Point& pb = fh->vertex(1)->point();
      const Point& pc = fh->vertex(2)->point();
      const double a = CGAL::squared_distance(pb, pc), b = CGAL::squared_distance(pc, pa),
                   c = CGAL::squared_distance(pa, pb);
      // The smallest angle is opposite the shortest edge: sin = 2·area / (product of the other two).
      const double lo = std::min({a, b, c}), hi = std::max({a, b, c});
      const double mid = a + b + c - lo - hi;
      const double area = 0.5 * ((pb.x() - pa.x()) * (pc.y() - pa.y()) - (pb.y() - pa.y()) * (pc.x() - pa.x()));
      q.sine2 = 4 * area * area / (hi * mid);
      q.size = 0.0;
      if (b_.max_edge > 0) q.size = std::max(q.size, hi / (b_.max_edge * b_.max_edge));
      if (b_.max_area > 0) q.size = std::max(q.size, area / b_.max_area);
      return (*this)(q);
    }

   private:
    Bounds b_;
  };

  Is_bad is_bad_object() const { return Is_bad(b_); }

 private:
  Bounds b_;
};

// Marks faces by nesting depth: outside 0, inside the outline 1, inside a hole 2...
// Odd depths are the piece (CGAL's polygon-with-holes recipe; needs no seed point).
// Only the contours' edges (`border(edge)`) change the depth; a line's do not.
template <class Border>
void mark_domain(CDT& cdt, Border&& is_border) {
  CGAL::Unique_hash_map<FH, int> depth(-1);
  std::list<CDT::Edge> border;
  auto flood = [&](FH start, int level) {
    if (depth[start] != -1) return;
    std::list<FH> queue{start};
    while (!queue.empty()) {
      FH f = queue.front();
      queue.pop_front();
      if (depth[f] != -1) continue;
      depth[f] = level;
      for (int i = 0; i < 3; ++i) {
        FH n = f->neighbor(i);
        if (depth[n] != -1) continue;
        if (cdt.is_constrained(CDT::Edge(f, i)) && is_border(CDT::Edge(f, i)))
          border.push_back(CDT::Edge(f, i));
        else
          queue.push_back(n);
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    const CDT::Edge e = border.front();
    border.pop_front();
    FH n = e.first->neighbor(e.second);
    if (depth[n] == -1) flood(n, depth[e.first] + 1);
  }
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
    f->set_in_domain(!cdt.is_infinite(f) && depth[f] % 2 == 1);
}

// Runs one mesher to completion, with the node guard.
template <class Mesher>
void run(Mesher& mesher, const CDT& cdt, const Bounds& b, const std::string& piece) {
  mesher.init(true);  // true: keep our domain marks
  std::size_t steps = 0;
  while (mesher.step_by_step_refine_mesh()) {
    if (++steps % 1024 == 0 && cdt.number_of_vertices() > b.max_nodes)
      throw Error("", piece,
                  "meshing stopped at " + std::to_string(b.max_nodes) +
                      " nodes: the size bounds are too small for this piece (mesh.max_area, mesh.spacing)");
  }
}

std::string where(const Point& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.4f, %.4f) m", p.x(), p.y());
  return buf;
}

}  // namespace

RawMesh refine(const std::vector<Contour>& contours, const std::vector<std::vector<Vec2>>& lines, const Bounds& b,
               const std::string& piece) {
  CDT cdt;
  RawMesh out;

  // Contour vertices, numbered in contour order; a point met twice is one node.
  int next = 0;
  VH hint;
  std::vector<std::vector<VH>> handles(contours.size());
  out.contour_nodes.resize(contours.size());
  for (std::size_t c = 0; c < contours.size(); ++c) {
    for (const Vec2& p : contours[c].points) {
      VH v = hint == VH() ? cdt.insert(Point(p.x(), p.y())) : cdt.insert(Point(p.x(), p.y()), hint->face());
      if (v->info().node < 0) {
        v->info().node = next++;
        out.nodes.push_back(p);
      }
      handles[c].push_back(v);
      out.contour_nodes[c].push_back(v->info().node);
      hint = v;
    }
  }

  // Every contour edge is a constraint, and a border of the domain.
  std::set<std::pair<int, int>> contour_edges;  // node pairs, smaller first
  for (const auto& h : handles)
    for (std::size_t i = 0; i < h.size(); ++i) {
      const VH a = h[i], b2 = h[(i + 1) % h.size()];
      if (a == b2) throw Error("", piece, "a contour repeats the vertex at " + where(a->point()));
      cdt.insert_constraint(a, b2);
      contour_edges.insert(std::minmax(a->info().node, b2->info().node));
    }

  // The lines' points, then their edges as constraints.
  out.line_nodes.resize(lines.size());
  for (std::size_t k = 0; k < lines.size(); ++k) {
    std::vector<VH> line;
    for (const Vec2& p : lines[k]) {
      VH v = cdt.insert(Point(p.x(), p.y()), hint->face());
      if (v->info().node < 0) {
        v->info().node = next++;
        out.nodes.push_back(p);
      }
      line.push_back(v);
      out.line_nodes[k].push_back(v->info().node);
      hint = v;
    }
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      if (line[i] == line[i + 1]) throw Error("", piece, "a line repeats the point at " + where(line[i]->point()));
      cdt.insert_constraint(line[i], line[i + 1]);
    }
  }

  // Crossing constraints add their crossing points as vertices: refuse and say where.
  if (cdt.number_of_vertices() != static_cast<std::size_t>(next))
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
      if (v->info().node < 0)
        throw Error("", piece, std::string(lines.empty() ? "the outline or a cutout" : "the outline, a cutout or a line") +
                                   " crosses itself or another contour near " + where(v->point()) +
                                   "; repair the piece or use a smaller mesh.spacing");

  // Domain, then refinement. The no-edge-refinement mesher never splits a contour
  // edge; it drops bad triangles whose fix would need that.
  mark_domain(cdt, [&](const CDT::Edge& e) {
    const int a = e.first->vertex(CDT::ccw(e.second))->info().node, c = e.first->vertex(CDT::cw(e.second))->info().node;
    return contour_edges.count(std::minmax(a, c)) > 0;
  });
  const Criteria criteria(b);
  if (b.split_boundary) {
    CGAL::Delaunay_mesher_2<CDT, Criteria> mesher(cdt, criteria);
    run(mesher, cdt, b, piece);
  } else {
    CGAL::Delaunay_mesher_no_edge_refinement_2<CDT, Criteria> mesher(cdt, criteria);
    run(mesher, cdt, b, piece);
  }

  // Vertices the piece uses but that are not contour vertices: mark them.
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->is_in_domain())
      for (int i = 0; i < 3; ++i)
        if (f->vertex(i)->info().node == -1) f->vertex(i)->info().node = -2;

  // Number them: Steiner points on contour edges first, then interior points
  // (those on a line among them: the domain lies on both sides of it).
  const auto on_border = [&](VH v) {
    auto e = cdt.incident_edges(v), end = e;
    do {
      if (cdt.is_constrained(*e)) {
        const FH f = e->first, n = f->neighbor(e->second);
        const bool in_f = !cdt.is_infinite(f) && f->is_in_domain(), in_n = !cdt.is_infinite(n) && n->is_in_domain();
        if (in_f != in_n) return true;
      }
    } while (++e != end);
    return false;
  };
  std::vector<VH> inner;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    if (v->info().node != -2) continue;
    if (cdt.are_there_incident_constraints(v) && (lines.empty() || on_border(v))) {
      v->info().node = next++;
      out.nodes.push_back(Vec2(v->point().x(), v->point().y()));
      ++out.boundary_steiner_nodes;
    } else {
      inner.push_back(v);
    }
  }
  for (VH v : inner) {
    v->info().node = next++;
    out.nodes.push_back(Vec2(v->point().x(), v->point().y()));
  }

  // Triangles (CGAL faces are counter-clockwise) and the domain's border edges:
  // the edge opposite vertex i runs ccw(i) -> cw(i) with the face on its left.
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    out.triangles.push_back({f->vertex(0)->info().node, f->vertex(1)->info().node, f->vertex(2)->info().node});
    for (int i = 0; i < 3; ++i) {
      const FH n = f->neighbor(i);
      if (cdt.is_infinite(n) || !n->is_in_domain())
        out.boundary.push_back({f->vertex(CDT::ccw(i))->info().node, f->vertex(CDT::cw(i))->info().node});
    }
  }
  return out;
}

}  // namespace vgd::mesh::detail
