// Arranging pieces by hand (dress/arrange.hpp): the body's arrangement points,
// a piece put on one, an arrangement moved along its segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "vgd/body/mannequin.hpp"
#include "vgd/body/sizes.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/dress/arrange.hpp"
#include "vgd/dress/placement.hpp"

using namespace vgd;
using body::Vec3;
using pattern::Vec2;

namespace {

const body::Avatar& mannequin() {
  static const body::Avatar a = body::make_mannequin(body::find_size("38"));
  return a;
}

std::map<std::string, dress::ArrangementPoint> points_by_label(const body::Avatar& a) {
  std::map<std::string, dress::ArrangementPoint> out;
  for (const auto& p : dress::arrangement_points(a)) out[p.label] = p;
  return out;
}

double nearest_body_vertex(const body::Avatar& a, const Vec3& p) {
  double d = 1e300;
  for (const auto& v : a.surface.vertices) d = std::min(d, (v - p).norm());
  return d;
}

// A 40 x 60 cm piece, its box from (0.1, 0.2) (so its reference point, the
// top middle, is (0.3, 0.8)).
pattern::Piece panel() {
  pattern::Piece p;
  p.name = "PANEL";
  p.boundary = {{Vec2(0.1, 0.2), pattern::PointKind::turn},
                {Vec2(0.5, 0.2), pattern::PointKind::turn},
                {Vec2(0.5, 0.8), pattern::PointKind::turn},
                {Vec2(0.1, 0.8), pattern::PointKind::turn}};
  return p;
}

xvc::Arrangement on(const std::string& segment, const std::string& side, double height, bool flip = false) {
  xvc::Arrangement a;
  a.segment = segment, a.side = side, a.height = height, a.flip = flip;
  a.angle_deg = 0, a.x = 0.3, a.y = 0.8;
  return a;
}

}  // namespace

// The mannequin's points: each segment's sides where the suggestions put
// pieces, outside the body by about the clearance, the sides mirror images.
TEST(Arrange, TheMannequinsPointsLieOutsideItsSegmentsOnTheirSides) {
  const auto& a = mannequin();
  const auto pts = points_by_label(a);
  const xvc::ArrangementOptions o = dress::arrangement_options(a);
  for (const char* label : {"neck front", "torso front", "torso back", "torso left", "torso right", "hips front",
                            "hips back", "hips left", "hips right", "left arm", "right arm", "left leg", "right leg"})
    ASSERT_EQ(pts.count(label), 1u) << label;
  EXPECT_EQ(pts.size(), 13u);
  // On the trunk the height is the point's world height.
  for (const auto& [label, p] : pts)
    if (p.arrangement.segment == "torso" || p.arrangement.segment == "hips") {
      EXPECT_NEAR(p.at.y(), p.arrangement.height, 1e-3) << label;
    }
  EXPECT_NEAR(pts.at("torso front").arrangement.height, o.neck_point_height + o.bodice_lift, 1e-12);
  EXPECT_NEAR(pts.at("hips back").arrangement.height, o.waist_height, 1e-12);
  EXPECT_GT(pts.at("torso front").at.z(), 0.03);
  EXPECT_LT(pts.at("torso back").at.z(), -0.03);
  EXPECT_GT(pts.at("hips front").at.z(), pts.at("hips left").at.z() + 0.05);
  EXPECT_NEAR(pts.at("hips front").at.x(), 0.0, 0.005);
  // The body's left is +x (it faces +z); left and right mirror each other.
  for (const auto& [l, r] : {std::pair{"torso left", "torso right"}, {"hips left", "hips right"},
                             {"left arm", "right arm"}, {"left leg", "right leg"}}) {
    EXPECT_GT(pts.at(l).at.x(), 0.1) << l;
    EXPECT_NEAR(pts.at(l).at.x(), -pts.at(r).at.x(), 0.002) << l;
    EXPECT_NEAR(pts.at(l).at.y(), pts.at(r).at.y(), 0.002) << l;
  }
  // An arm's point: the sleeve's cap top down from the shoulder end, outside the arm.
  const body::BodySegment* arm = a.segment("left-arm");
  const double s = (pts.at("left arm").at - arm->start).dot(arm->axis);
  EXPECT_NEAR(s, o.sleeve_drop, 0.01);
  EXPECT_GT(pts.at("left arm").at.x(), arm->start.x());
  // Outside the surface by about the clearance (the rings' envelope is elliptic, the surface not).
  for (const auto& [label, p] : pts) {
    const double d = nearest_body_vertex(a, p.at);
    EXPECT_GT(d, 0.4 * p.arrangement.clearance) << label;
    EXPECT_LT(d, p.arrangement.clearance + 0.05) << label;
  }
}

