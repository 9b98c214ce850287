#include "vgd/pattern/contour.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vgd::pattern {

namespace {

double poly_length(const std::vector<Vec2>& p) {
  double l = 0;
  for (std::size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

// Same points in the same order. A part repeated in the opposite direction is
// not a duplicate: real outlines go out and back along a slit (a zero-width
// spike), which remove_spikes() deals with after chaining.
bool same_part(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if ((a[i] - b[i]).norm() > tol) return false;
  return true;
}

int rank(PointKind k) { return k == PointKind::turn ? 2 : k == PointKind::curve ? 1 : 0; }

Vec2 reflect(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = (b - a).normalized();
  const Vec2 v = p - a;
  return a + 2.0 * v.dot(d) * d - v;
}

double distance_to_line(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len == 0) return (p - a).norm();
  return std::abs(d.x() * (p.y() - a.y()) - d.y() * (p.x() - a.x())) / len;
}

// Proper or touching intersection of segments p1p2 and q1q2; writes the point.
bool intersect(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2, Vec2& x) {
  const Vec2 r = p2 - p1, s = q2 - q1;
  const double den = r.x() * s.y() - r.y() * s.x();
  if (den == 0) return false;  // parallel: collinear overlaps are left to the caller's check
  const Vec2 qp = q1 - p1;
  const double t = (qp.x() * s.y() - qp.y() * s.x()) / den;
  const double u = (qp.x() * r.y() - qp.y() * r.x()) / den;
  if (t < 0 || t > 1 || u < 0 || u > 1) return false;
  x = p1 + t * r;
  return true;
}

}  // namespace

ChainResult chain_parts(std::vector<std::vector<Vec2>> parts, const ChainOptions& opts) {
  ChainResult res;
  // Drop empty parts and exact duplicates (some exporters write a stretch twice).
  std::vector<std::vector<Vec2>> kept;
  for (auto& p : parts) {
    if (p.size() < 2) continue;
    bool dup = false;
    for (const auto& k : kept)
      if (same_part(p, k, opts.join_tol_m)) { dup = true; break; }
    if (dup) ++res.parts_duplicate;
    else kept.push_back(std::move(p));
  }
  if (kept.empty()) return res;

  // Seed with the longest part.
  std::size_t seed = 0;
  for (std::size_t i = 1; i < kept.size(); ++i)
    if (poly_length(kept[i]) > poly_length(kept[seed])) seed = i;
  std::vector<bool> used(kept.size(), false);
  used[seed] = true;
  res.parts_used = 1;
  std::vector<Vec2>& out = res.outline;
  out = kept[seed];

  for (;;) {
    const Vec2 end = out.back();
    const double d_close = (end - out.front()).norm();
    // Nearest unused part end to the chain's end.
    std::size_t best = kept.size();
    bool best_reversed = false;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < kept.size(); ++i) {
      if (used[i]) continue;
      const double ds = (kept[i].front() - end).norm(), de = (kept[i].back() - end).norm();
      if (ds < best_d) { best_d = ds; best = i; best_reversed = false; }
      if (de < best_d) { best_d = de; best = i; best_reversed = true; }
    }
    const bool can_join = best < kept.size() &&
                          (best_d <= opts.join_tol_m || (best_d <= opts.repair_gap_m && best_d < d_close));
    if (!can_join) break;
    auto part = kept[best];
    if (best_reversed) std::reverse(part.begin(), part.end());
    if (best_d > opts.join_tol_m) {
      ++res.joins_bridged;
      res.largest_bridge_m = std::max(res.largest_bridge_m, best_d);
      out.insert(out.end(), part.begin(), part.end());  // keep both ends: the gap becomes an edge
    } else {
      out.insert(out.end(), part.begin() + 1, part.end());
    }
    used[best] = true;
    ++res.parts_used;
  }

  res.parts_unused = static_cast<int>(kept.size()) - res.parts_used;
  res.closing_gap_m = (out.back() - out.front()).norm();
  if (res.closing_gap_m <= opts.join_tol_m) {
    res.closed = true;
    if (out.size() > 1) out.pop_back();  // the repeated first vertex
  } else if (res.closing_gap_m <= opts.repair_gap_m) {
    res.closed = true;  // a tiny gap: the closing edge bridges it
  }
  return res;
}

