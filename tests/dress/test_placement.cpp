// Placement of pattern pieces around a hand-built avatar: clearance kept, lengths
// kept, the right side of the body, outward normals, wide pieces do not overlap.
#include <gtest/gtest.h>

#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/pattern/draft.hpp"
#include "vgd/dress/placement.hpp"
#include "vgd/xvc/arrangement.hpp"

using namespace vgd;
using namespace vgd::dress;
using namespace vgd::body;
using pattern::Vec2;

namespace {

// A torso from y = 0.9 to 1.5 m whose elliptic rings widen towards the shoulders, and
// a left arm hanging from (0.2, 1.45, 0) down -Y.
Avatar hand_avatar() {
  Avatar a;
  a.source = "hand-built";
  BodySegment torso;
  torso.name = "torso";
  torso.start = Vec3(0, 0.9, 0);
  torso.length = 0.6;
  for (const auto& [s, w, d] : {std::tuple{0.0, 0.17, 0.11}, {0.25, 0.14, 0.10}, {0.45, 0.17, 0.12}, {0.6, 0.19, 0.11}})
    torso.rings.push_back({s, torso.start + s * Vec3::UnitY(), w, d});
  a.segments.push_back(torso);
  BodySegment arm;
  arm.name = "left-arm";
  arm.start = Vec3(0.2, 1.45, 0);
  arm.axis = -Vec3::UnitY();
  arm.length = 0.55;
  for (const double s : {0.0, 0.55}) arm.rings.push_back({s, arm.start + s * arm.axis, 0.05, 0.05});
  a.segments.push_back(arm);
  return a;
}

// Distance outside the ellipse (x: half_width along X, z: half_depth along Z) at the
// ring for this point's height; negative inside. Dense sampling is enough for a test.
double outside(const BodySegment& seg, const Vec3& p) {
  const double s = std::clamp(p.y() - seg.start.y(), 0.0, seg.length);
  SegmentRing r = seg.rings.front();
  for (std::size_t i = 1; i < seg.rings.size(); ++i)
    if (s <= seg.rings[i].s) {
      const double t = (s - seg.rings[i - 1].s) / (seg.rings[i].s - seg.rings[i - 1].s);
      r.half_width = (1 - t) * seg.rings[i - 1].half_width + t * seg.rings[i].half_width;
      r.half_depth = (1 - t) * seg.rings[i - 1].half_depth + t * seg.rings[i].half_depth;
      break;
    }
  const double x = p.x(), z = p.z();
  const bool in = (x / r.half_width) * (x / r.half_width) + (z / r.half_depth) * (z / r.half_depth) < 1;
  double best = 1e9;
  for (int k = 0; k < 20000; ++k) {
    const double t = 2 * M_PI * k / 20000;
    best = std::min(best, std::hypot(x - r.half_width * std::cos(t), z - r.half_depth * std::sin(t)));
  }
  return in ? -best : best;
}

// The outline with every edge split into pieces of at most 1 cm, like a mesh's
// boundary (a long straight edge becomes a chord across the curved surface).
std::vector<Vec2> outline_of(const pattern::Piece& p) {
  std::vector<Vec2> v;
  const auto& b = p.boundary;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const Vec2 a = b[i].p, c = b[(i + 1) % b.size()].p;
    const int n = std::max(1, static_cast<int>(std::ceil((c - a).norm() / 0.01)));
    for (int k = 0; k < n; ++k) v.push_back(a + (c - a) * (static_cast<double>(k) / n));
  }
  return v;
}

// A grid of n × m nodes over a w × h rectangle with its top centre at the origin, and
// its counter-clockwise triangles.
void grid(double w, double h, int n, int m, std::vector<Vec2>& nodes, std::vector<std::array<int, 3>>& tris) {
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) nodes.emplace_back(-w / 2 + w * i / n, -h + h * j / m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
}

}  // namespace

