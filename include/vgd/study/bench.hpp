#pragma once
// The benchmarks `vgd bench` prints (docs/performance.md): the engine on the
// shipped flag for every cloth model × integrator × thread count; the
// benchmark scenes (drape-sphere, sew-cylinder) against a peer's Blender
// figures with their checks; the cost of each effect a scene calls for; the
// dressing benchmark (two garments, flat pieces to rest).
//
// Explicit methods run with automatic sub-stepping, so each takes its own
// stable step; implicit Euler takes the scene's step, BDF its own adaptive
// ones. A model or integrator this build lacks is reported as unavailable, a
// run the engine stops as failed (with its message), and a run that exceeds
// its wall-time budget as partial (rates are per simulated second reached).
// Each run sets the OpenMP thread count it is asked for; the functions that
// run several restore the count they found.
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "vgd/dress/certificate.hpp"
#include "vgd/scene/scene.hpp"
#include "vgd/sim/integrator.hpp"

namespace vgd::study {

// The thread counts a benchmark compares: 1 and, on a machine with more,
// every core; only `only` when it is given (> 0: the user's --threads).
std::vector<int> thread_counts(int only = 0);

// ---- the engine ---------------------------------------------------------------------

struct EngineRecord {
  std::string scene, variant, model, integrator, status = "ok", message;
  std::vector<std::string> effects;
  std::vector<std::pair<std::string, double>> profile;  // seconds per effect (System::profile)
  int threads = 1, particles = 0;
  long steps = 0, rhs = 0, jacobians = 0;
  double step_s = 0, simulated_s = 0, wall_s = 0;
  double particle_steps_per_s() const { return wall_s > 0 ? particles * static_cast<double>(steps) / wall_s : 0.0; }
  bool implicit() const { return integrator == "implicit-euler" || integrator == "bdf"; }
};

// Runs `def` with `method` on `threads` frame by frame until its duration or
// the wall budget (s).
EngineRecord run_engine(const scene::SceneDef& def, sim::Method method, int threads, double budget_s);

// Every cloth model × integrator × thread count on `base`, then `base` (its
// own method, 1 thread) with each listed effect switched off in turn
// (variants "all effects", "no wind", ...). `on_record` sees each record.
std::vector<EngineRecord> engine_study(const scene::SceneDef& base, double budget_s,
                                       const std::function<void(const EngineRecord&)>& on_record = {});

// ---- the benchmark scenes -------------------------------------------------------------

struct SceneRecord {
  std::string scene, status = "ok", message;
  int threads = 1, particles = 0, body_triangles = 0;
  long steps = 0;
  double simulated_s = 0, wall_s = 0;
  double blender_s = 0;        // a peer's Blender 3.4 wall s per simulated s on this kind of machine; 0 = none
  double max_penetration = 0;  // m, exact, over every frame
  int seam_pairs = 0, seams_closed = 0;
  bool self_collision = false;
  int crossings = -1;  // cloth triangle pairs passing through each other at the last frame (sewn topology)
  bool adapt_threads = true;        // fewer threads while cores are busy (sim/threads.hpp)
  int frames_on_fewer_threads = 0;  // frames it ran on fewer than `threads`
  double per_simulated_s() const { return simulated_s > 0 ? wall_s / simulated_s : 0.0; }
};

// Runs the shipped scene `name` (drape-sphere, sew-cylinder) on `threads`;
// frames are kept in memory and measured after the clock stops (exact
// penetration against the body's triangles). `duration` > 0 replaces the
// scene's; `self_collision` adds the effect; `adapt_threads` false keeps all
// `threads` however busy the machine is.
SceneRecord run_scene(const std::string& name, int threads, double duration, bool self_collision,
                      bool adapt_threads = true);

// ---- effects on demand ----------------------------------------------------------------

struct EffectsRecord {
  std::string scene, variant, status = "ok", message;
  std::vector<std::string> effects;                     // the effects the variant lists (System::profile)
  std::vector<std::pair<std::string, double>> profile;  // seconds per effect
  int particles = 0;
  long steps = 0, rhs = 0;
  double simulated_s = 0, wall_s = 0;
  double ms_per_step() const { return steps > 0 ? 1000 * wall_s / steps : 0.0; }
  double per_simulated_s() const { return simulated_s > 0 ? wall_s / simulated_s : 0.0; }
};

// The step cost of scenes against the effects they call for, 1 thread: the
// flag with and without wind, drape-sphere without and with self-collision
// and with a moving sphere, sew-cylinder while its seams work and after their
// last merge, and without seams. `quick`: 0.4 s of the flag and the drape.
std::vector<EffectsRecord> effects_study(bool quick, const std::function<void(const EffectsRecord&)>& on_record = {});

// ---- dressing -------------------------------------------------------------------------

struct DressRecord {
  int threads = 1;
  dress::Certificate certificate;
  int body_triangles = 0;
};

// The project's A-line skirt with the T-shirt over it, from flat pieces to
// rest on the mannequin of `size`, at `spacing` (m; 0.019 gives about 5 000
// particles), on thread_counts(threads), the body kept out between
// particles or not (DrapeOptions::between_particles). `on_record` sees each record.
std::vector<DressRecord> dress_study(double spacing, const std::string& size, double time_limit,
                                     bool between_particles = true,
                                     const std::function<void(const DressRecord&)>& on_record = {},
                                     int threads = 0);

// ---- robustness ---------------------------------------------------------------------

// One drape of the robustness sweep: a garment at a mesh spacing, a size, a
// fabric and a cloth model, from its start moved by `jitter` (m; 0 = as
// placed) with seed `seed`.
struct RobustnessCase {
  std::filesystem::path garment;
  double spacing = 0.015;     // m
  std::string size;           // "" = the document's sample size
  std::string material;       // a file of data/materials ("" = the garment's own, else shirting)
  scene::ClothModel model = scene::ClothModel::mass_spring;
  double jitter = 0.0;        // m
  unsigned seed = 1;
};

struct RobustnessRecord {
  RobustnessCase run;
  dress::Certificate certificate;
  bool clean = false;        // passed: rest, seams closed, no penetration, no crossing, no failure
  std::string failure;       // the failure classes, comma-separated ("" when clean); a run not at
                             // rest says where it still moves: "no rest (torso/left-arm)"
  double max_strain = 0.0;   // the largest warp or weft strain p95 over the pieces (1)
  double max_moved = 0.0;    // m: the largest placement displacement
  // m: the largest distance of a particle from where the same case's run
  // without jitter ended (jittered runs; -1 for that run itself or when its
  // particles differ).
  double spread = -1.0;
};

struct RobustnessOptions {
  std::vector<std::filesystem::path> garments;
  std::vector<double> spacings;          // m
  std::vector<std::string> sizes;        // "" = the sample size
  std::vector<std::string> materials;    // files of data/materials; "" = the garment's own
  std::vector<scene::ClothModel> models;
  int jitters = 2;                       // jittered runs per case, besides the one as placed
  double jitter = 1e-6;                  // m
  double time_limit = 8.0;               // s simulated
  bool between_particles = true;         // DrapeOptions::between_particles
  bool sleeves_first = false;            // DrapeOptions::sleeves_first
};

// The sweep docs/drape.md reports: the project's T-shirt and A-line skirt at
// spacings 1.2, 1.5, 1.9 and 2.5 cm, sizes 34–42, shirting, jersey and denim,
// both cloth models, two jitters of 1 µm. `quick`: the T-shirt and the skirt
// at 1.5 and 1.9 cm, size 38, shirting, mass-spring, one jitter.
RobustnessOptions robustness_sweep(bool quick);

// Throws vgd::Error naming a garment or material file that is not there, or
// a cloth model this build lacks, before any drape is run.
void check_robustness(const RobustnessOptions& options);

// Drapes every case on one thread (cases in order; a case's jittered runs
// right after its run as placed; check_robustness first). `on_record` sees
// each record as it is made.
std::vector<RobustnessRecord> robustness_study(const RobustnessOptions& options,
                                               const std::function<void(const RobustnessRecord&)>& on_record = {});

// The sweep summed up per garment, mesh spacing, fabric and cloth model (the
// sizes and starts of each together), in the order the records come: the
// table docs/drape.md gives under "Robustness".
struct RobustnessRow {
  std::string garment;   // the document's file name without extension
  double spacing = 0.0;  // m
  std::string material;  // "" = the garment's own
  scene::ClothModel model = scene::ClothModel::mass_spring;
  int runs = 0, clean = 0;
  // Each failure class (Failure::kind) and how many runs failed it, in the
  // order first met.
  std::vector<std::pair<std::string, int>> failures;
  // Ranges over the clean runs (rest: simulated s), over every run (wall: s)
  // and over the jittered runs (spread: m); lo > hi when there is none.
  double rest_lo = 1.0, rest_hi = 0.0, wall_lo = 1.0, wall_hi = 0.0, spread_lo = 1.0, spread_hi = 0.0;
};
std::vector<RobustnessRow> summarise_robustness(const std::vector<RobustnessRecord>& records);

}  // namespace vgd::study