int remove_duplicate_vertices(std::vector<ContourPoint>& o, double tol) {
  if (o.empty()) return 0;
  const std::size_t before = o.size();
  std::vector<ContourPoint> out;
  out.reserve(o.size());
  for (const auto& c : o) {
    if (!out.empty() && (c.p - out.back().p).norm() <= tol) {
      if (rank(c.kind) > rank(out.back().kind)) out.back().kind = c.kind;
      continue;
    }
    out.push_back(c);
  }
  while (out.size() > 1 && (out.back().p - out.front().p).norm() <= tol) {
    if (rank(out.back().kind) > rank(out.front().kind)) out.front().kind = out.back().kind;
    out.pop_back();
  }
  o = std::move(out);
  return static_cast<int>(before - o.size());
}

int remove_spikes(std::vector<ContourPoint>& o, double tol) {
  int removed = 0;
  bool changed = true;
  while (changed && o.size() > 3) {
    changed = false;
    const std::size_t n = o.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t prev = (i + n - 1) % n, next = (i + 1) % n;
      if ((o[prev].p - o[next].p).norm() > tol) continue;
      // i is the tip of an out-and-back spike: drop the tip and the return vertex.
      const std::size_t hi = std::max(i, next), lo = std::min(i, next);
      o.erase(o.begin() + static_cast<std::ptrdiff_t>(hi));
      o.erase(o.begin() + static_cast<std::ptrdiff_t>(lo));
      ++removed;
      changed = true;
      break;
    }
  }
  return removed;
}

bool make_counter_clockwise(std::vector<ContourPoint>& o) {
  if (signed_area(o) >= 0) return false;
  std::reverse(o.begin(), o.end());
  return true;
}

Nearest nearest_vertex(const std::vector<ContourPoint>& o, const Vec2& p) {
  Nearest n{-1, std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < o.size(); ++i) {
    const double d = (o[i].p - p).norm();
    if (d < n.distance) n = {static_cast<int>(i), d};
  }
  return n;
}

NearestEdge nearest_edge(const std::vector<ContourPoint>& o, const Vec2& p) {
  NearestEdge best;
  best.distance = std::numeric_limits<double>::infinity();
  const std::size_t n = o.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = o[i].p;
    const Vec2& b = o[(i + 1) % n].p;
    const Vec2 d = b - a;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
    const Vec2 q = a + t * d;
    const double dist = (p - q).norm();
    if (dist < best.distance) best = {static_cast<int>(i), t, dist, q};
  }
  return best;
}

bool unfold_about_mirror_line(Piece& piece, double tol) {
  if (!piece.mirror_line || piece.boundary.size() < 3) return false;
  const Vec2 a = piece.mirror_line->a, b = piece.mirror_line->b;
  if ((b - a).norm() <= tol) return false;
  const auto na = nearest_vertex(piece.boundary, a), nb = nearest_vertex(piece.boundary, b);
  if (na.index < 0 || nb.index < 0 || na.distance > tol || nb.distance > tol || na.index == nb.index)
    return false;
  const int n = static_cast<int>(piece.boundary.size());
  // The two ways around the outline between the fold ends; the fold side is the
  // one whose vertices all lie on the mirror line.
  auto path = [&](int from, int to) {
    std::vector<ContourPoint> p;
    for (int i = from;; i = (i + 1) % n) {
      p.push_back(piece.boundary[i]);
      if (i == to) break;
    }
    return p;
  };
  auto off_line = [&](const std::vector<ContourPoint>& p) {
    double m = 0;
    for (const auto& c : p) m = std::max(m, distance_to_line(c.p, a, b));
    return m;
  };
  auto p1 = path(na.index, nb.index), p2 = path(nb.index, na.index);
  const bool first = off_line(p1) >= off_line(p2);
  const auto& half = first ? p1 : p2;
  if (off_line(first ? p2 : p1) > tol) return false;  // neither side is the fold itself

  std::vector<ContourPoint> full = half;
  for (int k = static_cast<int>(half.size()) - 2; k >= 1; --k)
    full.push_back({reflect(half[k].p, a, b), half[k].kind});
  make_counter_clockwise(full);
  piece.boundary = std::move(full);

  // Mirror the markings that lie off the fold.
  const std::size_t nn = piece.notches.size();
  for (std::size_t i = 0; i < nn; ++i) {
    Notch m = piece.notches[i];
    if (distance_to_line(m.position, a, b) <= tol) continue;
    const Vec2 dir(std::cos(m.angle_deg * M_PI / 180), std::sin(m.angle_deg * M_PI / 180));
    const Vec2 rdir = reflect(m.position + dir, a, b) - reflect(m.position, a, b);
    m.position = reflect(m.position, a, b);
    m.angle_deg = std::atan2(rdir.y(), rdir.x()) * 180 / M_PI;
    m.boundary_index = -1;
    piece.notches.push_back(m);
  }
  auto mirror_lines = [&](std::vector<Polyline>& lines) {
    const std::size_t count = lines.size();
    for (std::size_t i = 0; i < count; ++i) {
      Polyline l = lines[i];
      double off = 0;
      for (auto& p : l.points) off = std::max(off, distance_to_line(p, a, b));
      if (off <= tol) continue;  // a line along the fold stays single
      for (auto& p : l.points) p = reflect(p, a, b);
      lines.push_back(std::move(l));
    }
  };
  mirror_lines(piece.internal_lines);
  mirror_lines(piece.sew_lines);
  mirror_lines(piece.cutouts);
  const std::size_t nh = piece.drill_holes.size();
  for (std::size_t i = 0; i < nh; ++i)
    if (distance_to_line(piece.drill_holes[i], a, b) > tol)
      piece.drill_holes.push_back(reflect(piece.drill_holes[i], a, b));
  piece.quantity_flipped = 0;
  piece.mirror_line.reset();
  return true;
}