// A body without arms or legs has no points on them.
TEST(Arrange, ABodyWithoutLimbsHasNoPointsOnThem) {
  body::Avatar a = mannequin();
  a.segments.erase(std::remove_if(a.segments.begin(), a.segments.end(),
                                  [](const body::BodySegment& s) { return s.name.find('-') != std::string::npos; }),
                   a.segments.end());
  const auto pts = points_by_label(a);
  EXPECT_EQ(pts.count("left arm") + pts.count("right arm") + pts.count("left leg") + pts.count("right leg"), 0u);
  EXPECT_EQ(pts.count("torso front"), 1u);
}

// Put on a point: a new place takes the point's segment, side, height and
// clearance with the piece's own reference point and angle; a limb's copy
// goes on the other limb mirrored; a place a copy already has only moves it.
TEST(Arrange, APiecePutOnAPointTakesItsPlaceAndItsCopiesFollowOnLimbs) {
  const auto pts = points_by_label(mannequin());
  const pattern::Piece piece = panel();

  // A front (one copy) from the torso to the hips' back.
  auto front = dress::put_on({on("torso", "front", 1.47)}, pts.at("hips back"), piece);
  ASSERT_EQ(front.size(), 1u);
  EXPECT_EQ(front[0].segment, "hips");
  EXPECT_EQ(front[0].side, "back");
  EXPECT_DOUBLE_EQ(front[0].height, pts.at("hips back").arrangement.height);
  EXPECT_DOUBLE_EQ(front[0].clearance, pts.at("hips back").arrangement.clearance);
  EXPECT_NEAR(front[0].x, 0.3, 1e-12);
  EXPECT_NEAR(front[0].y, 0.8, 1e-12);
  EXPECT_FALSE(front[0].flip);

  // Its angle is kept, and the reference point is the top middle of the turned box.
  auto turned = on("torso", "front", 1.47);
  turned.angle_deg = 90;  // the box turned a quarter counter-clockwise: x in [-0.8, -0.2], y in [0.1, 0.5]
  const auto t = dress::put_on({turned}, pts.at("torso back"), piece);
  EXPECT_DOUBLE_EQ(t[0].angle_deg, 90);
  const Vec2 ref = xvc::reference_point(piece, 90);
  EXPECT_NEAR(t[0].x, ref.x(), 1e-12);
  EXPECT_NEAR(t[0].y, ref.y(), 1e-12);
  EXPECT_NE(ref, Vec2(0.3, 0.8));

  // A sleeve cut twice, on the right arm and (mirrored) the left, put on the
  // right leg: the copies go to the two legs, the left one mirrored.
  const std::vector<xvc::Arrangement> sleeve = {on("right-arm", "right", 0.06), on("left-arm", "left", 0.06, true)};
  const auto legs = dress::put_on(sleeve, pts.at("right leg"), piece);
  ASSERT_EQ(legs.size(), 2u);
  EXPECT_EQ(legs[0].segment, "right-leg");
  EXPECT_EQ(legs[0].side, "right");
  EXPECT_FALSE(legs[0].flip);
  EXPECT_EQ(legs[1].segment, "left-leg");
  EXPECT_EQ(legs[1].side, "left");
  EXPECT_TRUE(legs[1].flip);
  EXPECT_DOUBLE_EQ(legs[1].height, pts.at("right leg").arrangement.height);

  // On the left arm, where a copy is already: only that copy's height changes.
  auto lower = pts.at("left arm");
  lower.arrangement.height = 0.12;
  const auto moved = dress::put_on(sleeve, lower, piece);
  ASSERT_EQ(moved.size(), 2u);
  EXPECT_DOUBLE_EQ(moved[1].height, 0.12);
  EXPECT_TRUE(moved[1].flip);
  EXPECT_DOUBLE_EQ(moved[0].height, 0.06);
  EXPECT_EQ(moved[0].segment, "right-arm");

  // A piece with no place yet, put on the left arm: mirrored there.
  const auto fresh = dress::put_on({}, pts.at("left arm"), piece);
  ASSERT_EQ(fresh.size(), 1u);
  EXPECT_TRUE(fresh[0].flip);
  EXPECT_EQ(fresh[0].segment, "left-arm");
}

