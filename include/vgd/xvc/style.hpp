#pragma once
// Between the 2-D pattern vocabulary (pattern::Style, pattern::Piece) and XVC.
//
// Style -> XVC -> Style is lossless: every field of Style and Piece has a place in the
// document (docs/xvc.md, "Mapping from a style") and coordinates are written in metres
// with the shortest text that reads back to the same double (vgd::format_double).
//
// Layout written by from_style:
//   one PATTERN per piece in one size (a DXF block), attributes piece and size;
//   its boundary split into C2DSEQs, a new one starting at every turn point, so that
//   hems can name the stretches between corners;
//   GRADATIONS: the style's size run as SIZEs, then one GRADATION per piece name whose
//   SIZEs name the PATTERN of each size and mark the sample size.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/pattern/piece.hpp"
#include "vgd/pattern/roles.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::xvc {

// A new document holding the style. Throws vgd::Error when the style holds something
// XVC cannot carry (a non-finite coordinate, a negative quantity, a notch vertex index
// beyond its boundary, a text with a character XML 1.0 cannot hold).
Document from_style(const pattern::Style& style);

// The style the document describes (materials, seams, ... are not part of a Style).
pattern::Style to_style(const Document& doc);

// One PATTERN as a piece. Throws vgd::Error when `pattern_id` names no PATTERN.
pattern::Piece to_piece(const Document& doc, std::string_view pattern_id);

// What a PATTERN is in its garment (pattern/roles.hpp): its role attribute
// when it has one (written by vgd dress, corrected by the designer), else
// from its piece name, category and annotation, the garment's name read as
// the style's code. The side and variant words are the name's.
pattern::RoleGuess piece_role(const Document& doc, const Node& pattern);

// A PATTERN's drape attribute: true or false as the document says (set by
// vgd dress, corrected by the designer), nothing when it has none.
std::optional<bool> drape_attribute(const Node& pattern);

// A PATTERN's folded attribute (cut double and folded lengthwise: draped as
// the half beside the edge its seam sews, two layers; set by vgd dress for a
// neckband, corrected by the designer), nothing when it has none.
std::optional<bool> folded_attribute(const Node& pattern);

// The MATERIAL a PATTERN is cut from when it names its own (an ASSOCIATION
// with role "material" referring to a MATERIAL of `doc`): its id, else "".
std::string piece_material(const Document& doc, const Node& pattern);

// The garment's own fabric: its first MATERIAL of scope "garment" (the
// default; "piece" MATERIALs serve only the pieces that name them), else ""
// (pieces without their own are then cut from the default fabric).
std::string garment_material(const Document& doc);

// A boundary C2DSEQ of a pattern and the vertices it holds in the piece's boundary:
// indices first .. first + count - 1. Its edge runs on to the first vertex of the next
// stretch (cyclically), so a stretch from corner to corner holds the first corner only.
struct Stretch {
  std::string id;
  std::size_t first = 0;
  std::size_t count = 0;
};
std::vector<Stretch> boundary_stretches(const Node& pattern);

}  // namespace vgd::xvc
