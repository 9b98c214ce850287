#pragma once
// The virtual fabric lab (seed 002 §5): the textile industry's own
// tests run on the cloth models, measured against mechanics (docs/fabric-lab.md).
//
// The lab builds a specimen (a strip of the fabric as a grid, cut at an angle
// to the warp), puts the engine's own effects on it (strain rosette + bending,
// or mass-spring; gravity when the test weighs the specimen), holds and loads
// it as the test machine would, solves for static equilibrium (Newton with the
// effects' exact Jacobians, the load applied in increments), measures, and
// compares with the analytic reference (../shared/reference/mechanics.md,
// recomputed here so the lab runs without ../shared):
//
//   tip-cantilever  strip clamped at one end, dead tip load P per width:
//                   u/L and w/L of the tip vs the elastica, k = P L²/B = 1…10
//   tensile         ISO 13934-1 strip (200 × 50 mm) stretched 0.01 % between clamps
//                   free to slide across (no clamp constraint): E_θ vs the orthotropic off-axis
//                   formula, θ = 0, 15, …, 90° (or the one --angle)
//   cantilever      strip under its own weight: chord angle vs the heavy
//                   elastica for g = w L³/B = 1, 2, 5, 8, 10, 20, and the
//                   bending length as FAST / ASTM D1388 computes it
//   buckling        strips of 50 and 100 mm, clamped-free (dead end load)
//                   and clamped-clamped (end shortening): the load at which
//                   the straight strip's stiffness across the sheet vanishes
//                   vs Euler's P_cr = C B / L² (rosette model only)
//                   and in shear: a 200 × 50 mm plate clamped on its long
//                   edges, one clamp moved parallel to the other: critical
//                   N_xy, wrinkle half-waves and wavelength, vs k_s π² D / b²,
//                   k_s = 8.98 (long plate, clamped edges) where the bending is
//                   isotropic (NaN otherwise)
//   shear           KES-FB1: 200 mm along the clamps, 50 mm between them, one
//                   clamp moved sideways by L tan φ at fixed distance, φ ≤ 8°:
//                   force per clamp length vs uniform simple shear of the law,
//                   G at 0.5° vs Q̄₆₆(θ) (G_xy at 0 and 90°)
//   bending         KES-FB2 pure bending: 10 mm between clamps set on an arc,
//                   K = ±0.5…2.5 1/cm: moment per width vs the plate's B_θ K, and
//                   B (the KES slope) per direction (warp and weft, or --angle)
//   drape           Cusick: a 300 mm disc clamped on a 180 mm disk hung to rest
//                   by the engine's implicit Euler: drape coefficient, nodes and
//                   a top view (no analytic reference)
//
// Bending references use the narrow-strip rigidity B_strip
// (sim::bending_rigidity_strip), the one a free strip shows; pure bending's
// wide specimen the plate's B_θ (sim::bending_rigidity).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "vgd/scene/material.hpp"
#include "vgd/scene/scene.hpp"