// Moved along its segment: the trunk by the vertical part of the move, a
// limb by the part along its axis; kept on the body.
TEST(Arrange, AMovedPieceSlidesAlongItsSegmentAndStaysOnTheBody) {
  const auto& a = mannequin();
  const Vec3 delta(0.10, -0.07, 0.20);
  const auto torso = dress::moved(on("torso", "front", 1.40), a, delta);
  EXPECT_NEAR(torso.height, 1.33, 1e-12);
  EXPECT_EQ(torso.side, "front");
  const body::BodySegment* arm = a.segment("left-arm");
  const auto sleeve = dress::moved(on("left-arm", "left", 0.06, true), a, delta);
  EXPECT_NEAR(sleeve.height, 0.06 + delta.dot(arm->axis), 1e-12);
  EXPECT_TRUE(sleeve.flip);
  // Far up: the body's top; far down a limb: its end.
  double top = 0;
  for (const auto& v : a.surface.vertices) top = std::max(top, v.y());
  EXPECT_NEAR(dress::moved(on("torso", "front", 1.40), a, Vec3(0, 5, 0)).height, top, 1e-12);
  EXPECT_NEAR(dress::moved(on("left-arm", "left", 0.06), a, 5 * arm->axis).height, arm->length, 1e-12);
  EXPECT_THROW(dress::moved(on("tail", "front", 0.1), a, delta), vgd::Error);
}

// Turned round its segment: a quarter at a time, each once the turn passes
// an eighth (positive: the front towards the left); the piece place_piece
// then lays out lies on that side (its middle along side_direction from the
// axis). A drag follows the mouse: from the front, the view's right is the
// body's left, and the front goes that way; the back, seen through the body,
// goes the same way on screen, to the body's left too; the turn is the move
// over the radius.
TEST(Arrange, ATurnedPieceGoesToTheSideItIsDraggedTo) {
  const auto& a = mannequin();
  const auto front = on("torso", "front", 1.40);
  const double q = std::numbers::pi / 2;
  const std::map<double, std::string> sides = {{0.0, "front"}, {0.7, "front"}, {0.8, "left"}, {q, "left"},
                                               {2 * q, "back"}, {-q, "right"}, {-2.4, "back"}, {4 * q, "front"}};
  const pattern::Piece piece = panel();
  std::vector<Vec2> nodes;
  for (const auto& p : piece.boundary) nodes.push_back(p.p);
  for (const auto& [angle, side] : sides) {
    const auto t = dress::turned_by(front, a, angle);
    EXPECT_EQ(t.side, side) << angle;
    EXPECT_DOUBLE_EQ(t.height, front.height);
    EXPECT_DOUBLE_EQ(t.clearance, front.clearance);
    const auto placed = dress::place_piece(nodes, t, a);
    Vec3 mid = Vec3::Zero();
    for (const auto& p : placed.points) mid += p / static_cast<double>(placed.points.size());
    Vec3 off = mid - placed.axis_point;
    off -= off.dot(placed.axis) * placed.axis;
    EXPECT_GT(off.normalized().dot(dress::side_direction(t, a)), 0.9) << side;
  }
  EXPECT_GT(dress::side_direction(dress::turned_by(front, a, q), a).x(), 0.9) << "the body's left is +x";
  // The rest of the turn past the side is kept (around, degrees), within an
  // eighth of a turn; within 5° of a side the piece faces it square.
  const std::map<double, double> rest = {{0.0, 0.0}, {0.7, 0.7 * 180 / std::numbers::pi},
                                         {0.8, 0.8 * 180 / std::numbers::pi - 90}, {q, 0.0}, {-2.4, 180 - 2.4 * 180 / std::numbers::pi},
                                         {0.05, 0.0}, {q + 0.1, 0.1 * 180 / std::numbers::pi}};
  for (const auto& [angle, deg] : rest) EXPECT_NEAR(dress::turned_by(front, a, angle).around_deg, deg, 1e-6) << angle;
  // A turned piece lies that far round: its middle 40° from the front towards the left.
  const auto part = dress::turned_by(front, a, 0.7);
  const Vec3 d = dress::side_direction(part, a);
  EXPECT_NEAR(std::acos(std::clamp(d.dot(dress::side_direction(front, a)), -1.0, 1.0)), 0.7, 1e-9);
  EXPECT_GT(d.x(), 0.5) << "towards the body's left";
  {
    const auto placed = dress::place_piece(nodes, part, a);
    Vec3 mid = Vec3::Zero();
    for (const auto& p : placed.points) mid += p / static_cast<double>(placed.points.size());
    Vec3 off = mid - placed.axis_point;
    off -= off.dot(placed.axis) * placed.axis;
    EXPECT_GT(off.normalized().dot(d), 0.97);
  }
  const auto again = dress::turned_by(part, a, -0.7);
  EXPECT_EQ(again.side, "front");
  EXPECT_EQ(again.around_deg, 0.0) << "turned back, it faces the front square";

  // Drags seen from the front (looking along -z; the view's right is +x): 10 cm to the right.
  const Vec3 view(0, 0, -1), move(0.10, 0.02, 0.0);
  const double turn = dress::drag_turn(front, a, move, view);
  EXPECT_GT(turn, 0.0);
  const body::BodySegment* torso = a.segment("torso");
  const body::SegmentRing ring = body::ring_at(*torso, front.height - torso->start.y());
  EXPECT_NEAR(turn, 0.10 / (0.5 * (ring.half_width + ring.half_depth) + front.clearance), 1e-9);
  EXPECT_LT(dress::drag_turn(on("torso", "back", 1.40), a, move, view), 0.0) << "the back turns the other way";
  EXPECT_EQ(dress::turned_by(on("torso", "back", 1.40), a, dress::drag_turn(on("torso", "back", 1.40), a, 3 * move, view)).side,
            "left");
  EXPECT_EQ(dress::turned_by(front, a, dress::drag_turn(front, a, -2 * move, view)).side, "right");
  EXPECT_DOUBLE_EQ(dress::drag_turn(front, a, 20 * move, view), std::numbers::pi) << "half a turn at most";
  EXPECT_DOUBLE_EQ(dress::drag_turn(front, a, -20 * move, view), -std::numbers::pi);
  // On the A-posed left arm: its outside is its "left"; turned a quarter it faces its back.
  const auto sleeve = on("left-arm", "left", 0.10, true);
  EXPECT_GT(dress::side_direction(sleeve, a).x(), 0.5);
  EXPECT_EQ(dress::turned_by(sleeve, a, q).side, "back");
  // A side piece seen edge on from the front (its arc runs towards the eye):
  // a drag across the torso still turns it, by a third of the move's worth.
  const auto side = on("torso", "left", 1.40);
  EXPECT_GT(std::abs(dress::drag_turn(side, a, move, view)), 0.1);
  EXPECT_NE(dress::turned_by(side, a, dress::drag_turn(side, a, 2 * move, view)).side, "left");
  // Seen from the side (looking along -x), a drag up the torso does not turn the front.
  EXPECT_NEAR(dress::drag_turn(front, a, Vec3(0, 0.1, 0), Vec3(-1, 0, 0)), 0.0, 1e-12);
  EXPECT_THROW(dress::turned_by(on("tail", "front", 0.1), a, q), vgd::Error);
  EXPECT_THROW(dress::drag_turn(on("tail", "front", 0.1), a, move, view), vgd::Error);
}

