#pragma once
// Graded sizes: carrying the sample size's marks to the other sizes of a piece.
//
// A graded CAD file (Gerber AccuMark, Lectra) writes one block per piece per
// size. Only the sample-size block carries the turn points, curve points and
// notches; the graded blocks are the same outline moved point by point by the
// grade rules, with no marks. Without them a graded size has one boundary
// stretch per piece and nothing to sew by. carry_marks() finds which vertex of
// a graded outline is which vertex of the sample outline and copies the marks.
//
// Correspondence: an order-keeping alignment (dynamic programming over the
// two cyclic vertex sequences; either may skip a vertex: duplicate or extra
// points) pairs vertices at the least cost, a pair costing its distance plus
// the difference in how the outline turns there, so corners pair with
// corners. First each outline in its own bounding box scaled to the unit
// square (grade rules grow lengths and widths by different amounts), then
// twice the graded outline mapped onto the sample's by the least-squares
// affine fit of the pairs found, in metres. Sizes are aligned with their
// neighbour outwards from the sample, one grade step at a time. Graded
// blocks of real files keep the sample's vertex count and order
// (MEN_CLASSIC_TEE: 27 of 27, one size 28), so the alignment is the identity
// up to those extra points. The graded outline is turned to start where the
// sample's does, so boundary stretch k is the same stretch in every size.
// Units: metres.
#include <string>
#include <vector>

#include "vgd/pattern/piece.hpp"

namespace vgd::pattern {

struct CarriedMarks {
  bool carried = false;         // false: `to` was left unchanged (see `why`)
  int turns = 0, curves = 0;    // marks set on `to`'s vertices
  int notches = 0;              // notches added to `to`
  double rms_m = 0;             // m: RMS distance of the paired vertices after the affine fit
  int unpaired = 0;             // vertices of `from` left without a partner
  std::string why;              // when not carried: the reason, one phrase
};

// Copies the turn/curve marks and the notches of `from` (the sample size) to
// `to` (another size of the same piece). `to` is left unchanged when it has
// as many turn points and notches as `from` (marks of its own; a stray turn
// point of its own is kept and the rest carried), or when no alignment is
// close enough: an RMS distance above `max_rms_fraction` of √area (at least
// 4 mm), or more than a tenth of the vertices unpaired.
CarriedMarks carry_marks(const Piece& from, Piece& to, double max_rms_fraction = 0.02);

// For every piece name of the style whose blocks are all of different sizes:
// the sample-size block (style.sample_size, else the block with the most
// turn points and notches) gives its marks to the other sizes' blocks, each
// through its neighbour size. Returns one entry per graded block considered, by block name.
std::vector<std::pair<std::string, CarriedMarks>> carry_sample_marks(Style& style);

}  // namespace vgd::pattern
