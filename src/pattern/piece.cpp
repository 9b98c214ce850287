#include "vgd/pattern/piece.hpp"

#include <algorithm>
#include <cmath>

namespace vgd::pattern {

std::vector<std::string> Style::piece_names() const {
  std::vector<std::string> names;
  for (const auto& p : pieces)
    if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
  return names;
}

std::vector<const Piece*> Style::pieces_of_size(const std::string& s) const {
  std::vector<const Piece*> out;
  for (const auto& p : pieces)
    if (p.size == s) out.push_back(&p);
  return out;
}

namespace {
template <class Get>
double shoelace(std::size_t n, Get get) {
  // Twice the signed area, accumulated relative to the first vertex to limit
  // cancellation when the piece sits far from the origin.
  if (n < 3) return 0.0;
  const Vec2 o = get(0);
  double a = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec2 p = get(i) - o, q = get(i + 1) - o;
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * a;
}

// Orientation of (a, b, c): >0 left turn, <0 right turn, 0 collinear.
double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

bool segments_intersect(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const double d1 = orient(q1, q2, p1), d2 = orient(q1, q2, p2);
  const double d3 = orient(p1, p2, q1), d4 = orient(p1, p2, q2);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  if (d1 == 0 && on_segment(q1, q2, p1)) return true;
  if (d2 == 0 && on_segment(q1, q2, p2)) return true;
  if (d3 == 0 && on_segment(p1, p2, q1)) return true;
  if (d4 == 0 && on_segment(p1, p2, q2)) return true;
  return false;
}
}  // namespace

double signed_area(const std::vector<ContourPoint>& o) {
  return shoelace(o.size(), [&](std::size_t i) { return o[i].p; });
}

double signed_area(const std::vector<Vec2>& o) {
  return shoelace(o.size(), [&](std::size_t i) { return o[i]; });
}

double perimeter(const std::vector<ContourPoint>& o) {
  double len = 0.0;
  for (std::size_t i = 0; i < o.size(); ++i) len += (o[(i + 1) % o.size()].p - o[i].p).norm();
  return len;
}

double grain_angle_deg(const Piece& piece) {
  if (!piece.grain_line) return 0.0;
  const Vec2 d = piece.grain_line->b - piece.grain_line->a;
  if (d.squaredNorm() == 0.0) return 0.0;
  double a = std::atan2(d.y(), d.x()) * 180.0 / M_PI;
  if (a <= -180.0) a += 360.0;
  return a;
}

bool is_self_intersecting(const std::vector<ContourPoint>& o) {
  const std::size_t n = o.size();
  if (n < 4) return false;
  // Sort edges by their min x and sweep: O(n log n + k) on real outlines,
  // which matters for dense ASTM curves with thousands of vertices.
  struct Edge { double xmin, xmax; std::size_t i; };
  std::vector<Edge> edges(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = o[i].p;
    const Vec2& b = o[(i + 1) % n].p;
    edges[i] = {std::min(a.x(), b.x()), std::max(a.x(), b.x()), i};
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& l, const Edge& r) { return l.xmin < r.xmin; });
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = edges[k].i;
    for (std::size_t m = k + 1; m < n && edges[m].xmin <= edges[k].xmax; ++m) {
      const std::size_t j = edges[m].i;
      // Adjacent edges share a vertex by construction; skip them.
      if (j == (i + 1) % n || i == (j + 1) % n) continue;
      if (segments_intersect(o[i].p, o[(i + 1) % n].p, o[j].p, o[(j + 1) % n].p)) return true;
    }
  }
  return false;
}

}  // namespace vgd::pattern
