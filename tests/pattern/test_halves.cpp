// Pieces written once per side (pattern/halves.hpp) and roles from shapes
// (pattern/shape_roles.hpp), on generated outlines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/halves.hpp"
#include "vgd/pattern/shape_roles.hpp"

using namespace vgd::pattern;

namespace {

// The left half of a front, its centre edge on x = 0 from the neck down to
// the hem (0.6 m), drawn counter-clockwise: hem, side, armhole, shoulder,
// neck (a scoop 0.1 m deep), centre. `x0` moves it.
Piece half_front(const std::string& name, double x0 = 0.0) {
  Piece p;
  p.block = name + "_M";
  p.name = name;
  p.size = "M";
  const double pts[][2] = {{0, 0},      {0.25, 0},   {0.25, 0.45}, {0.22, 0.50}, {0.19, 0.54}, {0.18, 0.64},
                           {0.08, 0.68}, {0.05, 0.63}, {0.02, 0.60}, {0, 0.58}};
  for (const auto& q : pts) p.boundary.push_back({Vec2(x0 - q[0], q[1])});  // x mirrored: the centre on the right
  std::reverse(p.boundary.begin(), p.boundary.end());                        // keep it counter-clockwise
  p.grain_line = Segment{Vec2(x0 - 0.1, 0.1), Vec2(x0 - 0.1, 0.4)};
  return p;
}

// `p` reflected across x = 0 and moved by dx, counter-clockwise again.
Piece mirrored(Piece p, const std::string& name, double dx) {
  p.block = name + "_M";
  p.name = name;
  for (auto& c : p.boundary) c.p = Vec2(-c.p.x() + dx, c.p.y());
  std::reverse(p.boundary.begin(), p.boundary.end());
  p.grain_line = Segment{Vec2(-p.grain_line->a.x() + dx, p.grain_line->a.y()), Vec2(-p.grain_line->b.x() + dx, p.grain_line->b.y())};
  return p;
}

// A short sleeve: a bell-shaped cap 0.15 m high over a 0.45 m base, the
// sides slanting in to a 0.34 m hem 0.1 m lower.
Piece sleeve(const std::string& name, double dx) {
  Piece p;
  p.block = name + "_M";
  p.name = name;
  p.size = "M";
  p.boundary.push_back({Vec2(dx + 0.055, 0)});
  p.boundary.push_back({Vec2(dx + 0.395, 0)});
  for (int k = 0; k <= 20; ++k) {
    const double t = k / 20.0, x = 0.45 * (1 - t);
    const double bell = 0.15 * std::exp(-std::pow((x - 0.225) / 0.1, 2));
    p.boundary.push_back({Vec2(dx + x, 0.1 + bell)});
  }
  p.grain_line = Segment{Vec2(dx + 0.225, 0.02), Vec2(dx + 0.225, 0.2)};
  return p;
}

double area_of(const Piece& p) { return std::abs(signed_area(p.boundary)); }

}  // namespace

// CLO's way: the left and right halves of a front as two blocks, cut once
// each, and a sleeve written twice. The halves become one front (twice the
// area, symmetric about its centre edge), the sleeves one sleeve cut twice.
TEST(PiecesPerSide, MirrorHalvesAreJoinedAndASleeveWrittenTwiceIsCutTwice) {
  Style s;
  s.pieces = {half_front("11"), sleeve("36", 2.0), mirrored(half_front("11"), "37", 1.0), sleeve("39", 3.0)};
  const double half = area_of(s.pieces[0]);
  const auto joined = join_pieces_written_per_side(s);
  ASSERT_EQ(joined.size(), 2u);
  EXPECT_TRUE(joined[0].halves);
  EXPECT_EQ(joined[0].kept, "11_M");
  EXPECT_EQ(joined[0].dropped, "37_M");
  EXPECT_NEAR(joined[0].centre_length, 0.58, 1e-9);
  EXPECT_FALSE(joined[1].halves);
  EXPECT_EQ(joined[1].dropped, "39_M");
  ASSERT_EQ(s.pieces.size(), 2u);
  const Piece& front = s.pieces[0];
  EXPECT_NEAR(area_of(front), 2 * half, 1e-9);
  EXPECT_EQ(front.quantity, 1);
  EXPECT_FALSE(is_self_intersecting(front.boundary));
  // Symmetric about the centre edge (x = 0): every vertex has its mirror image.
  for (const auto& c : front.boundary)
    EXPECT_LT(nearest_vertex(front.boundary, Vec2(-c.p.x(), c.p.y())).distance, 1e-9);
  EXPECT_EQ(s.pieces[1].name, "36");
  EXPECT_EQ(s.pieces[1].quantity, 2);
  EXPECT_NE(describe(joined[0]).find("joined along their 58.0 cm centre edge into 11_M"), std::string::npos);
}

