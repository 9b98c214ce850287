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
// Correspondence: the outlines are compared relative to their centroids, the
// graded one scaled by √(sample area / graded area) so that uniform grading
// cancels; an order-keeping alignment (dynamic programming over the two cyclic
// vertex sequences, either may skip a vertex: duplicate or extra points) pairs
// vertices at the least summed distance. Graded blocks of real files keep the
// sample's vertex count and order (MEN_CLASSIC_TEE: 27 of 27, one size 28), so
// the alignment is the identity up to those extra points. Units: metres.
#include <string>
#include <vector>

#include "vgd/pattern/piece.hpp"

namespace vgd::pattern {

struct CarriedMarks {
  bool carried = false;         // false: `to` was left unchanged (see `why`)
  int turns = 0, curves = 0;    // marks set on `to`'s vertices
  int notches = 0;              // notches added to `to`
  double rms_m = 0;             // RMS distance of the paired vertices after scaling
  int unpaired = 0;             // vertices of `from` left without a partner
  std::string why;              // when not carried: the reason, one phrase
};

// Copies the turn/curve marks and the notches of `from` (the sample size) to
// `to` (another size of the same piece). `to` is left unchanged when it has
// marks of its own (any turn point or notch), or when no alignment is close
// enough: an RMS distance above `max_rms_fraction` of √area, or more than a
// tenth of the vertices unpaired.
CarriedMarks carry_marks(const Piece& from, Piece& to, double max_rms_fraction = 0.02);

// For every piece name of the style: the sample-size block (style.sample_size,
// else the block with the most turn points) gives its marks to the other
// sizes' blocks. Returns one entry per graded block considered, by block name.
std::vector<std::pair<std::string, CarriedMarks>> carry_sample_marks(Style& style);

}  // namespace vgd::pattern