TEST(PiecePlacement, FrontAndBackKeepClearanceAndLengths) {
  const Avatar av = hand_avatar();
  const auto pieces = pattern::draft_tshirt(pattern::TShirtMeasurements{});
  for (const auto* p : {&pieces[0], &pieces[1]}) {
    SCOPED_TRACE(p->name);
    auto a = xvc::suggest_arrangement(*p, false).at(0);
    a.height = 1.5;  // top of the piece at the top of this torso
    const auto nodes = outline_of(*p);
    const auto placed = place_piece(nodes, a, av);
    ASSERT_EQ(placed.points.size(), nodes.size());
    double zsum = 0;
    for (const auto& q : placed.points) {
      EXPECT_GE(outside(av.segments[0], q), a.clearance - 1e-4);
      zsum += q.z();
    }
    if (p->name == "FRONT") EXPECT_GT(zsum / nodes.size(), 0.05);
    else EXPECT_LT(zsum / nodes.size(), -0.05);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::size_t j = (i + 1) % nodes.size();
      const double l2 = (nodes[j] - nodes[i]).norm(), l3 = (placed.points[j] - placed.points[i]).norm();
      // Half pieces follow the torso's taper: arc length round the body is
      // kept (horizontal edges within 1 %), lengths along it stretch by
      // √(1 + (dr/ds)²) where the radius changes (under 15 %), never shrink.
      const Vec2 d = nodes[j] - nodes[i];
      if (std::abs(d.y()) < 0.1 * std::abs(d.x())) {
        EXPECT_NEAR(l3, l2, 0.01 * l2 + 1e-6) << "edge " << i;
      }
      EXPECT_GE(l3, 0.99 * l2) << "edge " << i;
      EXPECT_LE(l3, 1.15 * l2) << "edge " << i;
    }
    // The reference point (top centre) sits at the arrangement's height.
    double top = -1e9;
    for (const auto& q : placed.points) top = std::max(top, q.y());
    EXPECT_NEAR(top, 1.5, 1e-9);
  }
}

TEST(PiecePlacement, NormalsPointAwayFromTheBody) {
  const Avatar av = hand_avatar();
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 3>> tris;
  grid(0.5, 0.4, 20, 8, nodes, tris);
  for (const char* side : {"front", "back", "left", "right"}) {
    xvc::Arrangement a;
    a.side = side;
    a.height = 1.4;
    const auto placed = place_piece(nodes, a, av);
    for (const auto& t : tris) {
      const Vec3 &p0 = placed.points[t[0]], &p1 = placed.points[t[1]], &p2 = placed.points[t[2]];
      const Vec3 n = (p1 - p0).cross(p2 - p0);
      Vec3 out = (p0 + p1 + p2) / 3 - placed.axis_point;
      out.y() = 0;
      EXPECT_GT(n.dot(out), 0) << side;
    }
    // Flipped: the winding reverses, as reported.
    a.flip = true;
    const auto f = place_piece(nodes, a, av);
    EXPECT_TRUE(f.reverses_winding);
    const auto& t = tris[0];
    const Vec3 n = (f.points[t[1]] - f.points[t[0]]).cross(f.points[t[2]] - f.points[t[0]]);
    Vec3 out = f.points[t[0]] - f.axis_point;
    out.y() = 0;
    EXPECT_LT(n.dot(out), 0) << side;
  }
}

TEST(PiecePlacement, LeftSleeveGoesOnTheLeftArm) {
  const Avatar av = hand_avatar();
  const auto pieces = pattern::draft_tshirt(pattern::TShirtMeasurements{});
  auto a = xvc::suggest_arrangement(pieces[2], false).at(0);
  ASSERT_EQ(a.segment, "left-arm");
  EXPECT_EQ(a.height, xvc::ArrangementOptions{}.sleeve_drop) << "sleeves start down the arm, clear of the bodice";
  a.height = 0.0;  // cap top at the arm's shoulder end
  const auto placed = place_piece(outline_of(pieces[2]), a, av);
  double xsum = 0, ymax = -1e9;
  for (const auto& q : placed.points) {
    xsum += q.x();
    ymax = std::max(ymax, q.y());
    EXPECT_GE(std::hypot(q.x() - 0.2, q.z()), 0.05 + a.clearance - 1e-4);
  }
  EXPECT_GT(xsum / placed.points.size(), 0.15) << "the left arm (at x = 0.2) is on +X";
  EXPECT_NEAR(ymax, 1.45, 1e-9) << "the cap top at the shoulder";
  EXPECT_EQ(placed.clearance, a.clearance) << "0.34 m of sleeve fits round a 0.08 m offset circle";
}

