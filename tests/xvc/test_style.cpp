#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fixtures.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;
using vgd::pattern::Piece;
using vgd::pattern::Style;

namespace {
// Bitwise-equal doubles: the mapping must not round anything (sign of zero aside).
::testing::AssertionResult same(const Vec2& a, const Vec2& b) {
  if (a.x() == b.x() && a.y() == b.y()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << a.x() << ", " << a.y() << ") != (" << b.x() << ", " << b.y() << ")";
}

void expect_same_piece(const Piece& a, const Piece& b) {
  SCOPED_TRACE(a.block);
  EXPECT_EQ(a.block, b.block);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.size, b.size);
  EXPECT_EQ(a.quantity, b.quantity);
  EXPECT_EQ(a.quantity_flipped, b.quantity_flipped);
  EXPECT_EQ(a.category, b.category);
  EXPECT_EQ(a.fabric, b.fabric);
  EXPECT_EQ(a.annotation, b.annotation);
  EXPECT_EQ(a.annotations, b.annotations);
  EXPECT_EQ(a.closed, b.closed);
  EXPECT_EQ(a.self_intersecting, b.self_intersecting);
  ASSERT_EQ(a.boundary.size(), b.boundary.size());
  for (std::size_t i = 0; i < a.boundary.size(); ++i) {
    EXPECT_TRUE(same(a.boundary[i].p, b.boundary[i].p)) << i;
    EXPECT_EQ(a.boundary[i].kind, b.boundary[i].kind) << i;
  }
  ASSERT_EQ(a.notches.size(), b.notches.size());
  for (std::size_t i = 0; i < a.notches.size(); ++i) {
    EXPECT_TRUE(same(a.notches[i].position, b.notches[i].position));
    EXPECT_EQ(a.notches[i].angle_deg, b.notches[i].angle_deg);
    EXPECT_EQ(a.notches[i].length_m, b.notches[i].length_m);
    EXPECT_EQ(a.notches[i].width_m, b.notches[i].width_m);
    EXPECT_EQ(a.notches[i].type, b.notches[i].type);
    EXPECT_EQ(a.notches[i].boundary_index, b.notches[i].boundary_index);
  }
  auto same_segment = [](const std::optional<vgd::pattern::Segment>& x, const std::optional<vgd::pattern::Segment>& y) {
    return x.has_value() == y.has_value() && (!x || (same(x->a, y->a) && same(x->b, y->b)));
  };
  EXPECT_TRUE(same_segment(a.grain_line, b.grain_line));
  EXPECT_TRUE(same_segment(a.mirror_line, b.mirror_line));
  EXPECT_TRUE(same_segment(a.grade_reference, b.grade_reference));
  auto same_lines = [](const std::vector<vgd::pattern::Polyline>& x, const std::vector<vgd::pattern::Polyline>& y) {
    if (x.size() != y.size()) return false;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (x[i].closed != y[i].closed || x[i].points.size() != y[i].points.size()) return false;
      for (std::size_t k = 0; k < x[i].points.size(); ++k)
        if (!same(x[i].points[k], y[i].points[k])) return false;
    }
    return true;
  };
  EXPECT_TRUE(same_lines(a.internal_lines, b.internal_lines));
  EXPECT_TRUE(same_lines(a.cutouts, b.cutouts));
  EXPECT_TRUE(same_lines(a.sew_lines, b.sew_lines));
  ASSERT_EQ(a.drill_holes.size(), b.drill_holes.size());
  for (std::size_t i = 0; i < a.drill_holes.size(); ++i) EXPECT_TRUE(same(a.drill_holes[i], b.drill_holes[i]));
}

void expect_same_style(const Style& a, const Style& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.producer, b.producer);
  EXPECT_EQ(a.flavour, b.flavour);
  EXPECT_EQ(a.units, b.units);
  EXPECT_EQ(a.sample_size, b.sample_size);
  EXPECT_EQ(a.sizes, b.sizes);
  ASSERT_EQ(a.pieces.size(), b.pieces.size());
  for (std::size_t i = 0; i < a.pieces.size(); ++i) expect_same_piece(a.pieces[i], b.pieces[i]);
}
}  // namespace

TEST(StyleMapping, StyleToXvcToStyleIsLossless) {
  const Style s = full_style();
  expect_same_style(to_style(from_style(s)), s);
}

TEST(StyleMapping, LosslessThroughTheSavedText) {
  const Style s = full_style();
  expect_same_style(to_style(load_string(save_string(from_style(s)), "s.xvc")), s);
}

