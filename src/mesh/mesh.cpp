// Meshing a piece: options, contour preparation, boundary bookkeeping. The CGAL
// work itself is in cgal_mesher.cpp.
#include "vgd/mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "cgal_mesher.hpp"

namespace vgd::mesh {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Refinement beyond this angle bound may never end (Shewchuk: about 33.8°).
constexpr double kMaxMinAngleDeg = 33.0;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Twice the signed area of a triangle.
double area2(const Vec2& a, const Vec2& b, const Vec2& c) { return cross(b - a, c - a); }

int marker_of(std::size_t contour) {
  return contour == 0 ? kOutlineMarker : kFirstCutoutMarker + static_cast<int>(contour) - 1;
}

// Checks the options a user (or a document) can get wrong.
void check_options(const MeshOptions& o, const std::string& piece) {
  if (!(o.min_angle_deg > 0 && o.min_angle_deg <= kMaxMinAngleDeg))
    throw Error("", piece, "the minimum angle must be in (0, 33] degrees (mesh.min_angle); got " +
                               std::to_string(o.min_angle_deg));
  if (!(o.max_area_m2 >= 0 && std::isfinite(o.max_area_m2)))
    throw Error("", piece, "the maximum triangle area must be >= 0 m² (mesh.max_area)");
  if (!(o.max_edge_m >= 0 && std::isfinite(o.max_edge_m)))
    throw Error("", piece, "the maximum edge length must be >= 0 m");
  if (o.resample_contour && o.resample.segments_per_side <= 0 &&
      !(o.resample.spacing_m > 0 && std::isfinite(o.resample.spacing_m)))
    throw Error("", piece, "the contour spacing must be > 0 m (mesh.spacing)");
  if (o.resample_contour && !(o.resample.turn_angle_deg >= 0 && o.resample.turn_angle_deg <= 180))
    throw Error("", piece, "the corner angle must be in [0, 180] degrees (mesh.turn_angle)");
}

// Gives every raw boundary edge its contour, contour edge, side and marker, and
// orders them along each contour with the piece on the left. Boundary Steiner
// nodes sit on exactly one contour edge: walking from a contour vertex along the
// mesh boundary reaches the next one through them.
void attribute_boundary(PieceMesh& m, const std::vector<std::array<int, 2>>& raw) {
  std::vector<std::vector<int>> out(m.nodes.size());
  for (std::size_t e = 0; e < raw.size(); ++e) out[raw[e][0]].push_back(static_cast<int>(e));
  std::vector<char> used(raw.size(), 0);

  for (std::size_t c = 0; c < m.contours.size(); ++c) {
    const Contour& ct = m.contours[c];
    const std::size_t n = ct.points.size();
    // The piece is on the left of the outline walked CCW and of a hole walked CW.
    const bool ccw = pattern::signed_area(ct.points) > 0;
    const bool forward = (c == 0) == ccw;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = forward ? k : n - 1 - k;
      const std::size_t j = (i + 1) % n;
      const int from = m.contour_nodes[c][forward ? i : j];
      const int to = m.contour_nodes[c][forward ? j : i];
      const Vec2 p = m.nodes[from], q = m.nodes[to];
      const Vec2 d = q - p;
      const double len2 = d.squaredNorm();
      int cur = from;
      for (std::size_t steps = 0; cur != to; ++steps) {
        if (steps > raw.size()) throw std::logic_error("mesh boundary walk did not reach the next contour vertex");
        // Prefer the edge that ends the contour edge; else the one through a
        // Steiner node on it (at a pinch two boundary edges leave one node).
        int pick = -1;
        double best = std::numeric_limits<double>::infinity();
        for (int e : out[cur]) {
          if (used[e]) continue;
          const int b = raw[e][1];
          if (b == to) { pick = e; break; }
          const Vec2 r = m.nodes[b] - p;
          const double t = r.dot(d) / len2;
          const double off = std::abs(cross(d, r)) / std::sqrt(len2);
          if (t > 0 && t < 1 && off < best) best = off, pick = e;
        }
        if (pick < 0) throw std::logic_error("mesh boundary edge missing along a contour");
        used[pick] = 1;
        const int side = ct.sides.empty() ? -1 : ct.sides[i];
        m.boundary.push_back({raw[pick][0], raw[pick][1], static_cast<int>(c), static_cast<int>(i), side, marker_of(c)});
        cur = raw[pick][1];
        if (m.node_markers[cur] == kInteriorMarker) m.node_markers[cur] = marker_of(c);
      }
    }
  }
  if (std::find(used.begin(), used.end(), 0) != used.end())
    throw std::logic_error("mesh boundary edge on no contour");
}