TEST(PiecePlacement, WidePiecesWrapWithoutOverlapping) {
  const Avatar av = hand_avatar();
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 3>> tris;
  grid(1.6, 0.2, 160, 2, nodes, tris);  // wider than the torso's girth
  xvc::Arrangement a;
  a.height = 1.3;
  const auto placed = place_piece(nodes, a, av);
  // Along the top row, the angle around the axis increases monotonically and turns
  // less than once.
  double total = 0, prev = std::atan2(placed.points[0].x(), placed.points[0].z());
  for (int i = 1; i <= 160; ++i) {
    const auto& q = placed.points[i];
    const double ang = std::atan2(q.x(), q.z());
    double d = ang - prev;
    if (d < -M_PI) d += 2 * M_PI;
    if (d > M_PI) d -= 2 * M_PI;
    EXPECT_GT(d, 0.0) << i;
    total += d;
    prev = ang;
  }
  EXPECT_LT(total, 2 * M_PI);
  EXPECT_GT(total, M_PI);
}

// A garment worn over another (a T-shirt over a skirt) starts outside it:
// the cloth under it bounds the rings like the body. Points of another
// segment (an arm's sleeve) do not.
TEST(PiecePlacement, StartsOutsideTheClothUnderIt) {
  const Avatar av = hand_avatar();
  const auto pieces = pattern::draft_tshirt(pattern::TShirtMeasurements{});
  auto a = xvc::suggest_arrangement(pieces[0], false).at(0);  // the front
  a.height = 1.5;
  const auto nodes = outline_of(pieces[0]);
  const auto alone = place_piece(nodes, a, av);

  // A skirt's top: an elliptic band 6 cm out from the torso's lowest rings, from 0.8 to 1.05 m.
  BodySegment band;
  band.start = Vec3(0, 0.8, 0);
  band.length = 0.25;
  band.rings = {{0.0, band.start, 0.23, 0.17}, {0.25, band.start + 0.25 * Vec3::UnitY(), 0.23, 0.17}};
  Underlayer skirt{"hips", {}};  // the trunk is one segment for this
  for (int j = 0; j <= 25; ++j)
    for (int k = 0; k < 360; ++k) {
      const double t = 2 * M_PI * k / 360;
      skirt.points.emplace_back(0.23 * std::cos(t), 0.8 + 0.01 * j, 0.17 * std::sin(t));
    }
  const auto over = place_piece(nodes, a, av, {skirt});
  int in_band = 0;
  for (const auto& q : over.points)
    if (q.y() >= 0.8 && q.y() <= 1.05) {
      ++in_band;
      EXPECT_GE(outside(band, q), kUnderlayerGap - 1e-3) << q.transpose();
    }
  EXPECT_GT(in_band, 10);
  // Without the skirt the same points start inside it.
  int inside_skirt = 0;
  for (const auto& q : alone.points)
    if (q.y() >= 0.8 && q.y() <= 1.05 && outside(band, q) < 0) ++inside_skirt;
  EXPECT_GT(inside_skirt, 10);

  // An arm's cloth leaves the torso's piece where it was.
  Underlayer sleeve{"left-arm", skirt.points};
  const auto with_sleeve = place_piece(nodes, a, av, {sleeve});
  ASSERT_EQ(with_sleeve.points.size(), alone.points.size());
  for (std::size_t i = 0; i < alone.points.size(); ++i)
    EXPECT_LT((with_sleeve.points[i] - alone.points[i]).norm(), 1e-12);
}

