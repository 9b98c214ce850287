#pragma once
// Arranging pieces round the body by hand (the studio's 3-D view): the
// points on the body a piece can be put on, the arrangements putting a piece
// there gives, and an arrangement moved by a drag: along its segment, round
// it to another side, or off the body.
// Units: metres (world frame: +Y up, the body facing +Z) and degrees.
#include <string>
#include <vector>

#include "vgd/body/avatar.hpp"
#include "vgd/pattern/piece.hpp"
#include "vgd/xvc/arrangement.hpp"

namespace vgd::dress {

// The heights arrangement suggestions use on `avatar`: a mannequin's
// landmarks, else those measured on an imported body, else its torso's top
// (the neck) and a waist at 62 % of the height; legs' tops at the waist.
xvc::ArrangementOptions arrangement_options(const body::Avatar& avatar);

// A place on the body a piece can be put on: the arrangement it gives a
// piece (segment, side, height, clearance; the reference point and angle are
// the piece's own) and where, in the world, the piece's reference point (the
// top middle of its box) then goes.
struct ArrangementPoint {
  std::string label;            // "torso front", "left arm", ...
  xvc::Arrangement arrangement;
  body::Vec3 at = body::Vec3::Zero();  // m, world frame
};

// The arrangement points of the body's segments, at the heights the
// suggestions use (arrangement_options): the neck's front at the neck point;
// the torso's front and back at a bodice's top (bodice_lift above the neck
// point) and its sides 15 cm below the neck point; the hips' four sides at
// the waist; each arm's outside a sleeve's cap down from the shoulder; each
// leg's outside at the waist. Points on segments the body lacks are left out.
std::vector<ArrangementPoint> arrangement_points(const body::Avatar& avatar);

// A pattern's arrangements (one per copy of the piece) after the piece is
// put on `point`. When a copy is already on the point's segment (and side, on
// the trunk) only its height changes. Otherwise the first copy takes the
// point's segment, side, height and clearance, keeps its angle, and its
// reference point is the piece's (xvc::reference_point); on a left arm or leg
// it is mirrored (a piece laid face up wraps a right limb as it is). On a
// limb, a second copy goes on the other limb, mirrored the other way.
std::vector<xvc::Arrangement> put_on(std::vector<xvc::Arrangement> current, const ArrangementPoint& point,
                                     const pattern::Piece& piece);

// The world direction (unit) in which `a`'s height grows: up (+Y) on the
// neck, torso and hips, down the limb's axis on an arm or a leg. Throws
// vgd::Error when the avatar lacks the segment.
body::Vec3 height_direction(const xvc::Arrangement& a, const body::Avatar& avatar);

// A segment that is a limb ("left-arm", "right-leg", ...): its pieces' heights run
// along its axis from the joint, not up the body.
bool on_limb(const std::string& segment);

// `a` moved by the world displacement `delta` (m) along its segment: on the
// neck, torso and hips its height changes by delta's vertical part, on an arm
// or a leg by delta's part along the limb's axis (down the limb). Heights
// are kept on the body: the trunk's between the floor and the body's top, a
// limb's between 30 cm above its joint and its length. Throws vgd::Error
// when the avatar lacks the segment.
xvc::Arrangement moved(xvc::Arrangement a, const body::Avatar& avatar, const body::Vec3& delta);

// The world direction (unit, normal to the segment's axis) that `a`'s side
// faces on its segment, as place_piece lays a piece out: front is the
// segment's front; left is the pattern's up × front (the body's left on the
// trunk; on a limb it turns with the limb, so an arm's outside stays its
// outside from A- to T-pose); back and right the opposites; turned by
// `around_deg` from there. Throws vgd::Error when the avatar lacks the
// segment.
body::Vec3 side_direction(const xvc::Arrangement& a, const body::Avatar& avatar);

// `a` turned round its segment by `angle` (rad; positive turns its front
// towards its left, counter-clockwise seen from the pattern's up end): set
// on the side (front, left, back or right) nearest the direction it then
// faces, and `around_deg` the rest of the turn past that side (at most an
// eighth of a turn either way; 0 within kSnapToSide, so a piece let go
// near a side faces it square). Throws vgd::Error when the avatar lacks the
// segment.
inline constexpr double kSnapToSide = 5.0;  // deg
xvc::Arrangement turned_by(xvc::Arrangement a, const body::Avatar& avatar, double angle);

// The turn (rad, for turned_by) that lets `a`'s piece follow a drag: the
// world displacement `delta` (m) at the piece, in a view looking along
// `view` (unit), moves the piece's middle as far along its arc round the
// segment (its radius: the segment's cross-section there and the
// clearance), as the view shows the arc, the way the mouse went; where the
// arc runs towards the eye (a sleeve on an arm held out, seen from the
// front) a drag across the segment turns it. Half a turn at most either
// way. Throws vgd::Error when the avatar lacks the segment.
double drag_turn(const xvc::Arrangement& a, const body::Avatar& avatar, const body::Vec3& delta, const body::Vec3& view);

// `a` moved off the body (or towards it) by the part of the world
// displacement `delta` (m) along its side's direction (side_direction): its
// clearance changes by that much, kept within [0, kMaxClearance]. Throws
// vgd::Error when the avatar lacks the segment.
inline constexpr double kMaxClearance = 0.30;  // m
xvc::Arrangement moved_off(xvc::Arrangement a, const body::Avatar& avatar, const body::Vec3& delta);

}  // namespace vgd::dress
