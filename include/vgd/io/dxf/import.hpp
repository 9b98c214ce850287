#pragma once
// AAMA / ASTM D6673 DXF import: real pattern files from Gerber AccuMark, Lectra,
// Optitex, CLO and Valentina/Seamly2D into a pattern::Style (metres).
//
// What the importer understands (docs/dxf-import.md has the details):
//   - one BLOCK per piece and size, placed by an INSERT (its transform is applied);
//   - TEXTs "Key: value" (case-insensitive): Piece Name, Size, Quantity, Category,
//     Fabric, Annotation, Style Name, Sample Size, Units, ...; unknown ones are kept;
//   - AAMA layers 1 boundary, 2 turn points, 3 curve points, 4 notches, 5 grade
//     reference, 6 mirror line, 7 grain line, 8 internal lines, 11 cut-outs,
//     13 drill holes, 14 sew lines, 15 annotation text; ASTM 80-83 notch types;
//     84-87 (ASTM quality-validation copies) are used only when layer 1 is missing;
//   - units from a "Units:" text, $INSUNITS or $MEASUREMENT, else the default (mm)
//     with a warning.
// Repairs it makes and reports: chaining split outlines, duplicate vertices and
// parts, tiny closing gaps, winding. Fatal problems throw vgd::Error naming the
// file, the line and the problem; per-block problems become diagnostics naming
// the block.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/units.hpp"
#include "vgd/pattern/halves.hpp"
#include "vgd/pattern/piece.hpp"

namespace vgd::dxf {

struct ImportOptions {
  // Units to use instead of what the file states (or does not state).
  std::optional<LengthUnit> units;
  // Units for a file that states none. Valentina R12 exports are mm.
  LengthUnit default_units = LengthUnit::millimetre;
  // Unfold half pieces about their mirror line (layer 6) into full pieces.
  bool unfold_mirrored = false;
  // Join pieces written once per side whose names say nothing (CLO's left and
  // right halves, a sleeve written twice): pattern::join_pieces_written_per_side.
  bool join_per_side = false;
  // Sew each piece on its sew line (layer 14) where it has one closed inside
  // its outline: pattern::sew_on_sew_line; the seam allowance is cut off.
  bool sew_on_sew_lines = false;
  // Cut small self-intersection loops (≤ 5 % of the area) out of outlines.
  bool repair_self_intersections = true;
  // Outline end points closer than this are joined silently (m).
  double join_tolerance_m = 1e-6;
  // Gaps up to this are bridged and reported; larger ones leave the outline open (m).
  double repair_gap_m = 1e-3;
  // Largest coordinate accepted after unit conversion (m): guards against
  // overflow and garbage. A piece may sit far from the origin (a 79 x 72 mm
  // piece placed 1.25 km away is a piece).
  double max_coordinate_m = 1.0e6;
  // Largest width or height of one piece (m): a block larger than this is
  // garbage or in the wrong units, and is dropped with an error; the other
  // blocks are kept.
  double max_piece_size_m = 20.0;
};

// What the file held for one block, as stored (before any unfolding).
struct BlockReport {
  std::string block, piece, size, category;
  int quantity = 1;
  int boundary_vertices = 0;  // after chaining and removing duplicates
  bool closed = false;
  double area_m2 = 0.0;
  double perimeter_m = 0.0;
  double grain_angle_deg = 0.0;
  int notches = 0, internal_lines = 0, drill_holes = 0;
  bool mirror_line = false;
  bool self_intersecting = false;  // as stored, before any repair
  bool imported = true;            // false when the block was dropped (see diagnostics)
};

struct ImportSummary {
  std::string producer, flavour, style, units, sample_size;
  int pieces = 0;  // distinct piece names
  int blocks = 0;  // piece × size blocks imported
  std::vector<std::string> sizes;
};

struct ImportResult {
  pattern::Style style;
  ImportSummary summary;
  std::vector<BlockReport> blocks;
  Diagnostics diagnostics;  // warnings and dropped blocks, each naming the block
  std::vector<pattern::JoinedPieces> joined;  // ImportOptions::join_per_side
  // ImportOptions::sew_on_sew_lines: blocks sewn on their sew line, and the
  // seam allowance cut off (m, smallest and largest over them).
  int sewn_on_sew_lines = 0;
  double allowance_min = 0.0, allowance_max = 0.0;
};

// What join_per_side and sew_on_sew_lines did, in words, a line each (none
// when they did nothing).
std::vector<std::string> import_notes(const ImportResult& result);

// Imports a file. Throws vgd::Error for files that cannot be read at all
// (empty, binary DXF, not a DXF, truncated, no pieces).
ImportResult import_file(const std::filesystem::path& path, const ImportOptions& opts = {});

// Same, from text in memory; `name` is used in messages (fuzzing, tests).
ImportResult import_string(std::string_view text, const std::string& name, const ImportOptions& opts = {});

}  // namespace vgd::dxf
