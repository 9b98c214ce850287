// Avatar segments (avatar.hpp).
#include "vgd/body/avatar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vgd::body {

SegmentRing ring_at(const BodySegment& segment, double s) {
  const auto& r = segment.rings;
  if (r.empty()) {
    SegmentRing out;
    out.s = std::clamp(s, 0.0, segment.length);
    out.centre = segment.start + out.s * segment.axis;
    return out;
  }
  s = std::clamp(s, 0.0, segment.length);
  if (s <= r.front().s) return r.front();
  if (s >= r.back().s) return r.back();
  const auto it = std::upper_bound(r.begin(), r.end(), s, [](double v, const SegmentRing& x) { return v < x.s; });
  const SegmentRing& b = *it;
  const SegmentRing& a = *(it - 1);
  const double t = b.s > a.s ? (s - a.s) / (b.s - a.s) : 0.0;
  SegmentRing out;
  out.s = s;
  out.centre = a.centre + t * (b.centre - a.centre);
  out.half_width = a.half_width + t * (b.half_width - a.half_width);
  out.half_depth = a.half_depth + t * (b.half_depth - a.half_depth);
  return out;
}

const BodySegment* Avatar::segment(std::string_view name) const {
  for (const auto& s : segments)
    if (s.name == name) return &s;
  return nullptr;
}

std::vector<std::string> segments_beside(const Avatar& body, const Vec3& p, double within) {
  const auto& surf = body.surface;
  const auto& segs = body.segments;
  std::vector<double> nearest(segs.size(), std::numeric_limits<double>::infinity());
  const auto& labels = body.triangle_segment;
  const bool labelled = labels.size() == surf.triangles.size() &&
                        std::any_of(labels.begin(), labels.end(), [](int l) { return l >= 0; });
  for (std::size_t t = 0; labelled && t < surf.triangles.size(); ++t) {
    const int sg = labels[t];
    if (sg < 0 || sg >= static_cast<int>(segs.size())) continue;
    const auto& tri = surf.triangles[t];
    const Vec3 c = (surf.vertices[tri[0]] + surf.vertices[tri[1]] + surf.vertices[tri[2]]) / 3.0;
    nearest[sg] = std::min(nearest[sg], (c - p).norm());
  }
  for (std::size_t k = 0; !labelled && k < segs.size(); ++k) {
    const BodySegment& sg = segs[k];
    if (sg.rings.empty()) continue;
    const double along = (p - sg.start).dot(sg.axis);
    const double s = std::clamp(along, 0.0, sg.length);
    const SegmentRing ring = ring_at(sg, s);
    Vec3 r = p - ring.centre;
    r -= r.dot(sg.axis) * sg.axis;
    const double u = r.dot(sg.side()), v = r.dot(sg.front), len = r.norm();
    double radial = 0.0;  // m outside the ellipse, along r
    if (len > 1e-12 && ring.half_width > 0.0 && ring.half_depth > 0.0) {
      const double a = u / len / ring.half_width, b = v / len / ring.half_depth;
      radial = std::max(0.0, len - 1.0 / std::sqrt(a * a + b * b));
    }
    nearest[k] = std::hypot(radial, along - s);
  }
  std::vector<std::size_t> order(segs.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return nearest[a] < nearest[b]; });
  std::vector<std::string> out;
  for (const std::size_t k : order)
    if (std::isfinite(nearest[k]) && nearest[k] <= nearest[order.front()] + within && out.size() < 2)
      out.push_back(segs[k].name);
  return out;
}

}  // namespace vgd::body
