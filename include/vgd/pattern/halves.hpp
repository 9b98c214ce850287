#pragma once
// Pieces a CAD system writes once per side. CLO exports a front cut in two as
// its left and its right half, each a block of its own and cut once, and a
// sleeve cut twice as two identical blocks. vgd sews a whole front and a
// sleeve cut twice (left and right copies), so such pieces are joined:
//  - two mirror images with a straight centre edge along the grain (the whole
//    piece on one side of it, at least 40 % of the piece's length along the
//    grain) are one piece's halves: the first is unfolded about that edge
//    (unfold_about_mirror_line) and the second dropped;
//  - two congruent outlines, or mirror images without such an edge, are one
//    piece cut twice: the first is kept with quantity 2 and the second dropped.
// Only pieces whose names, categories and annotations say nothing of their
// role (pattern::piece_role is unknown: CLO's numbered pieces), of one size,
// cut once, in the same category and fabric, with no mirror line: a placket
// and its interfacing, or two named pieces that happen to match, are left
// alone.
#include <string>
#include <vector>

#include "vgd/pattern/piece.hpp"

namespace vgd::pattern {

struct JoinedPieces {
  std::string size;
  std::string kept, dropped;  // blocks
  bool halves = false;        // true: unfolded about the centre edge; false: kept as cut twice
  double centre_length = 0.0;  // m: the centre edge's length (halves)
};

// Tolerance: m, the largest distance between the two outlines once one is
// reflected (or not) and moved onto the other's centroid; areas and
// perimeters must also agree within 1 %.
std::vector<JoinedPieces> join_pieces_written_per_side(Style& style, double tol_m = 0.002);

// The join in words, for the user: which blocks, what was made of them.
std::string describe(const JoinedPieces& joined);

// A top drawn in halves by a file that states no quantities (Valentina's
// shirt: FRONTPANEL, BACKPANEL and YOKE cut once, no side, no fold line, the
// centre front or back a straight edge along the grain with the whole piece
// on one side of it, and one SHORTSLEEVE). In a style with a sleeve and no
// leg, where every piece is cut at most once, not every piece 0 times (a
// file that says its cutting in the annotations) and none has a fold line:
//  - each front, back or yoke whose outline is such a half (its centre edge
//    at least 40 % of its length along the grain, the piece not its own
//    mirror image across its middle) is unfolded about that edge into the
//    whole piece (a front so made is closed at its centre, as buttoned);
//  - so is each collar or collar stand drawn as its half from centre back
//    (Valentina's COLLARBASE and COLLARTOP: a straight end across the band,
//    at least 40 % of its width, the other end shaped for the front);
//  - once a half is unfolded, each sleeve cut once naming no side is cut
//    twice (one sleeve is never a garment).
struct UnfoldedHalf {
  std::string size, block;
  double centre_length = 0.0;  // m
};
struct TopHalves {
  std::vector<UnfoldedHalf> unfolded;
  std::vector<std::string> sleeves_cut_twice;  // blocks
};
TopHalves unfold_top_halves(Style& style, double tol_m = 0.002);

// What unfold_top_halves did, a sentence per piece.
std::vector<std::string> describe(const TopHalves& halves);

// A piece cut double and folded lengthwise along its middle (a crew neck's
// rib, sewn to the neckline by both raw edges together): the half beside the
// line through `point` along `direction` (the edge that is sewn), as the two
// layers lie. Every point's distance across from that line is halved:
// outline, notches (and their cuts' directions), grain, mirror and grade
// lines, internal lines, cut-outs, sew lines and drill holes. The outline
// keeps its vertices, its order and its turn (counter-clockwise stays so),
// so what refers to them (stretches, seams) stays valid. Throws
// std::invalid_argument for a zero or non-finite direction.
void fold_lengthwise(Piece& piece, const Vec2& point, const Vec2& direction);

}  // namespace vgd::pattern