double width_at(const std::vector<ContourPoint>& o, const Vec2& up, double v) {
  const Vec2 across(up.y(), -up.x());
  double lo = 1e300, hi = -1e300;
  const std::size_t n = o.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = o[i].p, &b = o[(i + 1) % n].p;
    const double va = a.dot(up), vb = b.dot(up);
    if ((va - v) * (vb - v) > 0 || va == vb) continue;
    const double u = (a + (v - va) / (vb - va) * (b - a)).dot(across);
    lo = std::min(lo, u), hi = std::max(hi, u);
  }
  return hi > lo ? hi - lo : 0.0;
}

bool point_in_outline(const std::vector<ContourPoint>& o, const Vec2& p) {
  bool in = false;
  const std::size_t n = o.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 &a = o[i].p, &b = o[j].p;
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

bool mirror_symmetric(const std::vector<ContourPoint>& o, const Vec2& up, double tol) {
  const Vec2 across(up.y(), -up.x());
  double u0 = 1e300, u1 = -1e300;
  for (const auto& q : o) u0 = std::min(u0, q.p.dot(across)), u1 = std::max(u1, q.p.dot(across));
  const double mid = 0.5 * (u0 + u1);
  return std::all_of(o.begin(), o.end(), [&](const ContourPoint& q) {
    return nearest_edge(o, q.p - 2.0 * (q.p.dot(across) - mid) * across).distance <= tol;
  });
}

std::optional<Allowance> sew_on_sew_line(Piece& piece, double min_m, double max_m) {
  const Polyline* line = nullptr;
  for (const auto& l : piece.sew_lines)
    if (l.closed && l.points.size() >= 3) {
      if (line) return std::nullopt;  // several: which one is the piece's is not said
      line = &l;
    }
  if (!line || piece.boundary.size() < 3) return std::nullopt;
  // The allowance at the sew line's vertices and at points along its edges
  // (a corner is nearer the cut line than the middle of the hem beside it).
  Allowance a{1e300, 0.0};
  const std::size_t m = line->points.size();
  for (std::size_t i = 0; i < m; ++i)
    for (int k = 0; k < 4; ++k) {
      const Vec2 p = line->points[i] + (line->points[(i + 1) % m] - line->points[i]) * (k / 4.0);
      const double d = nearest_edge(piece.boundary, p).distance;
      if (!point_in_outline(piece.boundary, p) || d < min_m || d > max_m) return std::nullopt;
      a.min = std::min(a.min, d), a.max = std::max(a.max, d);
    }
  std::vector<ContourPoint> outline;
  for (const Vec2& p : line->points)
    if (outline.empty() || (p - outline.back().p).norm() > 1e-9) outline.push_back({p, PointKind::plain});
  while (outline.size() > 1 && (outline.front().p - outline.back().p).norm() <= 1e-9) outline.pop_back();
  if (outline.size() < 3) return std::nullopt;
  make_counter_clockwise(outline);
  // The corners the file marked on the cut line (carried to graded sizes, so
  // that stretch k is the same stretch in every size) go to the sew line's
  // nearest vertex; a cut line with none gets corners from the sew line's shape.
  bool marked = false;
  for (const auto& c : piece.boundary)
    if (c.kind == PointKind::turn) {
      const Nearest v = nearest_vertex(outline, c.p);
      if (v.index >= 0 && v.distance <= 1.5 * max_m) outline[v.index].kind = PointKind::turn, marked = true;
    }
  if (!marked) mark_corners(outline);
  piece.boundary = std::move(outline);
  for (auto& n : piece.notches) {
    const NearestEdge e = nearest_edge(piece.boundary, n.position);
    n.position = e.point;
    n.boundary_index = nearest_vertex(piece.boundary, n.position).index;
  }
  piece.sew_lines.clear();
  return a;
}

int remove_small_self_loops(std::vector<ContourPoint>& o, double max_loop_fraction) {
  int removed = 0;
  const double total = std::abs(signed_area(o));
  for (int guard = 0; guard < 1000; ++guard) {
    const int n = static_cast<int>(o.size());
    bool changed = false;
    for (int i = 0; i < n && !changed; ++i) {
      for (int j = i + 2; j < n && !changed; ++j) {
        if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
        Vec2 x;
        if (!intersect(o[i].p, o[(i + 1) % n].p, o[j].p, o[(j + 1) % n].p, x)) continue;
        // Loop A: vertices i+1..j; loop B: the rest. Cut off the smaller one.
        std::vector<ContourPoint> loop_a(o.begin() + i + 1, o.begin() + j + 1);
        loop_a.push_back({x, PointKind::turn});
        std::vector<ContourPoint> loop_b(o.begin() + j + 1, o.end());
        loop_b.insert(loop_b.end(), o.begin(), o.begin() + i + 1);
        loop_b.push_back({x, PointKind::turn});
        const double area_a = std::abs(signed_area(loop_a)), area_b = std::abs(signed_area(loop_b));
        const bool cut_a = area_a <= area_b;
        if (std::min(area_a, area_b) > max_loop_fraction * total) return removed;  // not a small loop
        o = cut_a ? loop_b : loop_a;
        remove_duplicate_vertices(o);
        ++removed;
        changed = true;
      }
    }
    if (!changed) break;
  }
  make_counter_clockwise(o);
  return removed;
}

}  // namespace vgd::pattern

