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

}  // namespace vgd::pattern
