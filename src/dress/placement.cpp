// Wrapping pattern pieces around body segments (placement.hpp, docs/placement.md).
#include "vgd/dress/placement.hpp"

#include <algorithm>
#include <cmath>

#include "vgd/core/diagnostics.hpp"

namespace vgd::dress {

using body::Avatar;
using body::BodySegment;
using body::SegmentRing;

namespace {

// The ring at s, linearly interpolated and clamped (as body::ring_at; kept
// here so placement depends on the Avatar data only).
SegmentRing ring_local(const BodySegment& seg, double s) {
  const auto& r = seg.rings;
  if (s <= r.front().s) return r.front();
  if (s >= r.back().s) return r.back();
  for (std::size_t i = 1; i < r.size(); ++i)
    if (s <= r[i].s) {
      const double t = r[i].s > r[i - 1].s ? (s - r[i - 1].s) / (r[i].s - r[i - 1].s) : 0.0;
      SegmentRing q;
      q.s = s;
      q.centre = (1 - t) * r[i - 1].centre + t * r[i].centre;
      q.half_width = (1 - t) * r[i - 1].half_width + t * r[i].half_width;
      q.half_depth = (1 - t) * r[i - 1].half_depth + t * r[i].half_depth;
      return q;
    }
  return r.back();
}

// The offset curve of the ellipse (a along e1, b along e2) at distance c, sampled by
// angle; cumulative arc length for the inverse map.
struct OffsetCurve {
  double a = 0, b = 0, c = 0;
  std::vector<double> theta, arc;  // arc[k]: length from theta = 0 to theta[k]
  double perimeter = 0;

  static constexpr int kSamples = 4096;

  Eigen::Vector2d at(double t) const {
    const Eigen::Vector2d e(a * std::cos(t), b * std::sin(t));
    const Eigen::Vector2d n = Eigen::Vector2d(std::cos(t) / a, std::sin(t) / b).normalized();
    return e + c * n;
  }
  void build() {
    theta.resize(kSamples + 1);
    arc.resize(kSamples + 1);
    Eigen::Vector2d prev = at(0);
    arc[0] = 0;
    for (int k = 1; k <= kSamples; ++k) {
      theta[k] = 2 * M_PI * k / kSamples;
      const Eigen::Vector2d q = at(theta[k]);
      arc[k] = arc[k - 1] + (q - prev).norm();
      prev = q;
    }
    perimeter = arc.back();
  }
  // The point at arc length s (any real; wraps), by linear interpolation of the samples.
  Eigen::Vector2d point_at_arc(double s) const {
    s = std::fmod(s, perimeter);
    if (s < 0) s += perimeter;
    const auto it = std::upper_bound(arc.begin(), arc.end(), s);
    const std::size_t k = std::min<std::size_t>(std::max<std::ptrdiff_t>(it - arc.begin(), 1), arc.size() - 1);
    const double t = (s - arc[k - 1]) / (arc[k] - arc[k - 1]);
    return (1 - t) * at(theta[k - 1]) + t * at(theta[k]);
  }
  double arc_at_theta(double t) const {
    t = std::fmod(t, 2 * M_PI);
    if (t < 0) t += 2 * M_PI;
    const double k = t / (2 * M_PI) * kSamples;
    const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(k), kSamples - 1);
    return arc[i] + (k - i) * (arc[i + 1] - arc[i]);
  }
};

// m: how far from a leg's axis the surface beyond its ankle counts as its foot.
constexpr double kFootReach = 0.30;

bool trunk(const std::string& segment) { return segment == "neck" || segment == "torso" || segment == "hips"; }

}  // namespace