// Left alone: pieces whose names give a role (a placket and its interfacing
// may share an outline), pieces of different sizes or categories, pieces cut
// twice already, and a mirror pair whose straight edge is shorter than 40 %
// of its length (not a centre).
TEST(PiecesPerSide, NamedPiecesAndOtherSizesAreLeftAlone) {
  Style s;
  s.pieces = {half_front("FRONT"), mirrored(half_front("FRONT"), "FRONT", 1.0)};
  s.pieces[1].block = "FRONT2_M";
  EXPECT_TRUE(join_pieces_written_per_side(s).empty());
  EXPECT_EQ(s.pieces.size(), 2u);

  Style sizes;
  sizes.pieces = {half_front("11"), mirrored(half_front("11"), "37", 1.0)};
  sizes.pieces[1].size = "L";
  EXPECT_TRUE(join_pieces_written_per_side(sizes).empty());

  Style category;
  category.pieces = {half_front("11"), mirrored(half_front("11"), "37", 1.0)};
  category.pieces[1].category = "LINING";
  EXPECT_TRUE(join_pieces_written_per_side(category).empty());

  Style twice;
  twice.pieces = {half_front("11"), mirrored(half_front("11"), "37", 1.0)};
  twice.pieces[0].quantity = 2;
  EXPECT_TRUE(join_pieces_written_per_side(twice).empty());

  Style different;
  different.pieces = {half_front("11"), mirrored(half_front("11"), "37", 1.0)};
  different.pieces[1].boundary[3].p.y() += 0.01;  // 1 cm off: not the same piece
  EXPECT_TRUE(join_pieces_written_per_side(different).empty());
}

// Valentina's way: a shirt whose front and back are drawn as halves, cut
// once, no side or fold line, and one sleeve. The halves are unfolded about
// their centre edges (twice the area, symmetric), the sleeve is cut twice;
// a whole piece (its own mirror image) and a sleeve naming its side are left
// as they are.
TEST(TopHalves, HalvesOfAShirtDrawnOnceAreUnfoldedAndItsSleeveCutTwice) {
  Style s;
  s.name = "shirt";
  s.pieces = {half_front("FRONT PANEL"), half_front("BACK PANEL", 1.0), sleeve("SLEEVE", 2.0)};
  Piece yoke;  // a whole piece with a straight edge on each side
  yoke.block = "BACK YOKE_M";
  yoke.name = "BACK YOKE";
  yoke.size = "M";
  yoke.boundary = {{Vec2(3.0, 0)}, {Vec2(3.4, 0)}, {Vec2(3.4, 0.3)}, {Vec2(3.0, 0.3)}};
  s.pieces.push_back(yoke);
  const double half = area_of(s.pieces[0]);
  const auto h = unfold_top_halves(s);
  ASSERT_EQ(h.unfolded.size(), 2u);
  EXPECT_EQ(h.unfolded[0].block, "FRONT PANEL_M");
  EXPECT_NEAR(h.unfolded[0].centre_length, 0.58, 1e-9);
  EXPECT_EQ(h.unfolded[1].block, "BACK PANEL_M");
  for (int i = 0; i < 2; ++i) {
    const Piece& p = s.pieces[i];
    EXPECT_NEAR(area_of(p), 2 * half, 1e-9) << p.name;
    EXPECT_FALSE(is_self_intersecting(p.boundary));
    const double centre = i == 0 ? 0.0 : 1.0;
    for (const auto& c : p.boundary)
      EXPECT_LT(nearest_vertex(p.boundary, Vec2(2 * centre - c.p.x(), c.p.y())).distance, 1e-9) << p.name;
  }
  EXPECT_EQ(s.pieces[2].quantity, 2);
  EXPECT_EQ(h.sleeves_cut_twice, std::vector<std::string>{"SLEEVE_M"});
  EXPECT_NEAR(area_of(s.pieces[3]), 0.12, 1e-12) << "a whole yoke is left whole";
  const auto said = describe(h);
  ASSERT_EQ(said.size(), 3u);
  EXPECT_NE(said[0].find("a straight 58.0 cm centre edge): unfolded"), std::string::npos) << said[0];
  EXPECT_NE(said[2].find("sleeve SLEEVE_M is cut twice"), std::string::npos) << said[2];
}

