#pragma once
// Placing pattern pieces around the body before draping (docs/placement.md).
//
// A piece's 2-D nodes (pattern coordinates, m: mesh::PieceMesh::nodes) are wrapped
// on a cylinder around one body segment of an Avatar, as its arrangement says
// (xvc/arrangement.hpp): the cylinder's cross-section is the offset curve, at
// distance `clearance`, of the largest elliptic ring of the segment over the piece's
// extent along the axis (the envelope of every ring there, so no point lands inside
// the body); its axis is the segment's. The pattern's "up" (after turning it by the
// arrangement's angle about its reference point) runs along the segment towards the
// head for neck/torso/hips and towards the shoulder or hip joint for arms and legs;
// the pattern's horizontal runs around the offset curve by arc length, so the map is
// an isometry of the plane onto the cylinder and pattern edge lengths are kept (up to
// chord versus arc). The reference point sits on the side's direction (front, back,
// body's left, body's right) at the arrangement's height.
//
// Orientation: a piece laid face up (counter-clockwise outline) is seen from outside:
// its +x runs to the viewer's right. Then every counter-clockwise pattern triangle
// has its normal pointing away from the body after placement. A flipped arrangement
// mirrors the piece, which reverses that: `reverses_winding` is true and the caller
// must reverse its triangles (or its normals) for the outward face.
//
// A half piece on the trunk (front or back, at most half way round) follows the
// body's taper instead of one cylinder: each height gets the offset curve of the
// rings near it, arc length round the body kept, lengths along it stretched by
// √(1 + (dr/ds)²) (docs/placement.md).
//
// A piece wider than the offset curve's perimeter (less 2 cm) cannot wrap without
// overlapping itself: the clearance is then increased until it fits, and the result
// reports the clearance used.
#include <vector>

#include "vgd/body/avatar.hpp"
#include "vgd/pattern/piece.hpp"
#include "vgd/xvc/arrangement.hpp"

namespace vgd::dress {

using Vec3 = Eigen::Vector3d;

struct PiecePlacement {
  std::vector<Vec3> points;         // m, world frame, one per input node
  double clearance = 0;             // m, the clearance used (≥ the arrangement's)
  double half_width = 0;            // m, semi-axis of the envelope ring along the body's left
  double half_depth = 0;            // m, semi-axis along the front
  Vec3 axis_point = Vec3::Zero();   // m, a point of the cylinder's axis
  Vec3 axis = Vec3::UnitY();        // unit
  bool reverses_winding = false;    // true for flipped arrangements (see above)
};

// Cloth already placed under the piece (a skirt under a T-shirt): its points
// bound the piece's rings like the body's, so the piece starts at least `gap`
// outside them. Only points of the same segment count (the trunk — neck, torso,
// hips — is one segment here), or a torso's points would inflate a sleeve.
struct Underlayer {
  std::string segment;      // the body segment the points were placed on
  std::vector<Vec3> points;  // m, world frame
};
inline constexpr double kUnderlayerGap = 0.015;  // m between a piece and the cloth under it

// Throws vgd::Error naming the segment when the avatar has no such segment, the
// segment has no rings, or (neck/torso/hips) its axis is too close to horizontal for
// a world height to be meaningful.
// `nest` (m): a back piece wrapped on one curve with its front (the two too
// wide to meet at the body's sides) starts this much further out, so the two
// overlap at the sides one over the other instead of in one surface, through
// each other (offset contact keeps what the start has).
PiecePlacement place_piece(const std::vector<pattern::Vec2>& nodes, const xvc::Arrangement& arrangement,
                           const body::Avatar& avatar, const std::vector<Underlayer>& under = {}, double nest = 0.0);

}  // namespace vgd::dress
