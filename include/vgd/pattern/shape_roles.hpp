#pragma once
// Roles from the pieces' shapes, for pieces whose names say nothing (CLO
// numbers its pieces: "11", "36", "Pattern2D_768516"). Read along each
// piece's grain line (else +y):
//  - a strip (narrower than 5 cm and at least 4 times as long) is a binding;
//  - a sleeve has a cap: its highest point within a tenth of its width of the
//    middle, and its outline narrower than half its width a tenth of its
//    length below the top;
//  - of the pieces at least 35 cm long and 25 cm wide that are no sleeve,
//    exactly two are a front and a back: the front's neckline is the deeper
//    (how far below its top the outline crosses its centre line), the other
//    the back.
// Anything else is left unknown, and said.
#include <string>
#include <vector>

#include "vgd/pattern/piece.hpp"
#include "vgd/pattern/roles.hpp"

namespace vgd::pattern {

struct ShapeRole {
  Role role = Role::unknown;
  std::string why;  // in words: "a cap 9.1 cm high, centred", "neckline 12.3 cm deep"
};

// One answer per piece, in order.
std::vector<ShapeRole> roles_from_shapes(const std::vector<const Piece*>& pieces);

}  // namespace vgd::pattern