// A shirt's collar and stand drawn as halves from centre back (Valentina's
// COLLARTOP and COLLARBASE): the straight end the outline leaves at right
// angles is centre back, not the longer straight front end it leaves
// aslant (the collar's point); each is unfolded about it into the whole band.
// A whole collar (symmetric about its middle) is left whole.
TEST(TopHalves, ACollarAndAStandDrawnFromCentreBackAreUnfoldedThere) {
  Style s;
  s.name = "shirt";
  s.pieces = {half_front("FRONT"), half_front("BACK", 1.0), sleeve("SLEEVE", 2.0)};
  // Half a collar, counter-clockwise: the neck edge from the front (x = 3.0)
  // to centre back (x = 3.22), rising 4 cm to the back (leaving the front
  // end at 16 degrees) and meeting centre back square; centre back 6 cm; the
  // outer edge back to the collar's point, 3 cm higher: a straight front end
  // 13 cm long, longer than centre back.
  Piece collar;
  collar.block = "COLLARTOP_M";
  collar.name = "COLLARTOP";
  collar.size = "M";
  for (int k = 0; k <= 10; ++k) {
    const double t = k / 10.0;
    collar.boundary.push_back({Vec2(3.0 + 0.22 * t, 0.04 * std::sin(0.5 * M_PI * t))});
  }
  collar.boundary.push_back({Vec2(3.22, 0.10)});
  for (int k = 1; k < 10; ++k) {
    const double t = k / 10.0;
    collar.boundary.push_back({Vec2(3.22 - 0.22 * t, 0.10 + 0.03 * t * t)});
  }
  collar.boundary.push_back({Vec2(3.0, 0.13)});
  // Half a stand: the neck edge from its rounded front end to centre back,
  // the top back to the front, 4 cm high at centre back, cut with its grain
  // along its length.
  Piece stand;
  stand.block = "COLLARBASE_M";
  stand.name = "COLLARBASE";
  stand.size = "M";
  stand.boundary = {{Vec2(4.0, 0.0)}, {Vec2(4.1, -0.005)}, {Vec2(4.25, 0.0)}, {Vec2(4.25, 0.04)},
                    {Vec2(4.1, 0.038)}, {Vec2(4.01, 0.03)}, {Vec2(3.995, 0.015)}};
  stand.grain_line = Segment{Vec2(4.05, 0.02), Vec2(4.2, 0.02)};  // along its length: centre back runs across the grain
  Piece whole;  // a whole collar: symmetric about its middle
  whole.block = "COLLAR_M";
  whole.name = "COLLAR";
  whole.size = "M";
  whole.boundary = {{Vec2(5.0, 0)}, {Vec2(5.31, 0)}, {Vec2(5.31, 0.08)}, {Vec2(5.0, 0.08)}};
  s.pieces.insert(s.pieces.end(), {collar, stand, whole});
  const double collar_area = area_of(collar), stand_area = area_of(stand);
  const auto h = unfold_top_halves(s);
  ASSERT_EQ(h.unfolded.size(), 4u);
  EXPECT_EQ(h.unfolded[2].block, "COLLARTOP_M");
  EXPECT_NEAR(h.unfolded[2].centre_length, 0.06, 1e-9) << "centre back, not the 13 cm front end";
  EXPECT_EQ(h.unfolded[3].block, "COLLARBASE_M");
  EXPECT_NEAR(h.unfolded[3].centre_length, 0.04, 1e-9);
  for (const auto& [p, half, centre] : {std::tuple{&s.pieces[3], collar_area, 3.22}, std::tuple{&s.pieces[4], stand_area, 4.25}}) {
    EXPECT_NEAR(area_of(*p), 2 * half, 1e-9) << p->name;
    EXPECT_FALSE(is_self_intersecting(p->boundary)) << p->name;
    for (const auto& c : p->boundary)
      EXPECT_LT(nearest_vertex(p->boundary, Vec2(2 * centre - c.p.x(), c.p.y())).distance, 1e-9) << p->name;
  }
  EXPECT_NEAR(area_of(s.pieces[5]), 0.31 * 0.08, 1e-12) << "a whole collar is left whole";
  EXPECT_NE(describe(h)[2].find("block COLLARTOP_M is half a piece"), std::string::npos);
}

