#pragma once
// Pattern pieces: the 2-D vocabulary every later stage speaks.
//
// Units: metres. Coordinates are the pattern's own 2-D frame as the CAD system
// drew it (x right, y up). A Piece is one block of a DXF file: one piece in one
// size. A Style is everything one file (or one XVC document) holds.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vgd::pattern {

using Vec2 = Eigen::Vector2d;  // metres

// What the CAD system said about a boundary vertex (AAMA layers 2 and 3).
enum class PointKind : unsigned char {
  plain,  // a vertex with no marker
  turn,   // a corner: resampling always keeps it and splits the contour there
  curve,  // a point on a smooth curve
};

struct ContourPoint {
  Vec2 p = Vec2::Zero();
  PointKind kind = PointKind::plain;
};

// A notch (AAMA layer 4): a short cut into the seam allowance used to match pieces.
struct Notch {
  Vec2 position = Vec2::Zero();  // on (or near) the boundary, metres
  double angle_deg = 0.0;        // direction of the cut, degrees counter-clockwise from +x
  double length_m = 0.0;         // depth of the cut when the file states it, else 0
  double width_m = 0.0;          // width when the file states it, else 0
  int type = 0;                  // AAMA notch type (0 = slit; 80..83 T, castle, check, U)
  int boundary_index = -1;       // nearest boundary vertex after import, -1 if unknown
};

// An open or closed polyline (internal lines, sew lines, cut-outs).
struct Polyline {
  std::vector<Vec2> points;
  bool closed = false;
};

// A segment given by two points (grain line, mirror/fold line, grade reference).
struct Segment {
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
};

// One piece in one size.
struct Piece {
  std::string block;     // the DXF block name, unique in the file
  std::string name;      // piece name (shared by all sizes of the piece)
  std::string size;      // size label, e.g. "38" or "M"
  int quantity = 1;      // pieces to cut (AAMA sum; ASTM "a,b" is summed)
  int quantity_flipped = 0;  // of which mirrored (ASTM second number), 0 if not stated
  std::string category;  // e.g. "SELF", "LINING"
  std::string fabric;
  std::string annotation;
  // Texts we did not recognise, kept as key/value (key empty when the text had no key).
  std::vector<std::pair<std::string, std::string>> annotations;

  // Closed outline, counter-clockwise, no repeated first vertex, no zero-length edge.
  std::vector<ContourPoint> boundary;
  bool closed = true;             // false when chaining could not close the outline
  bool self_intersecting = false;  // set by the importer's check; the outline is kept as read

  std::vector<Notch> notches;
  std::optional<Segment> grain_line;   // layer 7; its direction is the warp
  std::optional<Segment> mirror_line;  // layer 6; the fold of a half piece
  std::optional<Segment> grade_reference;  // layer 5
  std::vector<Polyline> internal_lines;    // layer 8
  std::vector<Polyline> cutouts;           // layer 11: holes in the piece (closed)
  std::vector<Polyline> sew_lines;         // layer 14
  std::vector<Vec2> drill_holes;           // layer 13
};

// A garment style: every block of one file.
struct Style {
  std::string name;         // "Style Name:" text, else the file stem
  std::string producer;     // e.g. "GERBER TECHNOLOGY / ACCUMARK 10.0.1", "CLO", "Valentina"
  std::string flavour;      // "AAMA" or "ASTM"
  std::string units;        // units the file was written in ("mm", "in", ...); data here is metres
  std::string sample_size;  // base size, empty if unknown
  std::vector<std::string> sizes;  // in the order first met
  std::vector<Piece> pieces;       // one per block, in file order

  // Distinct piece names in order of first appearance.
  std::vector<std::string> piece_names() const;
  // Blocks of the given size (pointers stay valid while `pieces` is unchanged).
  std::vector<const Piece*> pieces_of_size(const std::string& size) const;
};

// ---- geometry of a piece ------------------------------------------------------

// Signed area of a closed outline (shoelace), m²; positive when counter-clockwise.
double signed_area(const std::vector<ContourPoint>& outline);
double signed_area(const std::vector<Vec2>& outline);
// Length of the closed outline, m.
double perimeter(const std::vector<ContourPoint>& outline);
// Grain-line angle, degrees counter-clockwise from +x in (-180, 180]; 0 when absent.
double grain_angle_deg(const Piece& piece);
// True when two non-adjacent edges of the closed outline cross or touch.
bool is_self_intersecting(const std::vector<ContourPoint>& outline);

}  // namespace vgd::pattern