// True when two closed polygons have crossing or touching edges (brute force with
// a bounding-box test: cutouts are small).
bool polygons_touch(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  auto seg_hit = [](const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
    if (std::max(p1.x(), p2.x()) < std::min(q1.x(), q2.x()) || std::max(q1.x(), q2.x()) < std::min(p1.x(), p2.x()) ||
        std::max(p1.y(), p2.y()) < std::min(q1.y(), q2.y()) || std::max(q1.y(), q2.y()) < std::min(p1.y(), p2.y()))
      return false;
    const double d1 = area2(q1, q2, p1), d2 = area2(q1, q2, p2);
    const double d3 = area2(p1, p2, q1), d4 = area2(p1, p2, q2);
    return ((d1 >= 0 && d2 <= 0) || (d1 <= 0 && d2 >= 0)) && ((d3 >= 0 && d4 <= 0) || (d3 <= 0 && d4 >= 0));
  };
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (seg_hit(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
  return false;
}

// Even-odd point-in-polygon test.
bool inside(const std::vector<Vec2>& poly, const Vec2& q) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

std::vector<pattern::ContourPoint> as_contour(const std::vector<Vec2>& pts) {
  std::vector<pattern::ContourPoint> c;
  c.reserve(pts.size());
  for (const Vec2& p : pts) c.push_back({p, pattern::PointKind::plain});
  return c;
}

// Mesher contour from a resampled one: points and per-edge sides.
Contour to_contour(const pattern::ResampledContour& r) {
  Contour c;
  c.points.reserve(r.points.size());
  for (const auto& p : r.points) c.points.push_back(p.p);
  c.sides = r.side;
  return c;
}

// A contour vertex closer than kTouch to a contour edge that does not end at
// it or at its neighbour (over the edge's inside, or at another vertex): the
// outline (or a cutout) touches itself there, a sliver no triangle of the
// minimum angle fits in, and Delaunay refinement would add points there
// without end. Edges sorted by their smallest x are swept as in
// pattern::is_self_intersecting: O(n log n) on real outlines.
// Below any DXF's resolution (1 µm in mm, 2.5 µm in 1/10000 in): a real outline
// that comes back within a few µm of itself (a graded sleeve of the shared
// GMH1006F18 file does) meshes.
constexpr double kTouch = 1e-7;  // m

std::optional<Vec2> touching_vertex(const std::vector<Contour>& contours) {
  struct Edge { double xmin, xmax; std::size_t c, i; };
  struct Vertex { double x; std::size_t c, i; };
  std::vector<Edge> edges;
  std::vector<Vertex> vertices;
  for (std::size_t c = 0; c < contours.size(); ++c) {
    const auto& p = contours[c].points;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec2& a = p[i];
      const Vec2& b = p[(i + 1) % p.size()];
      edges.push_back({std::min(a.x(), b.x()) - kTouch, std::max(a.x(), b.x()) + kTouch, c, i});
      vertices.push_back({a.x(), c, i});
    }
  }
  std::sort(vertices.begin(), vertices.end(), [](const Vertex& l, const Vertex& r) { return l.x < r.x; });
  for (const Edge& e : edges) {
    const auto& p = contours[e.c].points;
    const std::size_t n = p.size(), j = (e.i + 1) % n;
    const Vec2 a = p[e.i], ab = p[j] - a;
    const double len2 = ab.squaredNorm();
    auto v = std::lower_bound(vertices.begin(), vertices.end(), e.xmin,
                              [](const Vertex& l, double x) { return l.x < x; });
    for (; v != vertices.end() && v->x <= e.xmax; ++v) {
      if (v->c == e.c && (v->i == e.i || v->i == j)) continue;
      const Vec2& q = contours[v->c].points[v->i];
      const double t = len2 > 0.0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const Vec2 foot = a + t * ab;
      if ((foot - q).norm() >= kTouch) continue;
      // Next to one of the edge's ends that is q's neighbour on its contour:
      // two consecutive points closer than kTouch (graded blocks have them)
      // mesh as they are.
      auto neighbours = [&](std::size_t k) { return v->c == e.c && (v->i == (k + 1) % n || k == (v->i + 1) % n); };
      if (((foot - a).norm() < kTouch && neighbours(e.i)) || ((foot - p[j]).norm() < kTouch && neighbours(j))) continue;
      return q;
    }
  }
  return std::nullopt;
}

}  // namespace