// Left alone: a file that states a quantity or a fold line anywhere, a
// garment without a sleeve (a half of a vest is drawn for a fold the file
// may not say) or with a leg, and a half whose side is named.
TEST(TopHalves, AFileThatStatesQuantitiesOrFoldsOrHasNoSleeveIsLeftAlone) {
  const auto shirt = [] {
    Style s;
    s.name = "shirt";
    s.pieces = {half_front("FRONT"), half_front("BACK", 1.0), sleeve("SLEEVE", 2.0)};
    return s;
  };
  Style quantity = shirt();
  quantity.pieces[2].quantity = 2;
  EXPECT_TRUE(unfold_top_halves(quantity).unfolded.empty());
  EXPECT_NEAR(area_of(quantity.pieces[0]), area_of(half_front("FRONT")), 1e-12);

  Style zero = shirt();  // every piece 0 times: the cutting is in the annotations (mirrored.DXF)
  for (auto& p : zero.pieces) p.quantity = 0;
  EXPECT_TRUE(unfold_top_halves(zero).unfolded.empty());

  Style fold = shirt();
  fold.pieces[1].mirror_line = Segment{Vec2(1.0, 0.0), Vec2(1.0, 0.58)};
  EXPECT_TRUE(unfold_top_halves(fold).unfolded.empty());

  Style vest = shirt();
  vest.pieces.pop_back();
  EXPECT_TRUE(unfold_top_halves(vest).unfolded.empty());

  Style trousers = shirt();
  trousers.pieces.push_back(half_front("LEG", 4.0));
  EXPECT_TRUE(unfold_top_halves(trousers).unfolded.empty());

  Style sided = shirt();
  sided.pieces[0].name = "LEFT FRONT";
  const auto h = unfold_top_halves(sided);
  ASSERT_EQ(h.unfolded.size(), 1u);
  EXPECT_EQ(h.unfolded[0].block, "BACK_M");
  EXPECT_EQ(sided.pieces[0].boundary.size(), half_front("FRONT").boundary.size());
}

