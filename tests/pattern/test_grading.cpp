// Carrying the sample size's turn points and notches to graded sizes.
#include <gtest/gtest.h>

#include <cmath>

#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/grading.hpp"

using namespace vgd::pattern;

namespace {

// A shirt-front-like outline (m): straight hem and side, a curved armhole and
// neckline, corners marked as turn points and one notch on the side.
Piece sample_piece() {
  Piece p;
  p.name = "FRONT";
  p.size = "50";
  p.block = "FRONT_50";
  const std::vector<Vec2> pts = {{0, 0}, {0.25, 0}, {0.25, 0.40}, {0.24, 0.44}, {0.22, 0.47}, {0.20, 0.50},
                                 {0.19, 0.56}, {0.08, 0.60}, {0.06, 0.57}, {0.03, 0.55}, {0, 0.54}};
  for (const auto& q : pts) p.boundary.push_back({q, PointKind::plain});
  for (int i : {0, 1, 2, 6, 7, 10}) p.boundary[i].kind = PointKind::turn;
  for (int i : {3, 4, 5, 8, 9}) p.boundary[i].kind = PointKind::curve;
  Notch n;
  n.position = {0.25, 0.18};
  n.angle_deg = 180;
  n.boundary_index = nearest_vertex(p.boundary, n.position).index;
  p.notches.push_back(n);
  return p;
}

// The same piece graded: lengths and widths grow by different factors, the
// piece sits elsewhere on the marker, and the marks are gone.
Piece graded(const Piece& s, double sx, double sy, const Vec2& shift, const std::string& size) {
  Piece g = s;
  g.size = size;
  g.block = "FRONT_" + size;
  g.notches.clear();
  for (auto& c : g.boundary) {
    c.p = Vec2(sx * c.p.x(), sy * c.p.y()) + shift;
    c.kind = PointKind::plain;
  }
  return g;
}

}  // namespace

TEST(CarryMarks, AGradedOutlineTakesTheSampleMarksAtTheSameVertices) {
  const Piece s = sample_piece();
  Piece g = graded(s, 1.08, 1.03, {1.5, -0.2}, "56");
  const CarriedMarks c = carry_marks(s, g);
  ASSERT_TRUE(c.carried) << c.why;
  EXPECT_EQ(c.turns, 6);
  EXPECT_EQ(c.curves, 5);
  EXPECT_EQ(c.unpaired, 0);
  EXPECT_LT(c.rms_m, 1e-9) << "an affine grading is undone exactly";
  for (std::size_t i = 0; i < s.boundary.size(); ++i) EXPECT_EQ(g.boundary[i].kind, s.boundary[i].kind) << i;
  ASSERT_EQ(g.notches.size(), 1u);
  // The notch at the same fraction of the side seam: 0.18 of 0.40 up it.
  EXPECT_NEAR(g.notches[0].position.x(), 1.08 * 0.25 + 1.5, 1e-9);
  EXPECT_NEAR(g.notches[0].position.y(), 1.03 * 0.18 - 0.2, 1e-9);
  EXPECT_NEAR(g.notches[0].angle_deg, 180, 1e-9);
}

TEST(CarryMarks, AnExtraVertexAndAnotherStartAreAligned) {
  const Piece s = sample_piece();
  Piece g = graded(s, 0.95, 0.97, {0, 0}, "46");
  // A point added half way along the hem, and the outline starting at vertex 4.
  g.boundary.insert(g.boundary.begin() + 1, ContourPoint{0.5 * (g.boundary[0].p + g.boundary[1].p), PointKind::plain});
  std::rotate(g.boundary.begin(), g.boundary.begin() + 4, g.boundary.end());
  const CarriedMarks c = carry_marks(s, g);
  ASSERT_TRUE(c.carried) << c.why;
  EXPECT_EQ(c.turns, 6);
  EXPECT_EQ(c.unpaired, 0);
  int turns = 0;
  for (const auto& q : g.boundary) turns += q.kind == PointKind::turn;
  EXPECT_EQ(turns, 6);
  // It starts again where the sample starts: stretch k is the same stretch in both.
  EXPECT_LT(g.boundary[0].p.norm(), 1e-12);
  // The inserted point stays plain; the hem's corners are turns.
  for (const auto& q : g.boundary) {
    if ((q.p - Vec2(0, 0)).norm() < 1e-12 || (q.p - Vec2(0.95 * 0.25, 0)).norm() < 1e-12) {
      EXPECT_EQ(q.kind, PointKind::turn);
    }
    if ((q.p - Vec2(0.95 * 0.125, 0)).norm() < 1e-12) {
      EXPECT_EQ(q.kind, PointKind::plain);
    }
  }
}