// Moved off the body: the clearance grows by the move's part along the
// side's direction, shrinks towards the body, and stays within [0, 30 cm].
TEST(Arrange, APieceMovedOffTheBodyChangesItsClearanceOnly) {
  const auto& a = mannequin();
  auto back = on("torso", "back", 1.40);
  back.clearance = 0.03;
  const auto out = dress::moved_off(back, a, Vec3(0.04, 0.10, -0.05));
  EXPECT_NEAR(out.clearance, 0.08, 1e-9);
  EXPECT_EQ(out.side, "back");
  EXPECT_DOUBLE_EQ(out.height, 1.40);
  EXPECT_NEAR(dress::moved_off(back, a, Vec3(0, 0, 0.02)).clearance, 0.01, 1e-9);
  EXPECT_DOUBLE_EQ(dress::moved_off(back, a, Vec3(0, 0, 0.5)).clearance, 0.0);
  EXPECT_DOUBLE_EQ(dress::moved_off(back, a, Vec3(0, 0, -2)).clearance, dress::kMaxClearance);
  // Laid out further off the body (at 3 cm place_piece widens the panel's
  // clearance a little so it fits half way round; at 8 cm it needs not).
  const pattern::Piece piece = panel();
  std::vector<Vec2> nodes;
  for (const auto& q : piece.boundary) nodes.push_back(q.p);
  const auto near = dress::place_piece(nodes, back, a), far = dress::place_piece(nodes, out, a);
  EXPECT_NEAR(far.clearance, 0.08, 1e-9);
  EXPECT_GT(far.clearance, near.clearance + 0.04);
}
