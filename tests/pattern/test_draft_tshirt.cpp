// The drafted T-shirt: clean outlines, and the lengths of every seam agree where
// the pieces are sewn together (draft.hpp states the guarantees).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/draft.hpp"

using namespace vgd::pattern;

namespace {

// Indices of the turn points of an outline: stretch k runs from turn k to turn k+1.
std::vector<std::size_t> turns(const Piece& p) {
  std::vector<std::size_t> t;
  for (std::size_t i = 0; i < p.boundary.size(); ++i)
    if (p.boundary[i].kind == PointKind::turn) t.push_back(i);
  return t;
}

// Length of stretch k (from its turn point to the next, along the contour).
double stretch_length(const Piece& p, std::size_t k) {
  const auto t = turns(p);
  const std::size_t n = p.boundary.size();
  std::size_t i = t.at(k);
  const std::size_t end = t[(k + 1) % t.size()];
  double len = 0;
  do {
    len += (p.boundary[(i + 1) % n].p - p.boundary[i].p).norm();
    i = (i + 1) % n;
  } while (i != end);
  return len;
}

const Piece& piece(const std::vector<Piece>& ps, const std::string& name) {
  for (const auto& p : ps)
    if (p.name == name) return p;
  throw std::runtime_error("no piece " + name);
}

}  // namespace

TEST(TShirtDraft, PiecesAreCleanOutlinesWithTheStatedStretches) {
  for (const auto& m : tshirt_size_table()) {
    const auto pieces = draft_tshirt(m);
    ASSERT_EQ(pieces.size(), 4u);
    for (const auto& p : pieces) {
      SCOPED_TRACE(p.block);
      EXPECT_GT(signed_area(p.boundary), 0.0);
      EXPECT_FALSE(is_self_intersecting(p.boundary));
      EXPECT_TRUE(p.grain_line.has_value());
      EXPECT_EQ(p.boundary.front().kind, PointKind::turn) << "vertex 0 must start stretch 0";
      auto copy = p.boundary;
      EXPECT_EQ(remove_duplicate_vertices(copy), 0);
      for (const auto& n : p.notches) EXPECT_LT(nearest_edge(p.boundary, n.position).distance, 1e-9);
      EXPECT_EQ(turns(p).size(), p.name.find("SLEEVE") != std::string::npos ? 4u : 8u);
    }
  }
}

TEST(TShirtDraft, SeamLengthsMatch) {
  for (const auto& m : tshirt_size_table()) {
    SCOPED_TRACE("size " + m.size);
    const auto ps = draft_tshirt(m);
    const auto &front = piece(ps, "FRONT"), &back = piece(ps, "BACK");
    // Side seams and shoulders: front and back equal, left and right equal.
    for (const int k : {1, 7}) {
      EXPECT_NEAR(stretch_length(front, k), stretch_length(back, k), 1e-9);
      // Straight from the underarm to the hem corner, which flares out to the
      // hips (hip + ease) when they are wider than the chest with its ease.
      const double flare = std::max(0.0, (m.hip + m.hip_ease) / 4 - (m.bust + m.bust_ease) / 4);
      EXPECT_NEAR(stretch_length(front, k), std::hypot(m.length - m.armhole_depth, flare), 1e-9);
    }
    for (const int k : {3, 5}) {
      EXPECT_NEAR(stretch_length(front, k), stretch_length(back, k), 1e-9);
      EXPECT_NEAR(stretch_length(front, k), m.shoulder, 1e-9);
    }
    // Left and right armholes of one piece are mirror images.
    EXPECT_NEAR(stretch_length(front, 2), stretch_length(front, 6), 1e-12);
    EXPECT_NEAR(stretch_length(back, 2), stretch_length(back, 6), 1e-12);
    // The front armhole is scooped deeper, so longer than the back one.
    EXPECT_GT(stretch_length(front, 2), stretch_length(back, 2));
    const double armhole = stretch_length(front, 2) + stretch_length(back, 2);
    for (const char* s : {"LEFT SLEEVE", "RIGHT SLEEVE"}) {
      const auto& sl = piece(ps, s);
      EXPECT_NEAR(stretch_length(sl, 2), armhole + m.cap_ease, 1e-9) << s << ": cap = armhole + ease";
      EXPECT_NEAR(stretch_length(sl, 1), stretch_length(sl, 3), 1e-12) << s << ": underarm seams";
    }
  }
}

// The hem of front plus back goes round the hips with their ease: a straight
// T-shirt as wide as the chest (0.98 m at size 38) could not close round the
// mannequin's 0.97 m hips plus its clearance, and its side seams stalled open.
TEST(TShirtDraft, HemPassesOverTheHips) {
  for (const auto& m : tshirt_size_table()) {
    SCOPED_TRACE("size " + m.size);
    const auto ps = draft_tshirt(m);
    double hem = 0;
    for (const char* name : {"FRONT", "BACK"}) {
      const auto& p = piece(ps, name);
      hem += (p.boundary[1].p - p.boundary[0].p).norm();
    }
    EXPECT_GE(hem, m.hip + m.hip_ease - 1e-9);
    EXPECT_GE(hem, m.bust + m.bust_ease - 1e-9);
  }
}

TEST(TShirtDraft, NotchesMarkFrontSingleBackDoubleAndTheCapMatches) {
  const auto ps = draft_tshirt(TShirtMeasurements{});
  EXPECT_EQ(piece(ps, "FRONT").notches.size(), 2u);   // one per armhole
  EXPECT_EQ(piece(ps, "BACK").notches.size(), 4u);    // a pair per armhole
  EXPECT_EQ(piece(ps, "LEFT SLEEVE").notches.size(), 4u);  // pair (back), single (front), shoulder
  EXPECT_EQ(piece(ps, "RIGHT SLEEVE").notches.size(), 4u);
  // The sleeves are mirror images: notch x flips, y stays.
  const auto &l = piece(ps, "LEFT SLEEVE"), &r = piece(ps, "RIGHT SLEEVE");
  for (std::size_t i = 0; i < l.notches.size(); ++i) {
    EXPECT_DOUBLE_EQ(l.notches[i].position.x(), -r.notches[i].position.x());
    EXPECT_DOUBLE_EQ(l.notches[i].position.y(), r.notches[i].position.y());
  }
  // The left sleeve's back (double notch) is on +x, its front on -x.
  EXPECT_GT(l.notches[0].position.x(), 0.0);
  EXPECT_LT(l.notches[2].position.x(), 0.0);
}

TEST(TShirtDraft, ImpossibleMeasurementsAreRefused) {
  TShirtMeasurements m;
  m.bust = -1;
  EXPECT_THROW(draft_tshirt(m), vgd::Error);
  m = {};
  m.shoulder = 0.3;  // past the chest
  EXPECT_THROW(draft_tshirt(m), vgd::Error);
  m = {};
  m.sleeve_length = 0.05;  // shorter than its cap
  EXPECT_THROW(draft_tshirt(m), vgd::Error);
}

TEST(TShirtDraft, StyleHasEverySizeAndTheSeamsNameItsPieces) {
  const auto style = draft_tshirt_style();
  EXPECT_EQ(style.sizes.size(), 5u);
  EXPECT_EQ(style.sample_size, "38");
  EXPECT_EQ(style.pieces.size(), 20u);
  const auto ps = draft_tshirt(TShirtMeasurements{});
  for (const auto& s : tshirt_seams())
    for (const auto& h : s.hems) {
      const auto& p = piece(ps, h.piece);
      EXPECT_LT(static_cast<std::size_t>(h.to), turns(p).size()) << s.name;
    }
}