TEST(CarryMarks, AnotherShapeOrAMarkedBlockIsLeftAlone) {
  const Piece s = sample_piece();
  Piece square;
  square.block = "FRONT_58";
  for (const auto& q : std::vector<Vec2>{{0, 0}, {0.3, 0}, {0.3, 0.3}, {0, 0.3}}) square.boundary.push_back({q, PointKind::plain});
  const Piece before = square;
  const CarriedMarks c = carry_marks(s, square);
  EXPECT_FALSE(c.carried);
  EXPECT_NE(c.why.find("does not correspond"), std::string::npos) << c.why;
  for (std::size_t i = 0; i < square.boundary.size(); ++i) EXPECT_EQ(square.boundary[i].kind, PointKind::plain);
  EXPECT_TRUE(square.notches.empty());

  // A block with marks of its own (as many turn points and notches) keeps them.
  Piece own = graded(s, 1.0, 1.0, {0, 0}, "52");
  for (int i : {0, 2, 4, 6, 8, 10}) own.boundary[i].kind = PointKind::turn;
  own.notches.push_back(s.notches[0]);
  const CarriedMarks kept = carry_marks(s, own);
  EXPECT_FALSE(kept.carried);
  EXPECT_EQ(own.boundary[1].kind, PointKind::plain);
  EXPECT_EQ(own.boundary[3].kind, PointKind::plain);

  // A block with a stray turn point of its own keeps it and takes the sample's.
  Piece stray = graded(s, 1.0, 1.0, {0, 0}, "54");
  stray.boundary[3].kind = PointKind::turn;
  ASSERT_TRUE(carry_marks(s, stray).carried);
  EXPECT_EQ(stray.boundary[3].kind, PointKind::turn);
  EXPECT_EQ(stray.boundary[7].kind, PointKind::turn);
  EXPECT_EQ(stray.notches.size(), 1u);
}

TEST(CarryMarks, SizesTakeTheirMarksFromTheNeighbourOutwardsFromTheSample) {
  Style st;
  st.sample_size = "50";
  st.sizes = {"42", "46", "50", "54", "58"};
  const Piece s = sample_piece();
  for (const auto& [size, k] : std::vector<std::pair<std::string, double>>{{"42", 0.84}, {"46", 0.92}, {"54", 1.08}, {"58", 1.16}})
    st.pieces.push_back(graded(s, k, 1 + 0.4 * (k - 1), {0, 0}, size));
  st.pieces.push_back(s);
  const auto carried = carry_sample_marks(st);
  ASSERT_EQ(carried.size(), 4u);
  for (const auto& [block, c] : carried) EXPECT_TRUE(c.carried) << block << ": " << c.why;
  for (const auto& p : st.pieces) {
    int turns = 0;
    for (const auto& q : p.boundary) turns += q.kind == PointKind::turn;
    EXPECT_EQ(turns, 6) << p.block;
    EXPECT_EQ(p.notches.size(), 1u) << p.block;
  }
}

// Corners of an outline that marks none (Valentina, CLO): a 30 x 40 cm
// panel drawn every 2 mm, three square corners and the fourth rounded with a
// 3 cm radius in 2-degree steps. The square corners are found, one turn point
// each; the rounded one, turning 2 degrees per vertex, is a curve.
TEST(MarkCorners, SquareCornersAreTurnsAndARoundedCornerIsNot) {
  std::vector<ContourPoint> o;
  auto line = [&](Vec2 a, Vec2 b) {
    const int n = static_cast<int>(std::ceil((b - a).norm() / 0.002));
    for (int k = 0; k < n; ++k) o.push_back({a + (b - a) * (static_cast<double>(k) / n), PointKind::plain});
  };
  const double r = 0.03;
  line({0, 0}, {0.30, 0});
  line({0.30, 0}, {0.30, 0.40 - r});
  for (int deg = 0; deg < 90; deg += 2)
    o.push_back({Vec2(0.30 - r, 0.40 - r) + r * Vec2(std::cos(deg * M_PI / 180), std::sin(deg * M_PI / 180)), PointKind::plain});
  line({0.30 - r, 0.40}, {0, 0.40});
  line({0, 0.40}, {0, 0});
  EXPECT_EQ(mark_corners(o), 3);
  std::vector<Vec2> corners;
  for (const auto& c : o)
    if (c.kind == PointKind::turn) corners.push_back(c.p);
  ASSERT_EQ(corners.size(), 3u);
  for (const Vec2& want : {Vec2(0, 0), Vec2(0.30, 0), Vec2(0, 0.40)}) {
    bool found = false;
    for (const auto& c : corners) found = found || (c - want).norm() < 1e-9;
    EXPECT_TRUE(found) << want.transpose();
  }
  EXPECT_EQ(mark_corners(o), 0) << "marked once";
}

// A leg's waist end is wider than its hem: measured across the given up
// direction, whichever way the outline is drawn.
TEST(WiderAtTop, TellsTheWaistEndOfALegFromItsHem) {
  // A tapered leg, waist (40 cm) at y = 1, hem (15 cm) at y = 0.
  const std::vector<ContourPoint> leg = {
      {{0.125, 0.0}, PointKind::turn}, {{0.275, 0.0}, PointKind::turn}, {{0.4, 1.0}, PointKind::turn}, {{0.0, 1.0}, PointKind::turn}};
  EXPECT_TRUE(wider_at_top(leg, Vec2(0, 1)));
  EXPECT_FALSE(wider_at_top(leg, Vec2(0, -1)));
  // Drawn sideways (waist at x = 1): +x is up.
  std::vector<ContourPoint> sideways = leg;
  for (auto& c : sideways) c.p = Vec2(c.p.y(), -c.p.x());
  EXPECT_TRUE(wider_at_top(sideways, Vec2(1, 0)));
  EXPECT_FALSE(wider_at_top(sideways, Vec2(-1, 0)));
  // The widths among the vertices of each end's 15 %, and the length.
  const EndWidths w = end_widths(leg, Vec2(0, 1));
  EXPECT_NEAR(w.bottom, 0.15, 1e-12);
  EXPECT_NEAR(w.top, 0.40, 1e-12);
  EXPECT_NEAR(w.length, 1.0, 1e-12);
  const EndWidths s = end_widths(sideways, Vec2(-1, 0));
  EXPECT_NEAR(s.bottom, 0.40, 1e-12) << "up reversed: the waist is the bottom end";
  EXPECT_NEAR(s.top, 0.15, 1e-12);
}