double effective_max_area(const MeshOptions& o) {
  if (o.max_area_m2 > 0) return o.max_area_m2;
  // A boundary triangle bigger than this has an apex angle below 45°, so its
  // circumcentre lies outside the edge's diametral circle: refining it inserts an
  // interior point instead of splitting the contour edge.
  if (o.resample_contour && o.resample.segments_per_side <= 0)
    return (1.0 + std::sqrt(2.0)) / 4.0 * o.resample.spacing_m * o.resample.spacing_m;
  return 0.0;
}

PieceMesh triangulate(const std::vector<Contour>& contours, const MeshOptions& o, const std::string& piece) {
  check_options(o, piece);
  if (contours.empty()) throw Error("", piece, "nothing to mesh: no outline");
  for (const Contour& c : contours) {
    if (c.points.size() < 3) throw Error("", piece, "a contour has fewer than 3 vertices");
    VGD_ASSERT(c.sides.empty() || c.sides.size() == c.points.size(), "Contour::sides needs one entry per edge");
  }
  const double outline_area = pattern::signed_area(contours[0].points);
  if (!(outline_area > 0)) throw Error("", piece, "the outline has no area or winds clockwise");
  if (const auto q = touching_vertex(contours)) {
    char at[96];
    std::snprintf(at, sizeof at, "(%.4f, %.4f) m", q->x(), q->y());
    throw Error("", piece, std::string("the outline or a cutout touches itself at ") + at +
                               " (a point less than 0.0001 mm from another part of the outline); repair the piece");
  }

  // Refinement (CGAL).
  detail::Bounds b;
  const double s = std::sin(o.min_angle_deg * kPi / 180.0);
  b.min_sine2 = s * s;
  b.max_area = effective_max_area(o);
  b.max_edge = o.max_edge_m;
  b.split_boundary = o.split_boundary;
  b.max_nodes = o.max_nodes;
  for (std::size_t k = 0; k < o.lines.size(); ++k) {
    if (o.lines[k].size() < 2) throw Error("", piece, "line " + std::to_string(k + 1) + " has fewer than 2 points");
    for (const Vec2& p : o.lines[k]) {
      bool in = inside(contours[0].points, p);
      for (std::size_t c = 1; in && c < contours.size(); ++c) in = !inside(contours[c].points, p);
      if (!in) {
        char at[96];
        std::snprintf(at, sizeof at, "(%.4f, %.4f) m", p.x(), p.y());
        throw Error("", piece, "line " + std::to_string(k + 1) + " leaves the piece at " + at);
      }
    }
  }
  detail::RawMesh raw = detail::refine(contours, o.lines, b, piece);

  // The domain must be the outline minus the holes: holes outside it or
  // overlapping each other show up as an area mismatch.
  double polygon = std::abs(outline_area), meshed = 0.0;
  for (std::size_t c = 1; c < contours.size(); ++c) polygon -= std::abs(pattern::signed_area(contours[c].points));
  for (const auto& t : raw.triangles) meshed += 0.5 * area2(raw.nodes[t[0]], raw.nodes[t[1]], raw.nodes[t[2]]);
  if (!(std::abs(meshed - polygon) <= 1e-9 * std::abs(polygon)))
    throw Error("", piece, "the cutouts overlap each other or lie outside the outline");

  // Assemble, then attribute the boundary edges.
  PieceMesh m;
  m.piece = piece;
  m.contours = contours;
  m.nodes = std::move(raw.nodes);
  m.triangles = std::move(raw.triangles);
  m.contour_nodes = std::move(raw.contour_nodes);
  m.line_nodes = std::move(raw.line_nodes);
  m.boundary_steiner_nodes = raw.boundary_steiner_nodes;
  m.node_markers.assign(m.nodes.size(), kInteriorMarker);
  for (std::size_t c = 0; c < contours.size(); ++c)
    for (int v : m.contour_nodes[c])
      if (m.node_markers[v] == kInteriorMarker) m.node_markers[v] = marker_of(c);
  attribute_boundary(m, raw.boundary);
  return m;
}

