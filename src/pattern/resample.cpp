#include "vgd/pattern/resample.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vgd/core/diagnostics.hpp"

namespace vgd::pattern {

namespace {

constexpr double kPi = 3.14159265358979323846;
// More points than this on one contour means the spacing is absurd for the piece.
constexpr double kMaxPoints = 1e7;

// Direction change at b between edges a->b and b->c, radians in [0, pi].
double turn_angle(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = b - a, v = c - b;
  return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
}

// Index of the point of `pts` nearest to q (first one on ties).
int nearest(const std::vector<ContourPoint>& pts, const Vec2& q) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double d = (pts[i].p - q).squaredNorm();
    if (d < best_d) best_d = d, best = static_cast<int>(i);
  }
  return best;
}

}  // namespace

ResampledContour resample_contour(const std::vector<ContourPoint>& contour, const ResampleOptions& o,
                                  const std::vector<int>& keep) {
  VGD_ASSERT(o.segments_per_side > 0 || (std::isfinite(o.spacing_m) && o.spacing_m > 0),
             "resample_contour needs spacing_m > 0 or segments_per_side > 0");
  VGD_ASSERT(o.turn_angle_deg >= 0 && o.turn_angle_deg <= 180, "turn_angle_deg must be in [0, 180]");
  const std::size_t n_in = contour.size();
  std::vector<char> keep_in(n_in, 0);
  for (int k : keep) {
    VGD_ASSERT(k >= 0 && static_cast<std::size_t>(k) < n_in, "keep index outside the contour");
    keep_in[k] = 1;
  }

  // Merge exact duplicate neighbours; a merged vertex keeps the strongest marking.
  std::vector<ContourPoint> pts;
  std::vector<int> from;     // input index of each distinct point
  std::vector<char> forced;  // must end a side (turn point or caller's keep)
  for (std::size_t i = 0; i < n_in; ++i) {
    const bool force = keep_in[i] || contour[i].kind == PointKind::turn;
    if (!pts.empty() && contour[i].p == pts.back().p) {
      if (contour[i].kind == PointKind::turn) pts.back().kind = PointKind::turn;
      forced.back() = forced.back() || force;
      continue;
    }
    pts.push_back(contour[i]);
    from.push_back(static_cast<int>(i));
    forced.push_back(force);
  }
  while (pts.size() > 1 && pts.back().p == pts.front().p) {
    if (pts.back().kind == PointKind::turn) pts.front().kind = PointKind::turn;
    forced.front() = forced.front() || forced.back();
    pts.pop_back(), from.pop_back(), forced.pop_back();
  }
  const std::size_t n = pts.size();

  // Too few points to have sides: hand back what there is.
  ResampledContour out;
  if (n < 3) {
    out.points = pts;
    out.side.assign(n, 0);
    out.source = from;
    out.side_count = 1;
    return out;
  }

  // Side ends: forced vertices and vertices turning by more than the threshold.
  const double threshold = o.turn_angle_deg * kPi / 180.0;
  std::vector<std::size_t> corners;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = pts[(i + n - 1) % n].p;
    const Vec2& c = pts[(i + 1) % n].p;
    if (forced[i] || turn_angle(a, pts[i].p, c) > threshold) corners.push_back(i);
  }
  // A smooth closed curve is one side that starts and ends at vertex 0.
  if (corners.empty()) corners.push_back(0);
  const std::size_t m = corners.size();

  // Arc length of each side (a side runs from corners[k] to corners[k+1], cyclically).
  auto side_steps = [&](std::size_t k) {
    const std::size_t a = corners[k], b = corners[(k + 1) % m];
    return m == 1 ? n : (b + n - a) % n;
  };
  std::vector<double> length(m, 0.0);
  std::vector<bool> curved(m, false);
  for (std::size_t k = 0; k < m; ++k) {
    for (std::size_t s = 0; s < side_steps(k); ++s) {
      const std::size_t i = (corners[k] + s) % n;
      length[k] += (pts[(i + 1) % n].p - pts[i].p).norm();
      if (s > 0 && pts[i].kind == PointKind::curve) curved[k] = true;
    }
  }

  // Segments per side: ceil(L / spacing) keeps every gap at or below the spacing.
  std::vector<long long> segs(m, 1);
  double total = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    const double want = o.segments_per_side > 0 ? o.segments_per_side
                                                : std::ceil(length[k] / o.spacing_m - 1e-9);
    total += want;
    if (!(total <= kMaxPoints))
      throw Error("", "", "resampling would put more than 10 million points on one outline; "
                          "the spacing is too small for this piece");
    segs[k] = std::max(1LL, static_cast<long long>(want));
  }
  // A polygon needs three points: lengthen the longest side's share if needed.
  const std::size_t longest = std::max_element(length.begin(), length.end()) - length.begin();
  long long count = 0;
  for (long long s : segs) count += s;
  if (count < 3) segs[longest] += 3 - count;

  // Walk each side: its start corner, then points at equal arc-length steps.
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t start = corners[k];
    const std::size_t end = corners[(k + 1) % m];
    out.points.push_back(pts[start]);
    out.side.push_back(static_cast<int>(k));
    out.source.push_back(from[start]);
    const PointKind new_kind = curved[k] ? PointKind::curve : PointKind::plain;
    std::size_t step = 0;  // current input edge: pts[start + step] -> next
    double edge_begin = 0.0;
    for (long long j = 1; j < segs[k]; ++j) {
      const double t = length[k] * static_cast<double>(j) / static_cast<double>(segs[k]);
      // Advance to the input edge holding arc length t.
      double edge_len = (pts[(start + step + 1) % n].p - pts[(start + step) % n].p).norm();
      while (edge_begin + edge_len < t && step + 1 < side_steps(k)) {
        edge_begin += edge_len;
        ++step;
        edge_len = (pts[(start + step + 1) % n].p - pts[(start + step) % n].p).norm();
      }
      const Vec2& a = pts[(start + step) % n].p;
      const Vec2& b = pts[(start + step + 1) % n].p;
      const double f = std::clamp((t - edge_begin) / edge_len, 0.0, 1.0);
      const Vec2 p = a + f * (b - a);
      // Rounding on a microscopic side could repeat a neighbour: never emit duplicates.
      if (p == out.points.back().p || p == pts[end].p) continue;
      out.points.push_back({p, new_kind});
      out.side.push_back(static_cast<int>(k));
      out.source.push_back(-1);
    }
  }
  out.side_count = static_cast<int>(m);
  return out;
}

