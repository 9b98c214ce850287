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

// Seams the drafter itself intends, by piece name and boundary stretch (the k-th
// stretch starts at the k-th turn point of the piece's boundary, counting from
// vertex 0, which every drafted piece makes a turn point; xvc::from_style splits
// the outline the same way, so stretch k is the k-th boundary C2DSEQ). The first
// hem is sewn to the concatenation of the others, in order (docs/xvc.md, SEAM).
struct HemPlan {
  std::string piece;     // piece name, e.g. "FRONT"
  int from = 0, to = 0;  // first and last stretch, inclusive, in contour order
  bool reverse = false;  // true: sewn against the contour (clockwise)
};
struct SeamPlan {
  std::string name;           // e.g. "left side seam"
  std::vector<HemPlan> hems;  // 2 or more
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

// The skirt's seams: right and left side seams (FRONT forward, BACK reverse) and
// the waist seam: WAISTBAND stretch 1 (the band's lower edge after the centre-back
// overlap, which stays open as the button stand) sewn to BACK's right waist half,
// FRONT's waist and BACK's left waist half, all reversed. BACK's waist is split at
// centre back (a turn point) so that the band can start there.
std::vector<SeamPlan> skirt_seams();

// ---- T-shirt ----------------------------------------------------------------------
//
// A simplified flat-pattern T-shirt after the jersey T-shirt block (Aldrich,
// "Metric Pattern Cutting for Women's Wear", 6th ed., ch. 5 "the basic T-shirt
// block"): no darts, straight side seams, shoulder sloped from the neck point,
// the front neck lower than the back neck, a set-in short sleeve whose cap is
// longer than the armhole by a stated ease.
//
// Pieces (all laid face up, the wearer's left on the piece's +x side for FRONT
// and on its -x side for BACK, as a pattern maker draws them):
//   FRONT, BACK   cut once each, full width, centred on x = 0, hem on y = 0,
//                 stretches 0 hem, 1 right side seam, 2 right armhole,
//                 3 right shoulder, 4 neckline, 5 left shoulder,
//                 6 left armhole, 7 left side seam.
//   LEFT SLEEVE, RIGHT SLEEVE  cut once each (the right is the left mirrored):
//                 stretches 0 sleeve hem, 1 right underarm seam, 2 cap,
//                 3 left underarm seam.
// Two sleeve pieces instead of one SLEEVE cut twice: every PATTERN is then one
// piece of cloth, so every SEAM names concrete pieces (the left cap sews to the
// left armholes) and every arrangement places one piece; a quantity-2 sleeve
// would need a rule for which copy a seam or a placement means.
//
// Guarantees (tests/pattern/test_draft_tshirt.cpp): front and back side seams
// and shoulders have equal length (to rounding), the two underarm seams of a
// sleeve are equal, and each sleeve cap is the front plus back armhole plus
// cap_ease. Notches: a single notch on the front armhole, a double notch on the
// back armhole, the same marks on the cap at the same distances from the
// underarm (the ease spread in proportion), and a shoulder notch on the cap.
struct TShirtMeasurements {
  std::string size = "38";
  double bust = 0.88;            // bust girth, m
  double hip = 0.97;             // hip girth, m: the hem must pass over it
  double neck = 0.36;            // neck base girth, m
  double shoulder = 0.135;       // shoulder length, neck point to shoulder point, m (a jersey tee's shoulder drops just past the body's)
  double shoulder_drop = 0.04;   // shoulder point below the neck point, m
  double length = 0.62;          // neck point to hem, vertically, m
  double armhole_depth = 0.20;   // neck point to the underarm line, vertically, m
  double upper_arm = 0.28;       // upper-arm girth, m
  double sleeve_length = 0.20;   // cap top to sleeve hem, m
  double bust_ease = 0.10;       // added to the bust girth (loose jersey fit), m
  double hip_ease = 0.08;        // added to the hip girth at the hem (the side seams flare when the hips need it), m
  double arm_ease = 0.06;        // added to the upper-arm girth, m
  double front_neck_depth = 0.08;  // neck point level to centre-front neck, m
  double back_neck_depth = 0.02;   // neck point level to centre-back neck, m
  double cap_ease = 0.015;       // sleeve cap minus (front + back armhole), m
  double sleeve_hem_taper = 0.02;  // sleeve half-width lost from underarm to hem, m
};

// Women's sizes 34-42 (same labels and chart as the skirt), sample 38.
std::vector<TShirtMeasurements> tshirt_size_table();

// Drafts one size: FRONT, BACK, LEFT SLEEVE, RIGHT SLEEVE. Throws vgd::Error when
// the measurements cannot make a T-shirt (non-positive lengths, a shoulder wider
// than the chest, a sleeve cap taller than the sleeve).
std::vector<Piece> draft_tshirt(const TShirtMeasurements& m);

// A graded style: every size given, sample size 38 when present.
Style draft_tshirt_style(const std::vector<TShirtMeasurements>& sizes = tshirt_size_table());

// The T-shirt's seams: side seams and shoulders (FRONT forward, BACK reverse),
// each sleeve cap (forward) to back + front armhole or front + back armhole
// (reversed, in the order the cap meets them), and each sleeve's underarm seam
// (stretch 3 forward, stretch 1 reverse).
std::vector<SeamPlan> tshirt_seams();

// A graded style from one drafter over a size table: every size's pieces in
// table order, producer "vgd", AAMA in mm; sample size 38 when drafted, else
// the first.
template <class Measurements, class Drafter>
Style graded_style(std::string name, const std::vector<Measurements>& sizes, Drafter draft) {
  Style s;
  s.name = std::move(name);
  s.producer = "vgd";
  s.flavour = "AAMA";
  s.units = "mm";
  for (const auto& m : sizes) {
    for (auto& p : draft(m)) s.pieces.push_back(std::move(p));
    s.sizes.push_back(m.size);
  }
  if (!s.sizes.empty()) s.sample_size = s.sizes.front();
  for (const auto& size : s.sizes)
    if (size == "38") s.sample_size = size;
  return s;
}

}  // namespace vgd::pattern