// Trousers cut to the floor: the half legs reach past the leg's last ring
// (the ankle) and go round the foot there instead of through it; above the
// foot they follow the leg as before, and the foot of the other leg does not
// push them out.
TEST(PiecePlacement, AHalfLegCutToTheFloorStartsRoundTheFoot) {
  Avatar av;
  av.source = "hand-built legs";
  // Feet: ellipsoids 26 cm long, 9 cm wide, 8 cm tall, standing on y = 0, their
  // centres 5 cm in front of the ankles (at x = ±0.1).
  const auto foot_at = [](double x, const Vec3& p) {
    const Vec3 c(x, 0.04, 0.05), r(0.045, 0.04, 0.13);
    const Vec3 q = (p - c).cwiseQuotient(r);
    return q.squaredNorm();  // < 1 inside
  };
  for (const double x : {0.1, -0.1}) {
    BodySegment leg;
    leg.name = x > 0 ? "left-leg" : "right-leg";
    leg.start = Vec3(x, 0.9, 0);
    leg.axis = -Vec3::UnitY();
    leg.length = 0.8;  // hip joint to ankle, 10 cm above the floor
    leg.front = Vec3::UnitZ();
    for (const auto& [s, r] : {std::pair{0.0, 0.08}, {0.4, 0.05}, {0.8, 0.04}})
      leg.rings.push_back({s, leg.start + s * leg.axis, r, r});
    av.segments.push_back(leg);
    for (int i = 0; i <= 24; ++i)
      for (int k = 0; k < 48; ++k) {
        const double th = M_PI * i / 24, ph = 2 * M_PI * k / 48;
        av.surface.vertices.emplace_back(x + 0.045 * std::sin(th) * std::cos(ph), 0.04 + 0.04 * std::cos(th),
                                         0.05 + 0.13 * std::sin(th) * std::sin(ph));
      }
  }
  // The front half of the left leg: 22 cm wide, from the waist (5 cm above the
  // hip joint) to 5 mm below the floor.
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 3>> tris;
  grid(0.22, 0.955, 22, 96, nodes, tris);
  xvc::Arrangement a;
  a.segment = "left-leg";
  a.side = "front";
  a.height = -0.05;
  a.clearance = 0.01;
  const auto placed = place_piece(nodes, a, av);
  double lowest = 1e9;
  int below_ankle = 0;
  for (const auto& q : placed.points) {
    lowest = std::min(lowest, q.y());
    EXPECT_GT(foot_at(0.1, q), 1.0) << "inside the foot: " << q.transpose();
    if (q.y() < 0.1) ++below_ankle;
    if (q.y() > 0.4) {  // the shin and up: the leg's rings and the clearance, as before the foot
      const double r = std::hypot(q.x() - 0.1, q.z());
      const double s = std::clamp(0.9 - q.y(), 0.0, 0.8);
      const double ring = s < 0.4 ? 0.08 - 0.03 * s / 0.4 : 0.05 - 0.01 * (s - 0.4) / 0.4;
      EXPECT_GT(r, ring + 0.01 - 2e-3) << q.transpose();
      EXPECT_LT(r, 0.13) << "pushed out by a foot 30 cm below: " << q.transpose();
    }
  }
  EXPECT_NEAR(lowest, -0.005, 1e-3);
  EXPECT_GT(below_ankle, 100);

  // Without the feet the same piece starts through the foot.
  Avatar bare = av;
  bare.surface.vertices.clear();
  int inside = 0;
  for (const auto& q : place_piece(nodes, a, bare).points)
    if (foot_at(0.1, q) < 1.0) ++inside;
  EXPECT_GT(inside, 50);
}