namespace vgd::pattern {

int mark_corners(std::vector<ContourPoint>& outline, double min_angle_deg, double window_m) {
  const int n = static_cast<int>(outline.size());
  if (n < 3) return 0;
  // The unit direction from the point `window_m` of arc before vertex i to
  // vertex i (way = -1), or from vertex i to the point that far after it (+1).
  auto direction = [&](int i, int way) -> Vec2 {
    double left = window_m;
    Vec2 at = outline[i].p;
    for (int step = 0, k = i; step < n; ++step) {
      const int next = (k + way + n) % n;
      const Vec2 e = outline[next].p - at;
      const double len = e.norm();
      if (len >= left) {
        at += e * (left / len);
        break;
      }
      left -= len;
      at = outline[next].p;
      k = next;
    }
    const Vec2 d = way > 0 ? Vec2(at - outline[i].p) : Vec2(outline[i].p - at);
    const double len = d.norm();
    return len > 0 ? Vec2(d / len) : Vec2::Zero();
  };
  std::vector<double> turn(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const Vec2 a = direction(i, -1), b = direction(i, +1);
    turn[i] = std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b))) * 180.0 / M_PI;
  }
  // Arc distance between vertices, to keep one corner per window.
  std::vector<double> s(n + 1, 0.0);
  for (int i = 0; i < n; ++i) s[i + 1] = s[i] + (outline[(i + 1) % n].p - outline[i].p).norm();
  const double total = s[n];
  auto apart = [&](int i, int j) {
    const double d = std::abs(s[i] - s[j]);
    return std::min(d, total - d);
  };
  int marked = 0;
  for (int i = 0; i < n; ++i) {
    if (turn[i] < min_angle_deg) continue;
    bool peak = true;
    for (int j = 0; j < n && peak; ++j)
      if (j != i && apart(i, j) <= window_m && (turn[j] > turn[i] || (turn[j] == turn[i] && j < i))) peak = false;
    if (!peak) continue;
    if (outline[i].kind != PointKind::turn) ++marked;
    outline[i].kind = PointKind::turn;
  }
  return marked;
}

