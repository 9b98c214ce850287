// Outlines drawn by clicks, smoothed (pattern::smooth_through).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vgd/pattern/contour.hpp"

using namespace vgd::pattern;

namespace {

double longest_piece(const std::vector<ContourPoint>& c, bool closed) {
  double l = 0;
  for (std::size_t i = 0; i + 1 < c.size(); ++i) l = std::max(l, (c[i + 1].p - c[i].p).norm());
  if (closed) l = std::max(l, (c.front().p - c.back().p).norm());
  return l;
}

}  // namespace

// Eight clicks on a circle of radius 10 cm, all curve points, closed: the
// outline passes through the eight exactly, no piece longer than the
// spacing, every point within 1.2 % of the radius of the circle and its area
// within 1.5 % of the circle's (a centripetal Catmull-Rom spline through eight
// points of it: 0.85 % and -0.93 % measured). Four clicks give a rounded
// square (a spline's tangents there are 60 % of the circle's).
TEST(SmoothThrough, EightClicksOnACircleGiveARoundOutlineThroughThem) {
  const double r = 0.1;
  std::vector<ContourPoint> clicks;
  for (int k = 0; k < 8; ++k)
    clicks.push_back({Vec2(r * std::cos(k * std::numbers::pi / 4), r * std::sin(k * std::numbers::pi / 4)), PointKind::curve});
  const auto out = smooth_through(clicks, true, 0.005);
  ASSERT_GT(out.size(), 100u);
  EXPECT_LE(longest_piece(out, true), 0.005 + 1e-12);
  for (const auto& c : clicks) {
    bool found = false;
    for (const auto& q : out) found = found || (q.p == c.p && q.kind == PointKind::curve);
    EXPECT_TRUE(found) << c.p.transpose();
  }
  double worst = 0;
  for (const auto& q : out) worst = std::max(worst, std::abs(q.p.norm() - r));
  EXPECT_LT(worst, 0.012 * r);
  EXPECT_GT(worst, 0.0) << "not the clicks alone";
  EXPECT_NEAR(std::abs(signed_area(out)), std::numbers::pi * r * r, 0.015 * std::numbers::pi * r * r);
}

// Corners keep the lines between them straight: a 20 cm square whose top has
// a curve point 3 cm above its middle. The bottom and the sides' lower ends
// have no samples; the top bulges through the curve point, leaving each top
// corner heading for it; clicks keep their kinds and order.
TEST(SmoothThrough, CornersKeepStraightSidesAndACurvePointBulgesItsSide) {
  const std::vector<ContourPoint> clicks = {{Vec2(0, 0), PointKind::turn},
                                            {Vec2(0.2, 0), PointKind::turn},
                                            {Vec2(0.2, 0.2), PointKind::turn},
                                            {Vec2(0.1, 0.23), PointKind::curve},
                                            {Vec2(0, 0.2), PointKind::turn}};
  const auto out = smooth_through(clicks, true, 0.01);
  // Clicks in order, kinds kept.
  std::size_t at = 0;
  for (const auto& q : out)
    if (at < clicks.size() && q.p == clicks[at].p) {
      EXPECT_EQ(q.kind, clicks[at].kind);
      ++at;
    }
  EXPECT_EQ(at, clicks.size());
  EXPECT_EQ(out[0].p, clicks[0].p);
  EXPECT_EQ(out[1].p, clicks[1].p) << "the bottom, corner to corner: straight";
  EXPECT_EQ(out[2].p, clicks[2].p) << "the right side, corner to corner: straight";
  // The top: samples between (0.2, 0.2) and (0, 0.2), all above the straight line, the highest the click.
  int samples = 0;
  for (const auto& q : out)
    if (q.kind == PointKind::curve && q.p != clicks[3].p) {
      ++samples;
      EXPECT_GT(q.p.y(), 0.2) << q.p.transpose();
      EXPECT_LT(q.p.y(), 0.23 + 1e-9) << q.p.transpose();
    }
  EXPECT_GE(samples, 16);
  for (std::size_t i = 3; i + 1 < out.size(); ++i) EXPECT_LE((out[i + 1].p - out[i].p).norm(), 0.01 + 1e-12) << "the top's pieces";
}

// An open line: its ends are corners whatever they are marked; a curve point
// between bends it through itself. One point, or a spacing of 0: as given.
TEST(SmoothThrough, AnOpenLineBendsThroughItsCurvePointsBetweenItsEnds) {
  const std::vector<ContourPoint> clicks = {
      {Vec2(0, 0), PointKind::curve}, {Vec2(0.1, 0.05), PointKind::curve}, {Vec2(0.2, 0), PointKind::curve}};
  const auto out = smooth_through(clicks, false, 0.004);
  EXPECT_EQ(out.front().p, clicks.front().p);
  EXPECT_EQ(out.back().p, clicks.back().p);
  EXPECT_LE(longest_piece(out, false), 0.004 + 1e-12);
  for (const auto& q : out) EXPECT_LE(q.p.y(), 0.05 + 1e-3);
  EXPECT_GT(out.size(), 50u);
  EXPECT_EQ(smooth_through({clicks[0]}, false).size(), 1u);
  EXPECT_EQ(smooth_through(clicks, false, 0.0).size(), 3u);
}