// A whole leg (leggings, tights: one piece round the leg, its inseam's edges
// meeting on the inside) goes once round its leg at every height: where the
// piece is narrower than the leg (negative ease at the ankle) it lies at the
// clearance from that height's ring, its edges apart by the difference; where
// it is wider (the top) the clearance grows until its edges are the gap apart.
// On one cylinder as wide as its top, the ankle lay 5 cm off the leg.
TEST(PiecePlacement, AWholeLegGoesOnceRoundItsLegAtEveryHeight) {
  Avatar av;
  av.source = "hand-built legs";
  for (const double x : {0.1, -0.1}) {
    BodySegment leg;
    leg.name = x > 0 ? "left-leg" : "right-leg";
    leg.start = Vec3(x, 0.9, 0);
    leg.axis = -Vec3::UnitY();
    leg.length = 0.8;
    leg.front = Vec3::UnitZ();
    for (const auto& [s, r] : {std::pair{0.0, 0.08}, {0.4, 0.05}, {0.8, 0.04}})
      leg.rings.push_back({s, leg.start + s * leg.axis, r, r});
    av.segments.push_back(leg);
  }
  const auto ring = [](double s) { return s < 0.4 ? 0.08 - 0.03 * s / 0.4 : 0.05 - 0.01 * (s - 0.4) / 0.4; };
  // 70 cm long, 60 cm wide at the top (more than the 50 cm round the leg
  // there), 20 cm at the bottom (less than the 25 cm round the leg there).
  const int n = 60, m = 70;
  const auto width = [&](double depth) { return 0.6 - 0.4 * depth / 0.7; };
  std::vector<Vec2> nodes;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) {
      const double depth = 0.7 * j / m;
      nodes.emplace_back(width(depth) * (static_cast<double>(i) / n - 0.5), -depth);
    }
  xvc::Arrangement a;
  a.segment = "left-leg";
  a.side = "left";
  a.height = 0.0;
  a.clearance = 0.01;
  const auto placed = place_piece(nodes, a, av);
  ASSERT_EQ(placed.points.size(), nodes.size());
  for (int j = 0; j <= m; j += 5) {
    const double depth = 0.7 * j / m;
    double turned = 0, along = 0;
    double prev = std::atan2(placed.points[j * (n + 1)].z(), placed.points[j * (n + 1)].x() - 0.1);
    for (int i = 0; i <= n; ++i) {
      const Vec3& q = placed.points[j * (n + 1) + i];
      EXPECT_NEAR(q.y(), 0.9 - depth, 1e-9);
      const double r = std::hypot(q.x() - 0.1, q.z());
      // Off its ring by the clearance, or more where it is wider than the leg
      // (the rings within 3 cm above bound it too), never inside it.
      EXPECT_GT(r, ring(depth) + 0.01 - 1e-3) << "row " << j << ", node " << i;
      // Narrower than the leg within 5 cm (the grown clearance spreads 3 cm
      // up and down from where the piece is wider): at the clearance.
      if (width(std::max(0.0, depth - 0.05)) + 0.02 < 2 * M_PI * (ring(depth) + 0.01)) {
        EXPECT_LT(r, ring(std::max(0.0, depth - 0.03)) + 0.01 + 1e-3) << "row " << j << ", node " << i;
      }
      if (i > 0) {
        const double ang = std::atan2(q.z(), q.x() - 0.1);
        double d = ang - prev;
        if (d < -M_PI) d += 2 * M_PI;
        if (d > M_PI) d -= 2 * M_PI;
        turned += d;
        prev = ang;
        along += (q - placed.points[j * (n + 1) + i - 1]).norm();
      }
    }
    // Once round at most, the widths kept (chords of 1 cm arcs).
    EXPECT_LT(std::abs(turned), 2 * M_PI) << "row " << j;
    EXPECT_NEAR(along, width(depth), 0.01 * width(depth)) << "row " << j;
    // At the top the edges meet the gap apart: nearly once round.
    if (j == 0) {
      EXPECT_GT(std::abs(turned), 2 * M_PI * 0.9);
    }
  }
}

TEST(PiecePlacement, MissingSegmentIsAnError) {
  xvc::Arrangement a;
  a.segment = "neck";
  try {
    place_piece({Vec2(0, 0)}, a, hand_avatar());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("neck"), std::string::npos);
  }
}
