// Contour resampling (seed 002 §2): corners stay, points spread evenly per side.
#include <gtest/gtest.h>

#include <cmath>

#include "vgd/pattern/resample.hpp"

using namespace vgd::pattern;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<ContourPoint> outline(std::initializer_list<std::pair<double, double>> pts) {
  std::vector<ContourPoint> o;
  for (auto [x, y] : pts) o.push_back({Vec2(x, y)});
  return o;
}

// Regular n-gon of radius r (a "curve" the CAD system drew densely).
std::vector<ContourPoint> circle(int n, double r, PointKind kind = PointKind::curve) {
  std::vector<ContourPoint> o;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    o.push_back({Vec2(r * std::cos(a), r * std::sin(a)), kind});
  }
  return o;
}

int count_exact(const std::vector<ContourPoint>& pts, const Vec2& q) {
  int c = 0;
  for (const auto& p : pts) c += p.p == q;
  return c;
}

bool has_duplicate_neighbours(const std::vector<ContourPoint>& pts) {
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (pts[i].p == pts[(i + 1) % pts.size()].p) return true;
  return false;
}

}  // namespace

TEST(Resample, SquareKeepsCornersAndSpacesSidesEvenly) {
  const auto sq = outline({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  const ResampledContour r = resample_contour(sq, {.spacing_m = 0.1});
  ASSERT_EQ(r.points.size(), 40u);
  EXPECT_EQ(r.side_count, 4);
  for (const auto& c : sq) EXPECT_EQ(count_exact(r.points, c.p), 1) << c.p.transpose();
  for (std::size_t i = 0; i < r.points.size(); ++i)
    EXPECT_NEAR((r.points[(i + 1) % 40].p - r.points[i].p).norm(), 0.1, 1e-12);
  EXPECT_NEAR(perimeter(r.points), 4.0, 1e-12);
  EXPECT_NEAR(signed_area(r.points), 1.0, 1e-12);
}

TEST(Resample, LShapePerimeterAndAreaArePreserved) {
  const auto l = outline({{0, 0}, {0.5, 0}, {0.5, 0.2}, {0.2, 0.2}, {0.2, 0.7}, {0, 0.7}});
  const ResampledContour r = resample_contour(l, {.spacing_m = 0.03});
  EXPECT_NEAR(perimeter(r.points), perimeter(l), 1e-12);
  EXPECT_NEAR(signed_area(r.points), signed_area(l), 1e-12);
  EXPECT_EQ(r.side_count, 6);
  EXPECT_FALSE(is_self_intersecting(r.points));
}

TEST(Resample, GapsNeverExceedSpacingAndAreEqualWithinASide) {
  // Side lengths 1.0 and 0.35 at spacing 0.1: 10 and 4 segments (0.1 and 0.0875).
  const auto rect = outline({{0, 0}, {1, 0}, {1, 0.35}, {0, 0.35}});
  const ResampledContour r = resample_contour(rect, {.spacing_m = 0.1});
  ASSERT_EQ(r.points.size(), 28u);
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const double gap = (r.points[(i + 1) % r.points.size()].p - r.points[i].p).norm();
    EXPECT_LE(gap, 0.1 + 1e-12);
    EXPECT_NEAR(gap, r.side[i] % 2 == 0 ? 0.1 : 0.0875, 1e-12);
  }
}

TEST(Resample, UnevenInputBecomesEven) {
  // One straight side holding clustered vertices; the others are plain edges.
  const auto o = outline({{0, 0}, {0.01, 0}, {0.015, 0}, {0.6, 0}, {1, 0}, {1, 1}, {0, 1}});
  const ResampledContour r = resample_contour(o, {.spacing_m = 0.25});
  ASSERT_EQ(r.points.size(), 16u);
  for (std::size_t i = 0; i < r.points.size(); ++i)
    EXPECT_NEAR((r.points[(i + 1) % r.points.size()].p - r.points[i].p).norm(), 0.25, 1e-12);
}

TEST(Resample, SmoothClosedCurveIsOneSideAnchoredAtVertexZero) {
  const auto c = circle(360, 0.2);
  const ResampledContour r = resample_contour(c, {.spacing_m = 0.01});
  EXPECT_EQ(r.side_count, 1);
  EXPECT_EQ(r.points.front().p, c.front().p);
  EXPECT_EQ(r.source.front(), 0);
  // Chords of equal arcs on a circle are equal: spacing equal within 1e-6 m.
  const double first = (r.points[1].p - r.points[0].p).norm();
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const double gap = (r.points[(i + 1) % r.points.size()].p - r.points[i].p).norm();
    EXPECT_NEAR(gap, first, 1e-6);
    EXPECT_LE(gap, 0.01);
  }
  // New points on a curved side are curve points.
  for (std::size_t i = 1; i < r.points.size(); ++i) EXPECT_EQ(r.points[i].kind, PointKind::curve);
}

TEST(Resample, TurnAngleThresholdDecidesSides) {
  // An 18-gon turns by 20° at each vertex: below 30° it is one side, above 10° 18 sides.
  const auto poly = circle(18, 0.3, PointKind::plain);
  EXPECT_EQ(resample_contour(poly, {.spacing_m = 0.02, .turn_angle_deg = 30}).side_count, 1);
  const ResampledContour r = resample_contour(poly, {.spacing_m = 0.02, .turn_angle_deg = 10});
  EXPECT_EQ(r.side_count, 18);
  for (const auto& v : poly) EXPECT_EQ(count_exact(r.points, v.p), 1);
}

