#pragma once
// Pattern drafting from body measurements: the project's own sample garments,
// so that the demo, tests and benchmarks never depend on third-party files.
//
// The A-line skirt follows the usual flat-pattern draft (e.g. Aldrich,
// "Metric Pattern Cutting for Women's Wear", the straight/A-line skirt block),
// simplified to dart-free panels whose side seams curve from hip to waist:
// a front and a back panel (each cut once, full width) and a straight
// waistband. Notches match the side seams at the hip line (single at the front,
// double at the back, as pattern makers mark them) and the waistband to the
// side seams and the centre front. Units: metres.
#include <string>
#include <vector>

#include "vgd/pattern/piece.hpp"

namespace vgd::pattern {

// Body measurements for a skirt (m).
struct SkirtMeasurements {
  std::string size = "38";
  double waist = 0.72;        // waist girth
  double hip = 0.97;          // hip girth at the fullest part
  double hip_depth = 0.20;    // waist to hip line, vertically
  double length = 0.60;       // waist to hem at centre front
  double hip_ease = 0.04;     // added to the hip girth for movement
  double waist_ease = 0.01;   // added to the waist girth
  double flare = 0.07;        // extra half-width at the hem of each panel (A-line)
  double waistband_width = 0.035;  // finished width; the piece is twice that (folded)
  double waistband_overlap = 0.03; // button stand at the back
};

// Women's sizes 34-42 after the German DOB size chart (EN 13402-3 labels);
// girths are the chart's body measurements.
std::vector<SkirtMeasurements> skirt_size_table();

// Drafts one size: pieces FRONT, BACK and WAISTBAND with turn points, notches
// and grain lines. Throws vgd::Error if the measurements cannot make a skirt
// (waist larger than hip, non-positive lengths).
std::vector<Piece> draft_skirt(const SkirtMeasurements& m);

// A graded style: every size of the table (or the given ones), sample size 38.
Style draft_skirt_style(const std::vector<SkirtMeasurements>& sizes = skirt_size_table());

}  // namespace vgd::pattern