namespace vgd::lab {

enum class Test { tip_cantilever, tensile, cantilever, buckling, shear, bending, drape };
const char* to_string(Test t);
// "tip-cantilever", "tensile", "cantilever", "buckling", "shear", "bending", "drape"; throws std::invalid_argument.
Test parse_test(const std::string& s);

// What to run.
struct LabSpec {
  Test test = Test::tip_cantilever;
  scene::ClothModel model = scene::ClothModel::strain_rosette;
  double angle_deg = 0.0;      // specimen axis from the warp (deg); tensile: < 0 = every 15° from 0 to 90;
                               // bending: < 0 = 0 and 90°
  double resolution = 0.005;   // m, grid spacing along the specimen
  double length = 0.1;         // m, free length of the tip-cantilever (tensile: the ISO 13934-1 200 × 50 mm strip)
  double width = 0.01;         // m, bending specimens' width (2 cells across, or width/resolution)
  // Run the fabric with ν_xy = 0, where the strip's and the plate's bending
  // rigidities coincide and the elastica's single EI is unambiguous
  // (docs/fabric-lab.md, "Strip or plate").
  bool poisson_free = false;
};

// One measurement: at x (k, θ in deg, g), `quantity` measured and expected
// (NaN where mechanics gives no reference: the drape's DC and nodes).
struct LabPoint {
  std::string quantity;  // e.g. "w/L", "u/L", "E_theta N/m", "chord deg"
  double x = 0.0;
  double measured = 0.0, expected = 0.0;
  double rel_error = 0.0;  // measured / expected − 1 (NaN when the solve failed)
};

struct LabResult {
  std::string test, material, model;
  std::string x_name;               // what x is: "k = PL^2/B", "angle deg", "g = wL^3/B"
  std::vector<LabPoint> points;
  double max_rel_error = 0.0;       // over the points with a reference, |rel_error| (inf when a solve failed, NaN
                                    // when no point has a reference: drape)
  double wall_s = 0.0;              // s, the whole test
  int cells_along = 0, cells_across = 0;  // the specimen grid (cells along the free length)
  std::vector<std::string> notes;   // reference, rigidities, what is reported beside the points
  // drape: the view from above, grey levels row by row from the top (+y up),
  // top_view_size² pixels of 0.5 mm centred on the disk: 255 nothing, 225 the
  // bare disk, darker the fabric (the steeper, the darker). Empty for other tests.
  std::vector<std::uint8_t> top_view;
  int top_view_size = 0;
};

// The material NAME (data/materials/NAME.xvc, MATERIAL id NAME) or an XVC
// FILE (its MATERIAL whose id is the file's stem). Throws vgd::Error.
scene::MaterialDef lab_material(const std::string& name_or_file);

// Runs one test. A static solve that fails leaves NaN in its points and makes
// max_rel_error infinite (the notes say why). Throws vgd::Error when the
// material lacks the model's values, or for buckling with the mass-spring model.
LabResult run(const LabSpec& spec, const scene::MaterialDef& material);

// The result as CSV: test,material,model,quantity,x,measured,expected,rel_error
// (header row), written atomically.
void write_csv(const LabResult& r, const std::filesystem::path& file);

// Q̄₆₆ (N/m): the sheet's stiffness in simple shear at angle_deg from the warp
// (G_xy at 0 and 90°; Jones eq. 2.85), the shear test's reference.
double simple_shear_modulus(const sim::OrthotropicMaterial& o, double angle_deg);

// ---- vgd lab all: every test and a Markdown report ----

// What the test does and what it is compared with, one line (for reports).
const char* describe(Test t);

// The runs of `vgd lab all`, in order: every test at `resolution` (tensile at
// 0…90°, bending warp and weft), the drape at `drape_resolution` (it costs
// ~ resolution⁻³: 116 s at 5 mm, 7 s at 10 mm on the shirting). Buckling is
// left out for the mass-spring model, which has no stiffness across the sheet.
std::vector<LabSpec> all_specs(scene::ClothModel model, double resolution, double drape_resolution, bool poisson_free);

// One run of a report and the files written beside it (names relative to the report).
struct ReportEntry {
  LabSpec spec;
  LabResult result;
  std::string csv, png;
};

// The report: a summary table, then per test what it does, its grid, a table
// of measured vs expected with relative errors, max |rel error|, wall time and
// links to its CSV and PNG. `command` is quoted as what generated it; `notes`
// are listed under the summary.
std::string report_markdown(const std::vector<ReportEntry>& runs, const std::string& command,
                            const std::vector<std::string>& notes, double total_wall_s);

// ---- analytic references (mechanics.md §1, §2), by shooting on θ'(0) ----

// Cantilever with a dead vertical tip load, k = P L²/EI: tip shortening u/L,
// deflection w/L, tip angle (rad). Agrees with cantilever_tip_load.csv to 1e-9.
struct Elastica {
  double u_over_L = 0.0, w_over_L = 0.0, tip_angle = 0.0;
  double chord_deg() const;  // atan(w / (L − u)) in degrees
};
Elastica tip_load_elastica(double k);
// Cantilever under its own weight, g = q L³/EI (heavy_elastica.csv).
Elastica heavy_elastica(double g);
// Peirce's bending length from the chord angle θ (rad): c / L = (cos(θ/2) / (8 tan θ))^(1/3).
double peirce_bending_length_over_L(double chord_rad);
// Cusick's drape coefficient (mechanics.md §6) from the shadow area A_s (m²) of a
// specimen of diameter D on a disk of diameter d (m): (A_s − A_d)/(A_D − A_d).
double drape_coefficient(double shadow_area, double specimen_diameter, double disk_diameter);

}  // namespace vgd::lab
