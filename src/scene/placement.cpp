// Wrapping pattern pieces around body segments (placement.hpp, docs/placement.md).
#include "vgd/scene/placement.hpp"

#include <algorithm>
#include <cmath>

#include "vgd/core/diagnostics.hpp"

namespace vgd::scene {

namespace {

// The ring at s, linearly interpolated and clamped (as ring_at in avatar.hpp; kept
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

}  // namespace

PiecePlacement place_piece(const std::vector<pattern::Vec2>& nodes, const xvc::Arrangement& ar, const Avatar& avatar) {
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

  // Envelope of the rings over [smin, smax] around the reference ring's centre line.
  const SegmentRing ref = ring_local(*seg, s_ref);
  const Vec3 axis_point = ref.centre;
  double a = 0, b = 0;  // along e1 (depth), e2 (width)
  auto take = [&](const SegmentRing& r) {
    Vec3 d = r.centre - axis_point;
    d -= d.dot(axis) * axis;
    b = std::max(b, r.half_width + std::abs(d.dot(e2)));
    a = std::max(a, r.half_depth + std::abs(d.dot(e1)));
  };
  take(ring_local(*seg, smin));
  take(ring_local(*seg, smax));
  for (const auto& r : seg->rings)
    if (r.s > smin && r.s < smax) take(r);
  a = std::max(a, 1e-3);
  b = std::max(b, 1e-3);

  OffsetCurve curve;
  curve.a = a;
  curve.b = b;
  curve.c = std::max(0.0, ar.clearance);
  curve.build();
  const double width = nodes.empty() ? 0 : umax - umin;
  const double gap = 0.02;
  if (width > curve.perimeter - gap) {
    // Wider than the body: grow the clearance until the piece fits once around.
    double lo = curve.c, hi = curve.c + width;
    for (int i = 0; i < 60; ++i) {
      curve.c = 0.5 * (lo + hi);
      curve.build();
      (curve.perimeter - gap < width ? lo : hi) = curve.c;
    }
    curve.c = hi;
    curve.build();
  }
  // Direction of the side: angle in the (e1, e2) plane.
  double theta0 = 0;
  if (ar.side == "back") theta0 = M_PI;
  else if (ar.side == "left") theta0 = M_PI / 2;
  else if (ar.side == "right") theta0 = -M_PI / 2;
  // For an upright `up`, e2 is the body's left; on a limb pointing down `up` is upwards
  // too. Where `up` points down (e2 the body's right), left and right swap.
  if ((ar.side == "left" || ar.side == "right") && up.y() < 0) theta0 = -theta0;
  const double arc0 = curve.arc_at_theta(theta0);

  PiecePlacement out;
  out.clearance = curve.c;
  out.half_depth = a;
  out.half_width = b;
  out.axis_point = axis_point;
  out.axis = axis;
  out.reverses_winding = ar.flip;
  out.points.reserve(nodes.size());
  for (const auto& q : uv) {
    const Eigen::Vector2d p = curve.point_at_arc(arc0 + q.x());
    const double s = sign_s * q.y();  // along the axis from the reference ring
    out.points.push_back(axis_point + s * axis + p.x() * e1 + p.y() * e2);
  }
  return out;
}

}  // namespace vgd::scene
