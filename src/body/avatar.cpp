// Avatar segments (avatar.hpp).
#include "vgd/body/avatar.hpp"

#include <algorithm>

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

}  // namespace vgd::body
