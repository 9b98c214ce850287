#include "vgd/dress/arrange.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vgd/body/mannequin.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/dress/placement.hpp"

namespace vgd::dress {

using body::Avatar;
using body::BodySegment;

bool on_limb(const std::string& segment) { return segment.find("-arm") != std::string::npos || segment.find("-leg") != std::string::npos; }

namespace {

bool on_left(const std::string& segment) { return segment.rfind("left-", 0) == 0; }

// The same limb on the body's other side.
std::string other_limb(const std::string& segment) {
  if (segment.rfind("left-", 0) == 0) return "right-" + segment.substr(5);
  if (segment.rfind("right-", 0) == 0) return "left-" + segment.substr(6);
  return segment;
}

std::string other_side(const std::string& side) {
  return side == "left" ? "right" : side == "right" ? "left" : side;
}

}  // namespace

xvc::ArrangementOptions arrangement_options(const Avatar& avatar) {
  xvc::ArrangementOptions ao;
  if (avatar.measurements) {
    const body::MannequinLandmarks l = body::mannequin_landmarks(*avatar.measurements);
    ao.neck_point_height = l.neck_base;
    ao.waist_height = l.waist;
  } else if (const auto& l = avatar.landmarks; l && l->shoulder > 0 && l->waist > 0) {
    // Measured on the body: the neck's base sits 3 % of the height above the
    // shoulders' top, as on the mannequin.
    ao.neck_point_height = l->shoulder + 0.03 * l->height;
    ao.waist_height = l->waist;
  } else if (const BodySegment* torso = avatar.segment("torso")) {
    ao.neck_point_height = (torso->start + torso->length * torso->axis).y();
    ao.waist_height = 0.62 * (ao.neck_point_height / 0.845);
  }
  // Legs: the piece's top at the waist, above the hip joint.
  if (const BodySegment* leg = avatar.segment("right-leg"); leg && ao.waist_height > 0 && leg->axis.y() < -0.5)
    ao.leg_top = (ao.waist_height - leg->start.y()) / leg->axis.y();  // < 0: the waist is above the joint
  return ao;
}

std::vector<ArrangementPoint> arrangement_points(const Avatar& avatar) {
  const xvc::ArrangementOptions o = arrangement_options(avatar);
  std::vector<ArrangementPoint> out;
  auto add = [&](std::string label, const char* segment, const char* side, double height, double clearance) {
    if (!avatar.segment(segment)) return;
    ArrangementPoint p;
    p.label = std::move(label);
    p.arrangement.segment = segment;
    p.arrangement.side = side;
    p.arrangement.height = height;
    p.arrangement.clearance = clearance;
    // Where a reference point goes: a small piece hanging from it, placed.
    const std::vector<pattern::Vec2> probe = {{0, 0}, {-0.01, -0.01}, {0.01, -0.01}};
    try {
      p.at = place_piece(probe, p.arrangement, avatar).points.front();
    } catch (const Error&) {
      return;  // a segment without rings, or tilted: nothing to put a piece on
    }
    out.push_back(std::move(p));
  };
  add("neck front", "neck", "front", o.neck_point_height, o.clearance);
  for (const char* side : {"front", "back"})
    add(std::string("torso ") + side, "torso", side, o.neck_point_height + o.bodice_lift, o.clearance);
  for (const char* side : {"left", "right"})
    add(std::string("torso ") + side, "torso", side, o.neck_point_height - 0.15, o.clearance);
  for (const char* side : {"front", "back", "left", "right"})
    add(std::string("hips ") + side, "hips", side, o.waist_height, o.clearance);
  add("left arm", "left-arm", "left", o.sleeve_drop, o.sleeve_clearance);
  add("right arm", "right-arm", "right", o.sleeve_drop, o.sleeve_clearance);
  add("left leg", "left-leg", "left", o.leg_top, o.sleeve_clearance);
  add("right leg", "right-leg", "right", o.leg_top, o.sleeve_clearance);
  return out;
}

std::vector<xvc::Arrangement> put_on(std::vector<xvc::Arrangement> current, const ArrangementPoint& point,
                                     const pattern::Piece& piece) {
  const xvc::Arrangement& p = point.arrangement;
  const bool limb = on_limb(p.segment);
  for (auto& a : current)
    if (a.segment == p.segment && (limb || a.side == p.side)) {
      a.height = p.height;  // already there: only its height
      return current;
    }
  xvc::Arrangement a = p;
  a.angle_deg = current.empty() ? 0.0 : current.front().angle_deg;
  const pattern::Vec2 ref = xvc::reference_point(piece, a.angle_deg);
  a.x = ref.x();
  a.y = ref.y();
  a.flip = limb && on_left(p.segment);
  if (current.empty())
    current.push_back(a);
  else
    current.front() = a;
  if (limb && current.size() >= 2) {
    xvc::Arrangement b = a;
    b.segment = other_limb(a.segment);
    b.side = other_side(a.side);
    b.flip = !a.flip;
    current[1] = b;
  }
  return current;
}

body::Vec3 height_direction(const xvc::Arrangement& a, const Avatar& avatar) {
  const BodySegment* s = avatar.segment(a.segment);
  if (!s) throw Error(avatar.source, a.segment, "the body has no such segment to move a piece along");
  return on_limb(a.segment) ? s->axis : body::Vec3::UnitY();
}

xvc::Arrangement moved(xvc::Arrangement a, const Avatar& avatar, const body::Vec3& delta) {
  const double step = delta.dot(height_direction(a, avatar));
  if (on_limb(a.segment)) {
    a.height = std::clamp(a.height + step, -0.3, avatar.segment(a.segment)->length);
  } else {
    double top = 0.0;
    for (const auto& v : avatar.surface.vertices) top = std::max(top, v.y());
    a.height = std::clamp(a.height + step, 0.0, top);
  }
  return a;
}

body::Vec3 side_direction(const xvc::Arrangement& a, const Avatar& avatar) {
  const BodySegment* s = avatar.segment(a.segment);
  if (!s) throw Error(avatar.source, a.segment, "the body has no such segment to turn a piece round");
  const body::Vec3 axis = s->axis.normalized();
  const body::Vec3 up = on_limb(a.segment) ? body::Vec3(-axis) : axis;  // the pattern's up, as place_piece has it
  const body::Vec3 e1 = (s->front - s->front.dot(axis) * axis).normalized();
  const body::Vec3 e2 = up.cross(e1).normalized();
  const body::Vec3 d = a.side == "back" ? body::Vec3(-e1) : a.side == "left" ? e2 : a.side == "right" ? body::Vec3(-e2) : e1;
  const double t = a.around_deg * std::numbers::pi / 180.0;
  return std::cos(t) * d + std::sin(t) * up.cross(d);
}

xvc::Arrangement turned_by(xvc::Arrangement a, const Avatar& avatar, double angle) {
  const BodySegment* s = avatar.segment(a.segment);
  if (!s) throw Error(avatar.source, a.segment, "the body has no such segment to turn a piece round");
  const body::Vec3 up = on_limb(a.segment) ? body::Vec3(-s->axis.normalized()) : body::Vec3(s->axis.normalized());
  const body::Vec3 d = side_direction(a, avatar);
  const body::Vec3 to = std::cos(angle) * d + std::sin(angle) * up.cross(d);  // d is normal to up
  std::string best = a.side;
  double most = -2;
  xvc::Arrangement plain = a;
  plain.around_deg = 0;
  for (const char* side : {"front", "left", "back", "right"}) {
    plain.side = side;
    const double c = to.dot(side_direction(plain, avatar));
    if (c > most + 1e-12) most = c, best = side;
  }
  // The rest of the turn past that side, within an eighth of a turn; a
  // piece let go within kSnapToSide of a side faces it square.
  plain.side = best;
  const body::Vec3 sd = side_direction(plain, avatar);
  const double rest = std::atan2(to.dot(up.cross(sd)), to.dot(sd)) * 180.0 / std::numbers::pi;
  a.side = best;
  a.around_deg = std::abs(rest) < kSnapToSide ? 0.0 : rest;
  return a;
}

double drag_turn(const xvc::Arrangement& a, const Avatar& avatar, const body::Vec3& delta, const body::Vec3& view) {
  const BodySegment* s = avatar.segment(a.segment);
  if (!s) throw Error(avatar.source, a.segment, "the body has no such segment to turn a piece round");
  const body::Vec3 axis = s->axis.normalized();
  const body::Vec3 up = on_limb(a.segment) ? body::Vec3(-axis) : axis;
  const body::Vec3 v = view.normalized();
  // The cross-section at the piece's height: the trunk's height is a world
  // height, a limb's the distance along its axis.
  const double along = on_limb(a.segment) ? a.height : (a.height - s->start.y()) / std::max(1e-9, axis.y());
  const body::SegmentRing ring = body::ring_at(*s, along);
  const double radius = std::max(0.5 * (ring.half_width + ring.half_depth) + a.clearance, 0.01);
  // Turning by +1 rad moves the piece's middle by `radius` along up × d; in
  // the view that is its part across the view direction. Seen edge on (the
  // middle moving towards the eye), the drag across the segment's axis on
  // screen turns it, as if a third of that move were seen.
  const body::Vec3 t = up.cross(side_direction(a, avatar));
  body::Vec3 seen = t - t.dot(v) * v;
  double scale = seen.norm();
  if (scale < 0.3) {
    body::Vec3 across = v.cross(up - up.dot(v) * v);
    if (across.norm() < 1e-9) return 0.0;  // looking along the segment: no drag across it
    across.normalize();
    seen = across.dot(t) < 0 ? body::Vec3(-across) : across;
    scale = 0.3;
  }
  const double turn = delta.dot(seen.normalized()) / (radius * scale);
  return std::clamp(turn, -std::numbers::pi, std::numbers::pi);
}

xvc::Arrangement moved_off(xvc::Arrangement a, const Avatar& avatar, const body::Vec3& delta) {
  a.clearance = std::clamp(a.clearance + delta.dot(side_direction(a, avatar)), 0.0, kMaxClearance);
  return a;
}

}  // namespace vgd::dress