PiecePlacement place_piece(const std::vector<pattern::Vec2>& nodes, const xvc::Arrangement& ar, const Avatar& avatar,
                           const std::vector<Underlayer>& under, double nest) {
  const BodySegment* seg = nullptr;
  for (const auto& s : avatar.segments)
    if (s.name == ar.segment) seg = &s;
  const std::string entity = "segment " + ar.segment;
  if (!seg) throw Error(avatar.source, entity, "the avatar has no segment '" + ar.segment + "' to place a piece on");
  if (seg->rings.empty()) throw Error(avatar.source, entity, "the segment has no cross-sections (rings)");
  const bool limb = ar.segment.find("arm") != std::string::npos || ar.segment.find("leg") != std::string::npos;
  const Vec3 axis = seg->axis.normalized();
  // The pattern's up: towards the head along neck/torso/hips, towards the joint on limbs.
  const Vec3 up = limb ? Vec3(-axis) : axis;
  const Vec3 e1 = (seg->front - seg->front.dot(axis) * axis).normalized();  // front
  const Vec3 e2 = up.cross(e1).normalized();  // +u direction at the front: the body's left for an upright `up`

  // s of the reference point.
  double s_ref = ar.height;
  if (!limb) {
    if (std::abs(axis.y()) < 0.1)
      throw Error(avatar.source, entity, "the segment's axis is nearly horizontal: a height cannot place a piece on it");
    s_ref = (ar.height - seg->start.y()) / axis.y();
  }
  // Pattern coordinates relative to the reference point, turned upright, mirrored if flipped.
  const double ang = ar.angle_deg * M_PI / 180.0, ca = std::cos(ang), sa = std::sin(ang);
  std::vector<Eigen::Vector2d> uv(nodes.size());
  double umin = 1e300, umax = -1e300, smin = 1e300, smax = -1e300;
  const double sign_s = up.dot(axis);  // +1 torso, -1 limbs
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const pattern::Vec2 d = nodes[i] - pattern::Vec2(ar.x, ar.y);
    double u = ca * d.x() - sa * d.y();
    const double v = sa * d.x() + ca * d.y();
    if (ar.flip) u = -u;
    uv[i] = {u, v};
    umin = std::min(umin, u);
    umax = std::max(umax, u);
    const double s = s_ref + sign_s * v;
    smin = std::min(smin, s);
    smax = std::max(smax, s);
  }
  if (nodes.empty()) smin = smax = s_ref;

  // A leg's piece may reach past the leg's last ring (the ankle): trousers cut
  // to the floor. There it goes round the foot, not through it: the body's
  // surface beyond that ring, nearer this leg's axis than any other leg's,
  // bounds the envelope as cloth under a piece does.
  std::vector<Vec3> foot;
  if (limb && ar.segment.find("leg") != std::string::npos && smax > seg->rings.back().s) {
    const auto off_axis = [](const BodySegment& g, const Vec3& p) {
      const Vec3 d = p - g.start;
      return (d - d.dot(g.axis.normalized()) * g.axis.normalized()).norm();
    };
    for (const auto& v : avatar.surface.vertices) {
      if ((v - seg->start).dot(axis) <= seg->rings.back().s) continue;
      const double r = off_axis(*seg, v);
      if (r > kFootReach) continue;
      bool mine = true;
      for (const auto& other : avatar.segments)
        if (&other != seg && other.name.find("leg") != std::string::npos && off_axis(other, v) < r) mine = false;
      if (mine) foot.push_back(v);
    }
  }

  // Envelope of the rings over [smin, smax] around the reference ring's centre line.
  // The reference ring is clamped to the segment's ends; the reference point is
  // not: a piece may reach above the torso's top ring (a bodice's shoulders).
  const SegmentRing ref = ring_local(*seg, s_ref);
  const Vec3 axis_point = ref.centre + (s_ref - ref.s) * axis;
  // The envelope (semi-axes along e1 = depth and e2 = width) of the rings
  // whose heights fall in [lo, hi], around the reference centre line.
  auto envelope = [&](double lo, double hi) {
    double a = 0, b = 0;
    auto take = [&](const SegmentRing& r) {
      Vec3 d = r.centre - axis_point;
      d -= d.dot(axis) * axis;
      b = std::max(b, r.half_width + std::abs(d.dot(e2)));
      a = std::max(a, r.half_depth + std::abs(d.dot(e1)));
    };
    take(ring_local(*seg, lo));
    take(ring_local(*seg, hi));
    for (const auto& r : seg->rings)
      if (r.s > lo && r.s < hi) take(r);
    // A piece on the trunk may reach past its segment's ends (a waistband above
    // the hips, a bodice's hem over them): the rings of the other trunk
    // segments at those heights bound it too, or it would start inside them
    // (and inside a skirt worn under it).
    if (!limb && !seg->rings.empty())
      for (const auto& other : avatar.segments) {
        if (&other == seg || !trunk(other.name)) continue;
        for (const auto& r : other.rings) {
          const double s = (r.centre - seg->start).dot(axis);
          const bool outside = s > seg->rings.back().s || s < seg->rings.front().s;
          if (outside && s > lo && s < hi) take(r);
        }
      }
    // The foot: each point inside the ellipse grows it along one semi-axis, or
    // both keeping its shape, whichever leaves the shorter perimeter.
    a = std::max(a, 1e-3), b = std::max(b, 1e-3);
    for (const auto& p : foot) {
      const double s = (p - seg->start).dot(axis);
      if (s < lo || s > hi) continue;
      Vec3 d = p - axis_point;
      d -= d.dot(axis) * axis;
      const double x = std::abs(d.dot(e1)), y = std::abs(d.dot(e2));
      const double q = (x / a) * (x / a) + (y / b) * (y / b);
      if (q <= 1) continue;
      std::pair<double, double> best{a * std::sqrt(q), b * std::sqrt(q)};
      if (y < 0.9 * b) {
        const double na = x / std::sqrt(1 - (y / b) * (y / b));
        if (na + b < best.first + best.second) best = {na, b};
      }
      if (x < 0.9 * a) {
        const double nb = y / std::sqrt(1 - (x / a) * (x / a));
        if (a + nb < best.first + best.second) best = {a, nb};
      }
      a = best.first, b = best.second;
    }
    // Cloth under the piece: the ellipse grows (keeping its shape) until its
    // offset curve at the clearance passes each point at the gap or more.
    const double inset = std::max(0.0, ar.clearance) - kUnderlayerGap;
    for (const auto& layer : under) {
      if (layer.segment != ar.segment && !(trunk(layer.segment) && trunk(ar.segment))) continue;
      for (const auto& p : layer.points) {
        const double s = (p - seg->start).dot(axis);
        if (s < lo || s > hi) continue;
        Vec3 d = p - axis_point;
        d -= d.dot(axis) * axis;
        const double r = d.norm();
        if (r <= inset || r < 1e-9) continue;
        const double k = (r - inset) / r;  // the point pulled in by what the clearance adds
        const double x = k * d.dot(e1) / a, y = k * d.dot(e2) / b, q = x * x + y * y;
        if (q > 1) a *= std::sqrt(q), b *= std::sqrt(q);
      }
    }
    return std::pair{a, b};
  };
  const auto [a, b] = envelope(smin, smax);

  OffsetCurve curve;
  curve.a = a;
  curve.b = b;
  curve.c = std::max(0.0, ar.clearance);
  curve.build();
  const double width = nodes.empty() ? 0 : umax - umin;
  const double gap = 0.02;
  // A half of a trouser leg (front or back of a leg) goes half way round at most,
  // so the front and back halves meet at the leg's sides instead of overlapping
  // (a back half is cut wider than the leg's half for the seat).
  const bool half_leg = ar.segment.find("leg") != std::string::npos && (ar.side == "front" || ar.side == "back");
  const bool whole_leg = limb && ar.segment.find("leg") != std::string::npos && !half_leg;
  const auto room = [&] { return half_leg ? 0.5 * curve.perimeter - 0.5 * gap : curve.perimeter - gap; };
  if (width > room()) {
    // Wider than the body: grow the clearance until the piece fits once around.
    double lo = curve.c, hi = curve.c + width;
    for (int i = 0; i < 60; ++i) {
      curve.c = 0.5 * (lo + hi);
      curve.build();
      (room() < width ? lo : hi) = curve.c;
    }
    curve.c = hi;
    curve.build();
  }
  // Direction of the side: angle in the (e1, e2) plane.
  double theta0 = 0;
  if (ar.side == "back") theta0 = M_PI;
  else if (ar.side == "left") theta0 = M_PI / 2;
  else if (ar.side == "right") theta0 = -M_PI / 2;
  theta0 += ar.around_deg * M_PI / 180.0;
  // e2 = up × front: on the trunk the body's left. On a limb it is front × axis,
  // which turns with the limb: a left arm's outside (+X hanging down) is its
  // top in a T-pose (+Y), so a sleeve's cap stays on the shoulder's side from
  // A- to T-pose and beyond; no swap where the limb crosses the horizontal.
  // A half piece on the trunk (front or back, at most half way round) follows
  // the body's taper (below); a wider one is wrapped on the one curve.
  // A half leg follows its leg the same way (round the foot below the ankle,
  // round the calf above it), however much wider than the leg it is cut. So
  // does a whole leg (leggings, tights: one piece round the leg), once round
  // at each height: on one cylinder as wide as its top, a leggings' ankle
  // covered a third of it, the inseam pulled its edges together across the
  // rest, and in sizes 38 and 40 the lower legs crumpled through the body.
  const bool follow = (half_leg || whole_leg ||
                       (!limb && (ar.side == "front" || ar.side == "back") && width <= 0.5 * curve.perimeter)) &&
                      !nodes.empty();
  if (!follow && nest > 0.0 && ar.side == "back") {
    curve.c += nest;
    curve.build();
  }
  const double arc0 = curve.arc_at_theta(theta0);

  // A half piece that follows the body's taper: each height gets the offset curve of the rings near it,
  // with the clearance grown where the piece is wider there than a quarter of
  // that curve on each side of its centre, so front and back meet at the
  // sides, not overlap. One cylinder at the largest ring of the whole piece put
  // a bodice's sides (as wide as the shoulders) into the A-posed arms below
  // the armpits, and the sleeves were sewn round them. Vertical lengths
  // stretch by √(1 + (dr/ds)²) where the radius r changes along the axis.
  constexpr double kBin = 0.01, kWindow = 0.03;  // m: height step of the curves, rings looked at around each
  std::vector<OffsetCurve> bins;
  std::vector<double> bin_arc0;
  double clearance_used = curve.c;
  if (follow) {
    const int nb = static_cast<int>(std::ceil((smax - smin) / kBin)) + 1;
    std::vector<double> half(nb, 0.0);  // the piece's largest |u| near each bin
    std::vector<double> u_lo(nb, 0.0), u_hi(nb, 0.0);  // its u range there (a whole leg)
    for (std::size_t i = 0; i < uv.size(); ++i) {
      const double s = s_ref + sign_s * uv[i].y();
      const int lo = std::max(0, static_cast<int>(std::floor((s - smin - 2 * kBin) / kBin)));
      const int hi = std::min(nb - 1, static_cast<int>(std::ceil((s - smin + 2 * kBin) / kBin)));
      for (int k = lo; k <= hi; ++k) {
        half[k] = std::max(half[k], std::abs(uv[i].x()));
        u_lo[k] = std::min(u_lo[k], uv[i].x());
        u_hi[k] = std::max(u_hi[k], uv[i].x());
      }
    }
    std::vector<std::pair<double, double>> ab(nb);
    for (int k = 0; k < nb; ++k) ab[k] = envelope(smin + k * kBin - kWindow, smin + k * kBin + kWindow);
    // Rings no steeper than kSlope up and down (a cone round each bin's ring):
    // a skirt's top under a T-shirt would otherwise step the T-shirt out by
    // centimetres within one bin, stretching its vertical edges at the start.
    constexpr double kSlope = 0.5;
    const auto steep = ab;
    for (int k = 0; k < nb; ++k)
      for (int j = 0; j < nb; ++j) {
        const double drop = kSlope * kBin * std::abs(k - j);
        ab[k].first = std::max(ab[k].first, steep[j].first - drop);
        ab[k].second = std::max(ab[k].second, steep[j].second - drop);
      }
    std::vector<double> c(nb);
    for (int k = 0; k < nb; ++k) {
      // An offset curve of a convex curve is longer by c times the angle turned:
      // a quarter (side to front) is the ellipse's quarter plus c·π/2.
      OffsetCurve e;
      e.a = ab[k].first;
      e.b = ab[k].second;
      e.c = 0;
      e.build();
      const double quarter = 0.25 * e.perimeter;
      // A whole leg: once round, its edges the gap apart where it is wider
      // than the curve (a full turn adds 2π c).
      const double grown = whole_leg ? (u_hi[k] - u_lo[k] + gap - e.perimeter) / (2.0 * M_PI)
                                     : (half[k] + 0.5 * gap - quarter) / (0.5 * M_PI);
      c[k] = std::max(std::max(0.0, ar.clearance), grown);
    }
    // Grown clearances spread a few centimetres up and down, so the surface has
    // no kinks.
    std::vector<double> cs = c;
    for (int k = 0; k < nb; ++k)
      for (int j = std::max(0, k - 3); j <= std::min(nb - 1, k + 3); ++j) cs[k] = std::max(cs[k], c[j]);
    bins.resize(nb);
    bin_arc0.resize(nb);
    clearance_used = 0;
    for (int k = 0; k < nb; ++k) {
      bins[k].a = ab[k].first;
      bins[k].b = ab[k].second;
      bins[k].c = cs[k];
      bins[k].build();
      bin_arc0[k] = bins[k].arc_at_theta(theta0);
      clearance_used = std::max(clearance_used, cs[k]);
    }
  }
  // The point of the surface at arc u from the side's direction, height s along the axis.
  auto surface_point = [&](double u, double s_abs) -> Eigen::Vector2d {
    if (!follow) return curve.point_at_arc(arc0 + u);
    const int last = static_cast<int>(bins.size()) - 1;
    if (last == 0) return bins[0].point_at_arc(bin_arc0[0] + u);
    const double t = std::clamp((s_abs - smin) / kBin, 0.0, static_cast<double>(last));
    const int k = std::min(static_cast<int>(t), last - 1);  // interpolate between bins k and k + 1
    const double w = t - k;
    return (1 - w) * bins[k].point_at_arc(bin_arc0[k] + u) + w * bins[k + 1].point_at_arc(bin_arc0[k + 1] + u);
  };

  PiecePlacement out;
  out.clearance = clearance_used;
  out.half_depth = a;
  out.half_width = b;
  out.axis_point = axis_point;
  out.axis = axis;
  out.reverses_winding = ar.flip;
  out.points.reserve(nodes.size());
  for (const auto& q : uv) {
    const double s = sign_s * q.y();  // along the axis from the reference ring
    const Eigen::Vector2d p = surface_point(q.x(), s_ref + s);
    out.points.push_back(axis_point + s * axis + p.x() * e1 + p.y() * e2);
  }
  return out;
}

}  // namespace vgd::dress