// Roles from shapes: a strip is a binding, a cap makes a sleeve, and of two
// body pieces the deeper neckline is the front's.
TEST(ShapeRoles, AStripACapAndTwoNecklines) {
  Style s;
  s.pieces = {half_front("11"), mirrored(half_front("11"), "37", 1.0)};
  join_pieces_written_per_side(s);
  Piece front = s.pieces[0];
  Piece back = front;
  for (auto& c : back.boundary)
    if (c.p.y() >= 0.58) c.p.y() = std::max(c.p.y(), 0.66);  // a shallow neck: 2 cm below the neck points
  Piece strip;
  strip.boundary = {{Vec2(0, 0)}, {Vec2(0.4, 0)}, {Vec2(0.4, 0.02)}, {Vec2(0, 0.02)}};
  const Piece cap = sleeve("36", 0.0);
  const auto roles = roles_from_shapes({&strip, &back, &cap, &front});
  ASSERT_EQ(roles.size(), 4u);
  EXPECT_EQ(roles[0].role, Role::binding) << roles[0].why;
  EXPECT_EQ(roles[1].role, Role::back) << roles[1].why;
  EXPECT_EQ(roles[2].role, Role::sleeve) << roles[2].why;
  EXPECT_EQ(roles[3].role, Role::front) << roles[3].why;
  EXPECT_NE(roles[3].why.find("10.0 cm"), std::string::npos) << roles[3].why;  // the scoop is 0.1 m deep
  // One body piece: front or back cannot be told, and is not guessed.
  const auto alone = roles_from_shapes({&front});
  EXPECT_EQ(alone[0].role, Role::unknown);
  // The sleeve turned upside down has no cap on top: not a sleeve.
  Piece down = cap;
  for (auto& c : down.boundary) c.p.y() = -c.p.y();
  std::reverse(down.boundary.begin(), down.boundary.end());
  EXPECT_NE(roles_from_shapes({&down})[0].role, Role::sleeve);
}