TEST(StyleMapping, AwkwardDoublesSurviveExactly) {
  Style s;
  Piece p;
  p.block = "B";
  const double values[] = {0.1, 1.0 / 3.0, 1e-300, 5e-324, 1.7976931348623157e308, -2.5e-9, 123456.789012345678};
  for (const double v : values) p.boundary.push_back({Vec2(v, -v)});
  s.pieces.push_back(p);
  const Style back = to_style(load_string(save_string(from_style(s)), "d.xvc"));
  for (std::size_t i = 0; i < p.boundary.size(); ++i) EXPECT_TRUE(same(back.pieces[0].boundary[i].p, p.boundary[i].p)) << i;
}

TEST(StyleMapping, BoundaryIsSplitAtEveryTurnPoint) {
  const Document doc = from_style(full_style());
  // Points 0..6 with turns at 1, 3, 5, 6: stretches [0], [1,2], [3,4], [5], [6].
  const auto st = boundary_stretches(*doc.find("pattern1"));
  ASSERT_EQ(st.size(), 5u);
  const std::size_t firsts[] = {0, 1, 3, 5, 6}, counts[] = {1, 2, 2, 1, 1};
  for (std::size_t i = 0; i < st.size(); ++i) {
    EXPECT_EQ(st[i].first, firsts[i]) << i;
    EXPECT_EQ(st[i].count, counts[i]) << i;
  }
  // Every stretch after the first starts at a turn point, so hems can name corner-to-corner edges.
  for (std::size_t i = 1; i < st.size(); ++i)
    EXPECT_EQ(doc.find(st[i].id)->children.front().attribute("kind"), "turn") << st[i].id;
}

TEST(StyleMapping, ContourWithoutTurnPointsIsOneStretch) {
  const Document doc = from_style(full_style());
  EXPECT_EQ(boundary_stretches(*doc.find("pattern5")).size(), 1u);
}

TEST(StyleMapping, OnePatternPerBlockAndOneGradationPerPiece) {
  const Document doc = from_style(full_style());
  ASSERT_EQ(doc.patterns().size(), 5u);
  EXPECT_EQ(doc.patterns()[2]->attribute("piece"), "FRONT");
  EXPECT_EQ(doc.patterns()[2]->attribute("size"), "38");
  const Node* grads = doc.container("GRADATIONS");
  ASSERT_NE(grads, nullptr);
  EXPECT_EQ(grads->attribute("sample_size"), "38");
  std::vector<std::string> run, pieces;
  const Node* front = nullptr;
  for (const auto& c : grads->children) {
    if (c.tag == "SIZE") run.emplace_back(c.attribute("name"));
    if (c.tag == "GRADATION") pieces.emplace_back(c.attribute("piece"));
    if (c.tag == "GRADATION" && c.attribute("piece") == "FRONT") front = &c;
  }
  EXPECT_EQ(run, (std::vector<std::string>{"36", "38", "40"}));
  EXPECT_EQ(pieces, (std::vector<std::string>{"FRONT", "BACK", "POCKET"}));
  ASSERT_NE(front, nullptr);
  ASSERT_EQ(front->children.size(), 2u);
  EXPECT_EQ(front->children[0].attribute("pattern"), "pattern1");
  EXPECT_FALSE(front->children[0].has_attribute("sample"));
  EXPECT_EQ(front->children[1].attribute("pattern"), "pattern3");
  EXPECT_EQ(front->children[1].attribute("sample"), "true");
}

TEST(StyleMapping, EmptyStyleGivesAValidEmptyGarment) {
  const Document doc = from_style(Style{});
  EXPECT_TRUE(doc.patterns().empty());
  EXPECT_FALSE(check(doc).has_errors());
  expect_same_style(to_style(doc), Style{});
}

TEST(StyleMapping, NonFiniteCoordinateIsRefused) {
  Style s = full_style();
  s.pieces[1].boundary[2].p.x() = std::numeric_limits<double>::quiet_NaN();
  try {
    from_style(s);
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_NE(e.diagnostic().message.find("not a finite number"), std::string::npos) << e.what();
  }
}

TEST(StyleMapping, NotchVertexBeyondTheBoundaryIsRefused) {
  Style s = full_style();
  s.pieces[0].notches[0].boundary_index = 99;
  EXPECT_THROW(from_style(s), vgd::Error);
}

TEST(StyleMapping, TextXmlCannotHoldIsRefused) {
  Style s = full_style();
  s.pieces[0].annotation = std::string("bell\x07");
  EXPECT_THROW(from_style(s), vgd::Error);
  s.pieces[0].annotation = std::string("bad utf8 \xC3");
  EXPECT_THROW(from_style(s), vgd::Error);
}

TEST(StyleMapping, ToPieceReadsOnePatternAndRefusesOtherElements) {
  const Document doc = from_style(full_style());
  expect_same_piece(to_piece(doc, "pattern4"), full_style().pieces[3]);
  EXPECT_THROW(to_piece(doc, "seq1"), vgd::Error);
  EXPECT_THROW(to_piece(doc, "nope"), vgd::Error);
}
