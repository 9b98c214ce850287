#pragma once
// The drape certificate: the numbers QA and a designer need before trusting a
// picture of a draped garment (docs/drape.md). Written as JSON beside every
// drape's outputs.
//
//   penetration    how deep cloth particles sit inside the body, measured
//                  exactly against the body's triangles (not the collision
//                  grid), m;
//   intersections  cloth triangle pairs that pass through each other;
//   seams          pairs closed, and the gap of each seam's open pairs, m;
//   strain         per piece, percentiles over its triangles of the
//                  engineering strain along the warp and the weft and of the
//                  shear angle (degrees), from each triangle's deformation
//                  gradient against its flat pattern shape;
//   contact        particles touching the body, their area and the pressure
//                  the cloth puts on it (normal force / particle area, Pa);
//   energy         the mean kinetic energy per particle at every frame, J.
#include <map>
#include <string>
#include <vector>

#include "vgd/scene/build.hpp"

namespace vgd::dress {

using Vec3 = Eigen::Vector3d;

struct Percentiles {
  double p5 = 0, p50 = 0, p95 = 0, max = 0, min = 0;
};

struct PieceStrain {
  std::string piece;
  Percentiles warp, weft;  // engineering strain, dimensionless (0.01 = 1 %)
  Percentiles shear_deg;   // change of the warp–weft angle, degrees
};

struct SeamState {
  std::string name;
  int pairs = 0, closed = 0;  // closed: merged, or within the merge distance
  double max_gap = 0, mean_gap = 0;  // m over all pairs
  Vec3 widest_at = Vec3::Zero();     // m: midpoint of the pair with the largest gap (where to look)
};

struct ContactState {
  int particles = 0;          // within the contact distance of the body
  double area = 0;            // m²: their lumped cloth area
  double force = 0;           // N: total normal force on the body
  Percentiles pressure;       // Pa over the contact particles
};

struct StageTime {
  std::string name;         // placing, sewing, settling
  double wall_s = 0;        // wall-clock seconds
  double simulated_s = 0;   // simulated seconds (0 for placing)
};

struct Certificate {
  // What was run.
  std::string version;                      // vgd's version
  std::vector<std::pair<std::string, std::string>> inputs;    // (what, file or value)
  std::vector<std::pair<std::string, std::string>> settings;  // (name, value with unit)
  // Why it stopped: "rest", "time limit", "error".
  std::string stop_reason;
  std::string stop_message;
  double simulated_s = 0, wall_s = 0;
  int frames = 0;
  std::vector<StageTime> stages;
  // Where the time went: seconds per effect (System::profile, all verbs) and
  // the integrator's counts.
  std::vector<std::pair<std::string, double>> effect_seconds;
  long steps = 0, force_evaluations = 0, linear_iterations = 0;
  // Self-collision's work over the run (absent: -1): detection passes, pairs
  // found, particles its fail-safe put back to their step's start.
  long self_detections = -1, self_pairs = 0, self_reverted = 0, self_untangled = 0;
  // The state reached.
  int particles = 0, triangles = 0;
  double max_penetration = 0;   // m, exact
  int particles_inside = 0;     // deeper than 0
  Vec3 deepest_at = Vec3::Zero();  // m: the deepest particle (where to look)
  double penetration_limit = 0.001;  // m: what the drape promises
  int triangle_intersections = -1;   // -1 when not measured
  std::map<std::string, int> crossings_by_pieces;  // "A / B" (A ≤ B by name) → crossing pairs between them
  std::vector<SeamState> seams;
  std::vector<PieceStrain> strain;
  ContactState contact;
  std::vector<double> times;            // s, per frame
  std::vector<double> kinetic_energy;   // J per particle, per frame
  // The checks a QA gate applies: penetration ≤ limit, every seam closed, no
  // crossing triangles, the run ended at rest.
  bool passed() const;
};

// Measures the scene's state at full positions x (3N of the original
// particles, as frames give them). `merge_distance` (m) counts a seam pair as
// closed; particles nearer the body than `contact_distance` (m: the collision
// clearance plus a tolerance) touch it. Measuring intersections costs ~0.1 s
// on 20 000 triangles; off when `intersections` is false.
void measure_state(const scene::Scene& scene, const sim::VecX& x, double merge_distance, double contact_distance,
                   bool intersections, Certificate& out);

// The certificate as pretty-printed JSON.
std::string to_json(const Certificate& c);

}  // namespace vgd::dress
