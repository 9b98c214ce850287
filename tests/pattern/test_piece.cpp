#include <gtest/gtest.h>

#include "vgd/pattern/piece.hpp"

using namespace vgd::pattern;

namespace {
std::vector<ContourPoint> outline(std::initializer_list<std::pair<double, double>> pts) {
  std::vector<ContourPoint> o;
  for (auto [x, y] : pts) o.push_back({Vec2(x, y)});
  return o;
}
}  // namespace

TEST(PieceGeometry, SquareAreaIsPositiveCounterClockwise) {
  auto sq = outline({{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  EXPECT_DOUBLE_EQ(signed_area(sq), 4.0);
  std::reverse(sq.begin(), sq.end());
  EXPECT_DOUBLE_EQ(signed_area(sq), -4.0);
  EXPECT_DOUBLE_EQ(perimeter(sq), 8.0);
}

TEST(PieceGeometry, AreaIsTranslationInvariantFarFromOrigin) {
  auto a = outline({{0, 0}, {0.3, 0}, {0.3, 0.2}, {0, 0.2}});
  auto b = a;
  for (auto& p : b) p.p += Vec2(1e4, -3e4);
  EXPECT_NEAR(signed_area(b), signed_area(a), 1e-9);
}

TEST(PieceGeometry, BowTieIsSelfIntersecting) {
  EXPECT_TRUE(is_self_intersecting(outline({{0, 0}, {1, 1}, {1, 0}, {0, 1}})));
  EXPECT_FALSE(is_self_intersecting(outline({{0, 0}, {1, 0}, {1, 1}, {0, 1}})));
}

TEST(PieceGeometry, TouchingNonAdjacentEdgesCount) {
  // The vertex (1,0) of edge 2 lies on edge 0: a pinched outline.
  EXPECT_TRUE(is_self_intersecting(outline({{0, 0}, {2, 0}, {2, 1}, {1, 0}, {0, 1}})));
}

TEST(PieceGeometry, GrainAngle) {
  Piece p;
  EXPECT_EQ(grain_angle_deg(p), 0.0);
  p.grain_line = Segment{Vec2(0, 0), Vec2(0, 1)};
  EXPECT_DOUBLE_EQ(grain_angle_deg(p), 90.0);
  p.grain_line = Segment{Vec2(0, 0), Vec2(-1, 0)};
  EXPECT_DOUBLE_EQ(grain_angle_deg(p), 180.0);
}

TEST(Style, PieceNamesAndSizes) {
  Style s;
  s.pieces.push_back({.block = "F_38", .name = "FRONT", .size = "38"});
  s.pieces.push_back({.block = "B_38", .name = "BACK", .size = "38"});
  s.pieces.push_back({.block = "F_40", .name = "FRONT", .size = "40"});
  EXPECT_EQ(s.piece_names(), (std::vector<std::string>{"FRONT", "BACK"}));
  EXPECT_EQ(s.pieces_of_size("38").size(), 2u);
}
