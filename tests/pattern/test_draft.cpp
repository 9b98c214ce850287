// The drafted skirt fits its measurements and its pieces sew together.
#include <gtest/gtest.h>

#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/draft.hpp"

using namespace vgd::pattern;

namespace {

// Width of the outline along the horizontal line y (max x - min x of the crossings).
double width_at(const Piece& p, double y) {
  double lo = 1e9, hi = -1e9;
  const auto& o = p.boundary;
  for (std::size_t i = 0; i < o.size(); ++i) {
    const Vec2 a = o[i].p, b = o[(i + 1) % o.size()].p;
    if ((a.y() - y) * (b.y() - y) > 0 || a.y() == b.y()) continue;
    const double x = a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return hi - lo;
}

// Length of the boundary between the vertices nearest to two points, going CCW.
double arc_length(const Piece& p, const Vec2& from, const Vec2& to) {
  const int n = static_cast<int>(p.boundary.size());
  int i = nearest_vertex(p.boundary, from).index;
  const int j = nearest_vertex(p.boundary, to).index;
  double len = 0;
  while (i != j) {
    len += (p.boundary[(i + 1) % n].p - p.boundary[i].p).norm();
    i = (i + 1) % n;
  }
  return len;
}

}  // namespace

TEST(SkirtDraft, PiecesAreCleanOutlines) {
  for (const auto& m : skirt_size_table()) {
    for (const auto& p : draft_skirt(m)) {
      SCOPED_TRACE(p.block);
      EXPECT_GT(signed_area(p.boundary), 0.0);
      EXPECT_FALSE(is_self_intersecting(p.boundary));
      EXPECT_TRUE(p.grain_line.has_value());
      auto copy = p.boundary;
      EXPECT_EQ(remove_duplicate_vertices(copy), 0);
      for (const auto& n : p.notches) EXPECT_LT(nearest_edge(p.boundary, n.position).distance, 1e-9);
    }
  }
}

TEST(SkirtDraft, PanelsHaveTheHipWidthPlusEase) {
  SkirtMeasurements m;
  const auto pieces = draft_skirt(m);
  const double hip_y = m.length - m.hip_depth;
  EXPECT_NEAR(width_at(pieces[0], hip_y) + width_at(pieces[1], hip_y), m.hip + m.hip_ease, 1e-9);
  EXPECT_NEAR(width_at(pieces[0], 1e-9), (m.hip + m.hip_ease) / 2 + 2 * m.flare, 1e-6);
}

TEST(SkirtDraft, WaistSeamsFitTheWaistband) {
  SkirtMeasurements m;
  const auto pieces = draft_skirt(m);
  // The waist curve runs between the two waist corners (the turn points at the top).
  auto waist_length = [&](const Piece& p) {
    Vec2 right(-1e9, 0), left(1e9, 0);
    for (const auto& c : p.boundary)
      if (c.kind == PointKind::turn && c.p.y() > m.length / 2) {
        if (c.p.x() > right.x()) right = c.p;
        if (c.p.x() < left.x()) left = c.p;
      }
    return arc_length(p, right, left);
  };
  const double skirt_waist = waist_length(pieces[0]) + waist_length(pieces[1]);
  EXPECT_NEAR(skirt_waist, m.waist + m.waist_ease, 0.02 * m.waist) << "waist seam vs body";
  const auto& band = pieces[2];
  EXPECT_NEAR(width_at(band, 0.01), m.waist + m.waist_ease + m.waistband_overlap, 1e-9);
}

TEST(SkirtDraft, SideSeamsOfFrontAndBackHaveEqualLength) {
  SkirtMeasurements m;
  const auto pieces = draft_skirt(m);
  for (const auto* p : {&pieces[0], &pieces[1]}) {
    // Right side seam: hem corner to waist corner.
    Vec2 hem(-1e9, 0), waist(-1e9, 0);
    for (const auto& c : p->boundary) {
      if (c.p.y() == 0 && c.p.x() > hem.x()) hem = c.p;
      if (c.kind == PointKind::turn && c.p.y() > m.length / 2 && c.p.x() > waist.x()) waist = c.p;
    }
    EXPECT_NEAR(arc_length(*p, hem, waist), arc_length(pieces[0], hem, waist), 1e-9);
  }
}

TEST(SkirtDraft, BackHasDoubleNotchesStraddlingTheFrontNotch) {
  const auto pieces = draft_skirt(SkirtMeasurements{});
  auto right_side = [](const Piece& p) {
    std::vector<double> ys;
    for (const auto& n : p.notches)
      if (n.position.x() > 0.05) ys.push_back(n.position.y());
    std::sort(ys.begin(), ys.end());
    return ys;
  };
  const auto front = right_side(pieces[0]), back = right_side(pieces[1]);
  ASSERT_EQ(front.size(), 1u);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_NEAR((back[0] + back[1]) / 2, front[0], 1e-12);
}

TEST(SkirtDraft, ImpossibleMeasurementsAreRefused) {
  SkirtMeasurements m;
  m.waist = 1.2;
  EXPECT_THROW(draft_skirt(m), vgd::Error);
  m = {};
  m.length = -0.1;
  EXPECT_THROW(draft_skirt(m), vgd::Error);
  m = {};
  m.hip_depth = 0.7;
  EXPECT_THROW(draft_skirt(m), vgd::Error);
}

TEST(SkirtDraft, SizesGradeUpwards) {
  const auto style = draft_skirt_style();
  EXPECT_EQ(style.sizes.size(), 5u);
  EXPECT_EQ(style.sample_size, "38");
  double last = 0;
  for (const auto* p : [&] {
         std::vector<const Piece*> fronts;
         for (const auto& q : style.pieces)
           if (q.name == "FRONT") fronts.push_back(&q);
         return fronts;
       }()) {
    const double a = signed_area(p->boundary);
    EXPECT_GT(a, last);
    last = a;
  }
}