PieceMesh mesh_piece(const pattern::Piece& piece, const MeshOptions& o, Diagnostics& diag) {
  const std::string id = piece.block.empty() ? piece.name : piece.block;
  check_options(o, id);
  if (!piece.closed) throw Error("", id, "the outline is not closed; it cannot be meshed");
  if (piece.self_intersecting) throw Error("", id, "the outline crosses itself; repair it before meshing");
  if (piece.boundary.size() < 3) throw Error("", id, "the outline has fewer than 3 vertices");
  if (pattern::signed_area(piece.boundary) <= 0) throw Error("", id, "the outline has no area or winds clockwise");

  // Outline: resampled (keeping notch vertices when asked) or as drawn.
  std::vector<Contour> contours;
  if (o.resample_contour) {
    std::vector<int> keep;
    if (o.resample.keep_notch_vertices)
      for (const auto& nt : piece.notches)
        if (nt.boundary_index >= 0 && static_cast<std::size_t>(nt.boundary_index) < piece.boundary.size())
          keep.push_back(nt.boundary_index);
    contours.push_back(to_contour(pattern::resample_contour(piece.boundary, o.resample, keep)));
  } else {
    Contour c;
    for (const auto& p : piece.boundary) c.points.push_back(p.p);
    contours.push_back(std::move(c));
  }

  // Cutouts: closed, simple, inside the outline and apart from each other, or skipped.
  for (std::size_t k = 0; k < piece.cutouts.size(); ++k) {
    const pattern::Polyline& cut = piece.cutouts[k];
    const std::string what = "cutout " + std::to_string(k + 1);
    if (!cut.closed || cut.points.size() < 3) {
      diag.warn("", id, what + " is not a closed polygon; it is not cut out of the mesh");
      continue;
    }
    Contour c = o.resample_contour ? to_contour(pattern::resample_contour(as_contour(cut.points), o.resample))
                                   : Contour{cut.points, {}, -1};
    c.cutout = static_cast<int>(k);
    bool ok = c.points.size() >= 3 && !pattern::is_self_intersecting(as_contour(c.points)) &&
              std::abs(pattern::signed_area(c.points)) > 0;
    ok = ok && inside(contours[0].points, c.points[0]) && !polygons_touch(contours[0].points, c.points);
    for (std::size_t h = 1; ok && h < contours.size(); ++h)
      ok = !polygons_touch(contours[h].points, c.points) && !inside(contours[h].points, c.points[0]) &&
           !inside(c.points, contours[h].points[0]);
    if (!ok) {
      diag.warn("", id, what + " crosses itself, the outline or another cutout, or lies outside the piece; "
                               "it is not cut out of the mesh");
      continue;
    }
    contours.push_back(std::move(c));
  }

  PieceMesh m = triangulate(contours, o, id);
  m.frame = material_frame(piece);
  return m;
}