EndWidths end_widths(const std::vector<ContourPoint>& outline, const Vec2& up) {
  if (outline.empty()) return {};
  const Vec2 across(up.y(), -up.x());
  double lo = 1e300, hi = -1e300;
  for (const auto& c : outline) lo = std::min(lo, c.p.dot(up)), hi = std::max(hi, c.p.dot(up));
  double b0 = 1e300, b1 = -1e300, t0 = 1e300, t1 = -1e300;
  for (const auto& c : outline) {
    const double u = c.p.dot(across), v = c.p.dot(up);
    if (v < lo + 0.15 * (hi - lo)) b0 = std::min(b0, u), b1 = std::max(b1, u);
    if (v > hi - 0.15 * (hi - lo)) t0 = std::min(t0, u), t1 = std::max(t1, u);
  }
  return {b1 - b0, t1 - t0, hi - lo};
}

bool wider_at_top(const std::vector<ContourPoint>& outline, const Vec2& up) {
  const EndWidths w = end_widths(outline, up);
  return w.top > w.bottom;
}

namespace {

// The centripetal Catmull-Rom segment from p1 to p2 (neighbours p0, p3) at
// u in [0, 1] (Barry and Goldman's pyramid, knots spaced by the square root
// of the chord lengths: no cusps or self-loops within a segment).
Vec2 catmull_rom(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double u) {
  auto knot = [](const Vec2& a, const Vec2& b) { return std::max(std::sqrt((b - a).norm()), 1e-9); };
  const double t0 = 0, t1 = t0 + knot(p0, p1), t2 = t1 + knot(p1, p2), t3 = t2 + knot(p2, p3);
  const double t = t1 + u * (t2 - t1);
  const Vec2 a1 = ((t1 - t) * p0 + (t - t0) * p1) / (t1 - t0);
  const Vec2 a2 = ((t2 - t) * p1 + (t - t1) * p2) / (t2 - t1);
  const Vec2 a3 = ((t3 - t) * p2 + (t - t2) * p3) / (t3 - t2);
  const Vec2 b1 = ((t2 - t) * a1 + (t - t0) * a2) / (t2 - t0);
  const Vec2 b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1);
  return ((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1);
}

}  // namespace

std::vector<ContourPoint> smooth_through(const std::vector<ContourPoint>& points, bool closed, double spacing) {
  const std::size_t n = points.size();
  if (n < 2 || !(spacing > 0)) return points;
  std::vector<ContourPoint> out;
  const std::size_t segments = closed ? n : n - 1;
  // A point the curve passes through smoothly: a curve point that has
  // neighbours on both sides (an open line's ends are corners).
  auto smooth = [&](std::size_t i) { return points[i].kind == PointKind::curve && (closed || (i > 0 && i + 1 < n)); };
  for (std::size_t s = 0; s < segments; ++s) {
    const std::size_t i = s, j = (s + 1) % n;
    out.push_back(points[i]);
    if (!smooth(i) && !smooth(j)) continue;  // corner to corner: straight
    const Vec2 &p1 = points[i].p, &p2 = points[j].p;
    // At a corner the curve heads for its neighbour: the neighbour beyond it mirrored.
    const Vec2 p0 = smooth(i) ? points[(i + n - 1) % n].p : Vec2(2 * p1 - p2);
    const Vec2 p3 = smooth(j) ? points[(j + 1) % n].p : Vec2(2 * p2 - p1);
    // As many samples as keep every piece within the spacing.
    std::vector<Vec2> run;
    for (int k = std::max(1, static_cast<int>(std::ceil((p2 - p1).norm() / spacing)));; k *= 2) {
      run.clear();
      for (int m = 1; m < k; ++m) run.push_back(catmull_rom(p0, p1, p2, p3, static_cast<double>(m) / k));
      double longest = 0;
      Vec2 prev = p1;
      for (const auto& q : run) longest = std::max(longest, (q - prev).norm()), prev = q;
      longest = std::max(longest, (p2 - prev).norm());
      if (longest <= spacing || k > 4096) break;
    }
    for (const auto& q : run) out.push_back({q, PointKind::curve});
  }
  if (!closed) out.push_back(points.back());
  return out;
}

}  // namespace vgd::pattern