TEST(Resample, TurnPointsAlwaysSplitEvenWhereStraight) {
  // (0.37, 0) is collinear: a plain vertex there would vanish, a turn point stays.
  auto o = outline({{0, 0}, {0.37, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_EQ(count_exact(resample_contour(o, {.spacing_m = 0.1}).points, Vec2(0.37, 0)), 0);
  o[1].kind = PointKind::turn;
  const ResampledContour r = resample_contour(o, {.spacing_m = 0.1});
  EXPECT_EQ(r.side_count, 5);
  ASSERT_EQ(count_exact(r.points, Vec2(0.37, 0)), 1);
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    if (r.points[i].p == Vec2(0.37, 0)) {
      EXPECT_EQ(r.points[i].kind, PointKind::turn);
      EXPECT_EQ(r.source[i], 1);
    }
  }
  // Turn points split even with a threshold that splits nothing else.
  EXPECT_EQ(resample_contour(o, {.spacing_m = 0.1, .turn_angle_deg = 180}).side_count, 1);
}

TEST(Resample, SegmentsPerSideGivesExactCounts) {
  const auto tri = outline({{0, 0}, {1, 0}, {0, 1}});
  const ResampledContour r = resample_contour(tri, {.segments_per_side = 5});
  ASSERT_EQ(r.points.size(), 15u);
  std::vector<int> per_side(3, 0);
  for (int s : r.side) ++per_side[s];
  EXPECT_EQ(per_side, (std::vector<int>{5, 5, 5}));
  EXPECT_NEAR((r.points[1].p - r.points[0].p).norm(), 0.2, 1e-12);
}

TEST(Resample, TinySidesKeepBothEnds) {
  // A 1 mm chamfer on a 1 m square at 1 cm spacing: the chamfer is one segment.
  const auto o = outline({{0, 0}, {1, 0}, {1, 0.999}, {0.999, 1}, {0, 1}});
  const ResampledContour r = resample_contour(o, {.spacing_m = 0.01, .turn_angle_deg = 30});
  for (const auto& v : o) EXPECT_EQ(count_exact(r.points, v.p), 1);
  EXPECT_FALSE(has_duplicate_neighbours(r.points));
  EXPECT_NEAR(perimeter(r.points), perimeter(o), 1e-12);
  // And a side far below the spacing, between two turn points.
  auto t = outline({{0, 0}, {1e-7, 0}, {1, 0}, {1, 1}});
  t[1].kind = PointKind::turn;
  const ResampledContour rt = resample_contour(t, {.spacing_m = 0.1});
  EXPECT_EQ(rt.points[1].p, Vec2(1e-7, 0));
  EXPECT_FALSE(has_duplicate_neighbours(rt.points));
}

TEST(Resample, OrientationIsKept) {
  auto o = outline({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_GT(signed_area(resample_contour(o, {.spacing_m = 0.3}).points), 0);
  std::reverse(o.begin(), o.end());
  EXPECT_LT(signed_area(resample_contour(o, {.spacing_m = 0.3}).points), 0);
}

TEST(Resample, DuplicateInputVerticesAreMerged) {
  auto o = outline({{0, 0}, {0, 0}, {1, 0}, {1, 1}, {1, 1}, {0, 1}, {0, 0}});
  o[4].kind = PointKind::turn;  // the duplicate carries the marking
  const ResampledContour r = resample_contour(o, {.spacing_m = 0.5});
  EXPECT_EQ(r.points.size(), 8u);
  EXPECT_FALSE(has_duplicate_neighbours(r.points));
  for (const auto& p : r.points) {
    if (p.p == Vec2(1, 1)) {
      EXPECT_EQ(p.kind, PointKind::turn);
    }
  }
}

TEST(Resample, AlwaysAtLeastATriangle) {
  // A thin sliver with two sharp ends: two sides, each shorter than the spacing.
  const auto o = outline({{0, 0}, {0.05, 0.001}, {0.1, 0}, {0.05, -0.001}});
  const ResampledContour r = resample_contour(o, {.spacing_m = 1.0, .turn_angle_deg = 30});
  EXPECT_GE(r.points.size(), 3u);
  EXPECT_EQ(r.points.front().p, Vec2(0, 0));
}

TEST(Resample, PieceCutoutsAndNotches) {
  Piece p;
  p.boundary = outline({{0, 0}, {0.4, 0}, {0.4, 0.3}, {0.23, 0.3}, {0, 0.3}});
  p.notches.push_back({.position = Vec2(0.23, 0.302), .boundary_index = 3});
  p.cutouts.push_back({{Vec2(0.1, 0.1), Vec2(0.2, 0.1), Vec2(0.2, 0.2), Vec2(0.1, 0.2)}, true});
  p.cutouts.push_back({{Vec2(0.3, 0.1), Vec2(0.35, 0.15)}, false});
  const Piece r = resample_piece(p, {.spacing_m = 0.02});
  // The notch vertex is collinear but kept, and the notch points at it.
  ASSERT_GE(r.notches[0].boundary_index, 0);
  EXPECT_EQ(r.boundary[r.notches[0].boundary_index].p, Vec2(0.23, 0.3));
  EXPECT_EQ(r.cutouts[0].points.size(), 20u);
  EXPECT_EQ(r.cutouts[1].points.size(), 2u);  // open: copied
  EXPECT_NEAR(perimeter(r.boundary), 1.4, 1e-12);
  // Without keep_notch_vertices the collinear vertex goes.
  const Piece r2 = resample_piece(p, {.spacing_m = 0.02, .keep_notch_vertices = false});
  EXPECT_EQ(count_exact(r2.boundary, Vec2(0.23, 0.3)), 0);
}