std::vector<Vec2> resample_polygon(const std::vector<Vec2>& polygon, const ResampleOptions& o) {
  std::vector<ContourPoint> c;
  c.reserve(polygon.size());
  for (const Vec2& p : polygon) c.push_back({p, PointKind::plain});
  const ResampledContour r = resample_contour(c, o);
  std::vector<Vec2> out;
  out.reserve(r.points.size());
  for (const auto& q : r.points) out.push_back(q.p);
  return out;
}

Piece resample_piece(const Piece& piece, const ResampleOptions& o) {
  Piece out = piece;

  // Boundary, keeping the notches' vertices as side ends when asked.
  std::vector<int> keep;
  if (o.keep_notch_vertices)
    for (const Notch& nt : piece.notches)
      if (nt.boundary_index >= 0 && static_cast<std::size_t>(nt.boundary_index) < piece.boundary.size())
        keep.push_back(nt.boundary_index);
  out.boundary = resample_contour(piece.boundary, o, keep).points;

  // Notches point at the new vertex nearest their old one (the same vertex when kept).
  for (Notch& nt : out.notches) {
    if (nt.boundary_index < 0 || static_cast<std::size_t>(nt.boundary_index) >= piece.boundary.size()) continue;
    nt.boundary_index = nearest(out.boundary, piece.boundary[nt.boundary_index].p);
  }

  // Closed cutouts are holes in the mesh: resample them the same way.
  for (Polyline& c : out.cutouts)
    if (c.closed && c.points.size() >= 3) c.points = resample_polygon(c.points, o);
  return out;
}

}  // namespace vgd::pattern