// A piece sewn on its sew line: a 30 × 40 cm rectangle cut with a 1 cm
// allowance (the sew line 1 cm inside, 2 cm at the hem) becomes the 28 × 37 cm
// rectangle the sewer sews, its corners marked, a notch on the cut edge moved
// onto the sew line. Not sewn on: two sew lines, an open one, one crossing the
// cut line, one 10 cm in (more than any allowance).
TEST(SewLines, APieceIsSewnOnItsSewLineAndTheAllowanceIsCutOff) {
  auto rect = [](double x0, double y0, double x1, double y1) {
    return std::vector<Vec2>{Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
  };
  Piece cut;
  for (const Vec2& p : rect(0, 0, 0.30, 0.40)) cut.boundary.push_back({p});
  cut.notches.push_back({Vec2(0.30, 0.20)});
  Piece p = cut;
  p.sew_lines.push_back({rect(0.01, 0.02, 0.29, 0.39), true});
  const auto a = sew_on_sew_line(p);
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(a->min, 0.01, 1e-12);
  EXPECT_NEAR(a->max, 0.02, 1e-12);
  EXPECT_NEAR(signed_area(p.boundary), 0.28 * 0.37, 1e-12);
  EXPECT_EQ(std::count_if(p.boundary.begin(), p.boundary.end(), [](const ContourPoint& c) { return c.kind == PointKind::turn; }), 4);
  EXPECT_NEAR((p.notches[0].position - Vec2(0.29, 0.20)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(p.sew_lines.empty());
  // A cut line whose corners the file marked (two of four here, as carried to
  // graded sizes) gives its marks to the sew line instead.
  Piece marked = cut;
  marked.boundary[0].kind = marked.boundary[2].kind = PointKind::turn;
  marked.sew_lines.push_back({rect(0.01, 0.02, 0.29, 0.39), true});
  ASSERT_TRUE(sew_on_sew_line(marked).has_value());
  std::vector<Vec2> turns;
  for (const auto& c : marked.boundary)
    if (c.kind == PointKind::turn) turns.push_back(c.p);
  ASSERT_EQ(turns.size(), 2u);
  EXPECT_NEAR(nearest_vertex(marked.boundary, Vec2(0.01, 0.02)).distance, 0.0, 1e-12);
  for (const Vec2& t : turns) EXPECT_TRUE((t - Vec2(0.01, 0.02)).norm() < 1e-12 || (t - Vec2(0.29, 0.39)).norm() < 1e-12);

  Piece two = cut;
  two.sew_lines = {{rect(0.01, 0.02, 0.29, 0.39), true}, {rect(0.02, 0.03, 0.28, 0.38), true}};
  Piece open = cut;
  open.sew_lines = {{rect(0.01, 0.02, 0.29, 0.39), false}};
  Piece crossing = cut;
  crossing.sew_lines = {{rect(0.01, 0.02, 0.31, 0.39), true}};
  Piece deep = cut;
  deep.sew_lines = {{rect(0.10, 0.10, 0.20, 0.30), true}};
  for (Piece* q : {&two, &open, &crossing, &deep}) {
    EXPECT_FALSE(sew_on_sew_line(*q).has_value());
    EXPECT_NEAR(signed_area(q->boundary), 0.30 * 0.40, 1e-12);  // unchanged
  }
}

// A rib 4 cm x 40 cm drawn upright, cut double: folded about its right edge
// (the one sewn), it is the 2 cm beside that edge, every point's distance
// across halved and nothing moved along it; its vertices, their order and
// its turn stay.
TEST(FoldLengthwise, TheHalfBesideTheSewnEdgeIsKept) {
  Piece p;
  const double pts[][2] = {{0.10, 0.00}, {0.14, 0.00}, {0.14, 0.40}, {0.10, 0.40}};
  for (const auto& q : pts) p.boundary.push_back({Vec2(q[0], q[1])});
  p.notches.push_back({Vec2(0.12, 0.0), -90.0});   // the fold's mark on an end
  p.notches.push_back({Vec2(0.10, 0.2), 135.0});   // a cut slanting across
  p.grain_line = Segment{Vec2(0.105, 0.2), Vec2(0.135, 0.2)};
  p.internal_lines.push_back({{Vec2(0.10, 0.1), Vec2(0.14, 0.3)}, false});
  const double area = signed_area(p.boundary);
  ASSERT_GT(area, 0.0);
  fold_lengthwise(p, Vec2(0.14, 0.0), Vec2(0.0, 0.4));
  const double want[][2] = {{0.12, 0.00}, {0.14, 0.00}, {0.14, 0.40}, {0.12, 0.40}};
  ASSERT_EQ(p.boundary.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(p.boundary[i].p.x(), want[i][0], 1e-12) << i;
    EXPECT_NEAR(p.boundary[i].p.y(), want[i][1], 1e-12) << i;
  }
  EXPECT_NEAR(signed_area(p.boundary), 0.5 * area, 1e-12);  // still counter-clockwise
  EXPECT_NEAR(p.notches[0].position.x(), 0.13, 1e-12);
  EXPECT_NEAR(p.notches[0].angle_deg, -90.0, 1e-9);
  EXPECT_NEAR(p.notches[1].position.x(), 0.12, 1e-12);
  // (-1, 1) across halved: (-0.5, 1), atan2(1, -0.5).
  EXPECT_NEAR(p.notches[1].angle_deg, std::atan2(1.0, -0.5) * 180.0 / M_PI, 1e-9);
  EXPECT_NEAR(p.grain_line->a.x(), 0.1225, 1e-12);
  EXPECT_NEAR(p.grain_line->b.x(), 0.1375, 1e-12);
  EXPECT_NEAR(p.internal_lines[0].points[0].x(), 0.12, 1e-12);
  EXPECT_NEAR(p.internal_lines[0].points[1].y(), 0.3, 1e-12);
  // The edge given the other way round folds the same.
  Piece q;
  for (const auto& c : pts) q.boundary.push_back({Vec2(c[0], c[1])});
  fold_lengthwise(q, Vec2(0.14, 0.4), Vec2(0.0, -1.0));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(q.boundary[i].p.x(), want[i][0], 1e-12) << i;
  EXPECT_THROW(fold_lengthwise(q, Vec2(0.14, 0.4), Vec2(0.0, 0.0)), std::invalid_argument);
}