std::vector<PieceMesh> mesh_style(const pattern::Style& style, const std::string& size, const MeshOptions& o,
                                  Diagnostics& diag) {
  std::string chosen = size;
  if (chosen.empty()) chosen = !style.sample_size.empty() ? style.sample_size : style.sizes.empty() ? "" : style.sizes[0];
  if (!size.empty() && std::find(style.sizes.begin(), style.sizes.end(), size) == style.sizes.end()) {
    std::string known;
    for (const auto& s : style.sizes) known += (known.empty() ? "" : ", ") + s;
    throw Error("", style.name, "the style has no size \"" + size + "\" (sizes: " + known + ")");
  }
  std::vector<PieceMesh> out;
  for (const pattern::Piece* p : style.pieces_of_size(chosen)) {
    const std::string id = p->block.empty() ? p->name : p->block;
    // Open and self-intersecting outlines were reported by the importer: skip them.
    if (!p->closed || p->self_intersecting) {
      diag.warn("", id, !p->closed ? "the outline is not closed; piece not meshed"
                                   : "the outline crosses itself; piece not meshed");
      continue;
    }
    try {
      out.push_back(mesh_piece(*p, o, diag));
    } catch (const Error& e) {
      Diagnostic d = e.diagnostic();
      d.severity = Severity::error;
      diag.add(std::move(d));
    }
  }
  return out;
}

// ---- material frame ---------------------------------------------------------------

MaterialFrame material_frame(const pattern::Piece& piece) {
  MaterialFrame f;
  if (!piece.grain_line) return f;
  const Vec2 d = piece.grain_line->b - piece.grain_line->a;
  if (!(d.norm() > 0)) return f;
  f.origin = piece.grain_line->a;
  f.warp = d.normalized();
  f.weft = Vec2(-f.warp.y(), f.warp.x());
  return f;
}

Vec2 to_material(const MaterialFrame& f, const Vec2& p) {
  const Vec2 r = p - f.origin;
  return Vec2(r.dot(f.warp), r.dot(f.weft));
}

std::vector<Vec2> material_coordinates(const PieceMesh& m) {
  std::vector<Vec2> out;
  out.reserve(m.nodes.size());
  for (const Vec2& p : m.nodes) out.push_back(to_material(m.frame, p));
  return out;
}

Vec2 interior_point(const std::vector<Vec2>& poly) {
  VGD_ASSERT(poly.size() >= 3, "interior_point needs a polygon");
  // A horizontal line through the middle of the widest gap between vertex heights
  // meets no vertex; the midpoint of its widest inside stretch is well inside.
  std::vector<double> ys;
  for (const Vec2& p : poly) ys.push_back(p.y());
  std::sort(ys.begin(), ys.end());
  double y = ys.front(), gap = -1;
  for (std::size_t i = 1; i < ys.size(); ++i)
    if (ys[i] - ys[i - 1] > gap) gap = ys[i] - ys[i - 1], y = 0.5 * (ys[i] + ys[i - 1]);
  std::vector<double> xs;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > y) != (b.y() > y)) xs.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
  }
  std::sort(xs.begin(), xs.end());
  Vec2 best(xs.empty() ? poly[0].x() : xs[0], y);
  double width = -1;
  for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
    if (xs[i + 1] - xs[i] > width) width = xs[i + 1] - xs[i], best = Vec2(0.5 * (xs[i] + xs[i + 1]), y);
  return best;
}

}  // namespace vgd::mesh
