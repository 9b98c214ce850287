// vgd bench drape-sphere | sew-cylinder: the benchmark scenes
// (data/scenes/), 1 thread and every core, wall time per simulated second
// against a peer's Blender 3.4 figures, with the exact penetration over every
// frame and the seams closed.
//
// vgd bench engine: the shipped flag (data/scenes/flag.json) for every cloth
// model x integrator, with 1 thread and with every core, then the cost of each
// listed effect (the flag with one effect switched off at a time).
//
// vgd bench effects (issue 7): the step cost of a scene against the effects it
// calls for — the flag with and without wind, drape-sphere with and without
// self-collision, sew-cylinder while its seams work and after their last merge.
//
// vgd bench accuracy (issue 7, cmd_accuracy.cpp): error against CPU time for
// every integrator on problems with a known answer.
//
// vgd bench dress (issue 4, cmd_bench_dress.cpp): two garments from flat
// pieces to rest, against the 10 s target.
//
// Explicit methods run with automatic sub-stepping, so each takes its own
// stable step; implicit Euler takes the scene's step, BDF its own adaptive
// ones. A model or integrator this build lacks is reported as unavailable, a
// run the engine stops as failed (with its message), and a run that exceeds
// its wall-time budget as partial (rates are per simulated second reached).
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/mesh/surface_checks.hpp"
#include "vgd/scene/build.hpp"
#include "vgd/scene/certificate.hpp"
#include "vgd/scene/data.hpp"
#include "vgd/scene/json.hpp"

namespace vgd::cli {
// cmd_accuracy.cpp
int bench_accuracy(bool quick, bool json, const std::filesystem::path& out_dir, const std::vector<std::string>& problems);
// cmd_bench_dress.cpp
int bench_dress(double spacing, const std::string& size, double time_limit, bool json);
}  // namespace vgd::cli

namespace {

namespace scene = vgd::scene;
namespace sim = vgd::sim;

struct Options {
  bool json = false, quick = false;
  std::string scene_file;
};

struct Record {
  std::string scene, variant, model, integrator, status = "ok", message;
  std::vector<std::string> effects;
  std::vector<std::pair<std::string, double>> profile;  // seconds per effect (System::profile)
  int threads = 1, particles = 0;
  long steps = 0, rhs = 0, jacobians = 0;
  double step_s = 0, simulated_s = 0, wall_s = 0;
  double particle_steps_per_s() const { return wall_s > 0 ? particles * static_cast<double>(steps) / wall_s : 0.0; }
  bool implicit() const { return integrator == "implicit-euler" || integrator == "bdf"; }
};

// Runs `def` frame by frame until its duration or the wall budget (s).
Record run_one(const scene::SceneDef& def, sim::Method method, int threads, double budget_s) {
  Record r;
  r.scene = def.name;
  r.model = scene::to_string(def.cloth.front().model);
  r.integrator = sim::to_string(method);
  r.threads = threads;
  r.effects = scene::effect_names(def);
  if (!scene::model_available(def.cloth.front().model)) {
    r.status = "unavailable";
    r.message = "this build has no " + r.model + " model";
    return r;
  }
  omp_set_num_threads(threads);
  scene::Scene s = scene::build(def);
  sim::IntegratorSettings settings = s.integrator;
  settings.method = method;
  settings.auto_substep = sim::is_explicit(method);  // each explicit method at its own stable step
  std::unique_ptr<sim::Integrator> integ;
  try {
    integ = sim::make_integrator(settings);
  } catch (const sim::SimulationError& e) {
    r.status = "unavailable";
    r.message = e.what();
    return r;
  }
  auto& sys = *s.system;
  r.particles = sys.model().num_particles();
  sim::State st = sim::initial_state(sys.model());
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto wall = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  try {
    sys.apply_prescribed(st);
    integ->prepare(sys, st);
    const int frames = static_cast<int>(std::floor(s.run.duration * s.run.fps + 1e-9));
    for (int k = 1; k <= frames; ++k) {
      integ->advance(sys, st, k / s.run.fps);
      if (wall() > budget_s && k < frames) {
        r.status = "partial";
        r.message = "stopped at the wall-time budget of " + vgd::format_fixed(budget_s, 0) + " s";
        break;
      }
    }
  } catch (const sim::SimulationError& e) {
    r.status = "failed";
    r.message = e.what();
  }
  r.wall_s = wall();
  r.simulated_s = st.t;
  for (const auto& p : sys.profile()) r.profile.emplace_back(p.name, p.seconds);
  const auto stats = integ->stats();
  r.steps = stats.steps;
  r.rhs = stats.rhs_evaluations;
  r.jacobians = stats.jacobian_evaluations;
  r.step_s = integ->step() > 0 ? integ->step() : (stats.steps > 0 ? st.t / stats.steps : 0.0);
  return r;
}

nlohmann::json to_json(const Record& r) {
  nlohmann::json j{{"scene", r.scene},
                   {"model", r.model},
                   {"integrator", r.integrator},
                   {"threads", r.threads},
                   {"particles", r.particles},
                   {"steps", r.steps},
                   {"wall_s", r.wall_s},
                   {"particle_steps_per_s", r.particle_steps_per_s()},
                   {"simulated_s", r.simulated_s},
                   {"step_s", r.step_s},
                   {"effects", r.effects},
                   {"status", r.status}};
  if (!r.variant.empty()) j["variant"] = r.variant;
  auto prof = nlohmann::json::object();
  for (const auto& [name, sec] : r.profile) prof[name] = prof.value(name, 0.0) + sec;
  j["effect_seconds"] = prof;
  if (!r.message.empty()) j["message"] = r.message;
  if (r.implicit() && r.simulated_s > 0) {
    j["rhs_per_simulated_s"] = r.rhs / r.simulated_s;
    j["jacobians_per_simulated_s"] = r.jacobians / r.simulated_s;
  }
  return j;
}

void print_row(const Record& r) {
  auto rate = [&](long n) { return r.implicit() && r.simulated_s > 0 ? vgd::format_fixed(n / r.simulated_s, 0) : "-"; };
  std::printf("%-15s %-17s %3d %10.3g %7ld %8.3f %11.3g %9s %9s  %s%s%s\n", r.model.c_str(), r.integrator.c_str(),
              r.threads, r.step_s, r.steps, r.wall_s, r.particle_steps_per_s(), rate(r.rhs).c_str(),
              rate(r.jacobians).c_str(), r.status.c_str(), r.message.empty() ? "" : ": ",
              r.message.substr(0, 90).c_str());
  std::fflush(stdout);
}

// ---- the benchmark scenes against Blender's published figures -----------

// A peer's measurements of Blender 3.4 (Debian's package, implicit mass-spring
// cloth) on this kind of machine: wall seconds per simulated second.
struct Reference {
  const char* scene;
  double one_thread, two_threads;
};
constexpr Reference kBlender[] = {{"drape-sphere", 11.4, 8.1}, {"sew-cylinder", 13.0, 9.0}};
// The same peer's drape-sphere with Blender's self-collision on.
constexpr Reference kBlenderSelf[] = {{"drape-sphere", 13.9, 9.4}};

struct SceneRecord {
  std::string scene, status = "ok", message;
  int threads = 1, particles = 0, body_triangles = 0;
  long steps = 0;
  double simulated_s = 0, wall_s = 0, blender_s = 0;
  double max_penetration = 0;  // m, exact, over every frame
  int seam_pairs = 0, seams_closed = 0;
  bool self_collision = false;
  int crossings = -1;  // cloth triangle pairs passing through each other at the last frame (sewn topology)
  double per_simulated_s() const { return simulated_s > 0 ? wall_s / simulated_s : 0.0; }
};

// Runs a shipped benchmark scene; frames are kept in memory and measured
// after the clock stops (exact penetration against the body's triangles).
SceneRecord run_scene(const std::string& name, int threads, double duration, bool self_collision) {
  SceneRecord r;
  r.scene = name;
  r.threads = threads;
  r.self_collision = self_collision;
  omp_set_num_threads(threads);
  scene::SceneDef def = scene::load_scene(scene::shipped_scene(name));
  if (duration > 0) def.run.duration = duration;
  if (self_collision) def.effects.self_collision = sim::SelfCollisionDef{};
  def.outputs.clear();
  scene::Scene s = scene::build(def);
  auto integ = sim::make_integrator(s.integrator);
  auto& sys = *s.system;
  r.particles = sys.model().num_particles();
  r.body_triangles = s.avatar ? s.avatar->surface.num_triangles() : 0;
  sim::State st = sim::initial_state(sys.model());
  sim::MemorySink frames;
  const sim::RunSummary sum = sim::run(sys, *integ, st, s.run, {&frames});
  r.wall_s = sum.wall_s;
  r.simulated_s = sum.simulated_s;
  r.steps = sum.stats.steps;
  if (!sum.ok) {
    r.status = "failed";
    r.message = sum.error;
  }
  for (const auto& ref : self_collision ? std::span<const Reference>(kBlenderSelf) : std::span<const Reference>(kBlender))
    if (name == ref.scene) r.blender_s = threads > 1 ? ref.two_threads : ref.one_thread;
  if (s.avatar)
    for (const auto& x : frames.frames) {
      std::vector<vgd::mesh::Vec3> pts(sys.model().num_particles());
      for (int i = 0; i < sys.model().num_particles(); ++i) pts[i] = sim::at(x, i);
      for (double d : vgd::mesh::penetration_depths(s.avatar->surface, pts)) r.max_penetration = std::max(r.max_penetration, d);
    }
  if (!frames.frames.empty()) {
    scene::Certificate c;
    const double merge = def.effects.seams ? def.effects.seams->effect.merge_distance : 0.0;
    scene::measure_state(s, frames.frames.back(), merge, 0.004, true, c);
    for (const auto& seam : c.seams) r.seam_pairs += seam.pairs, r.seams_closed += seam.closed;
    r.crossings = c.triangle_intersections;
  }
  return r;
}

nlohmann::json to_json(const SceneRecord& r) {
  nlohmann::json j{{"scene", r.scene},
                   {"threads", r.threads},
                   {"particles", r.particles},
                   {"body_triangles", r.body_triangles},
                   {"steps", r.steps},
                   {"simulated_s", r.simulated_s},
                   {"wall_s", r.wall_s},
                   {"wall_per_simulated_s", r.per_simulated_s()},
                   {"blender_wall_per_simulated_s", r.blender_s},
                   {"speedup_vs_blender", r.per_simulated_s() > 0 ? r.blender_s / r.per_simulated_s() : 0.0},
                   {"max_penetration_m", r.max_penetration},
                   {"seam_pairs", r.seam_pairs},
                   {"seams_closed", r.seams_closed},
                   {"self_collision", r.self_collision},
                   {"crossing_triangle_pairs", r.crossings},
                   {"status", r.status}};
  if (!r.message.empty()) j["message"] = r.message;
  return j;
}

// `vgd bench drape-sphere` / `sew-cylinder`: 1 thread, then every core.
int scene_bench(const std::string& name, bool json, double duration, bool self_collision) {
  const int cores = std::max(1, omp_get_num_procs());
  std::vector<int> thread_counts{1};
  if (cores > 1) thread_counts.push_back(cores);
  std::vector<SceneRecord> records;
  if (!json)
    std::printf("%-13s %3s %9s %9s %7s %8s %12s %12s %8s %9s %7s %9s  %s\n", "scene", "thr", "particles", "body tris",
                "sim s", "wall s", "wall/sim-s", "Blender", "speedup", "pen. mm", "seams", "crossings", "status");
  for (const int t : thread_counts) {
    SceneRecord r = run_scene(name, t, duration, self_collision);
    if (!json) {
      // No Blender figure for this scene (sew-cylinder with self-collision): a dash, not 0.
      const bool known = r.blender_s > 0 && r.per_simulated_s() > 0;
      const std::string blender = known ? vgd::format_fixed(r.blender_s, 1) : "-";
      const std::string speedup = known ? vgd::format_fixed(r.blender_s / r.per_simulated_s(), 1) + "x" : "-";
      std::printf("%-13s %3d %9d %9d %7.2f %8.2f %12.3f %12s %8s %9.3f %7s %9d  %s%s%s\n",
                  (r.scene + (self_collision ? "+self" : "")).c_str(), r.threads,
                  r.particles, r.body_triangles, r.simulated_s, r.wall_s, r.per_simulated_s(), blender.c_str(),
                  speedup.c_str(), r.max_penetration * 1000,
                  r.seam_pairs ? (std::to_string(r.seams_closed) + "/" + std::to_string(r.seam_pairs)).c_str() : "-",
                  r.crossings, r.status.c_str(), r.message.empty() ? "" : ": ", r.message.substr(0, 80).c_str());
      std::fflush(stdout);
    }
    records.push_back(std::move(r));
  }
  omp_set_num_threads(cores);
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& r : records) list.push_back(to_json(r));
    vgd::cli::print_json(list);
  }
  return vgd::cli::kOk;
}

// ---- effects on demand (issue 7) ------------------------------------------------

// One run of a scene variant, 1 thread, no outputs: cost per step and per effect.
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

// Where a run stood at one frame: enough to split it into phases.
struct Mark {
  double t = 0, wall_s = 0;
  long steps = 0, rhs = 0;
  std::vector<double> seconds;  // per effect (System::profile)
};

Mark mark(const sim::System& sys, const sim::Integrator& integ, double t, double wall_s) {
  Mark m{t, wall_s, integ.stats().steps, integ.stats().rhs_evaluations, {}};
  for (const auto& p : sys.profile()) m.seconds.push_back(p.seconds);
  return m;
}

// The part of a run between two marks.
EffectsRecord phase(const EffectsRecord& base, const std::string& variant, const Mark& a, const Mark& b) {
  EffectsRecord r = base;
  r.variant = variant;
  r.simulated_s = b.t - a.t;
  r.wall_s = b.wall_s - a.wall_s;
  r.steps = b.steps - a.steps;
  r.rhs = b.rhs - a.rhs;
  for (std::size_t i = 0; i < r.profile.size(); ++i) r.profile[i].second = b.seconds[i] - a.seconds[i];
  return r;
}

// Runs `def` for its duration with 1 thread. With `split_at_seams`, returns
// two phases: while the seam effect works, and after it finished (its last
// merge); else one record for the whole run.
std::vector<EffectsRecord> effects_run(const std::string& variant, const scene::SceneDef& def, bool split_at_seams) {
  EffectsRecord r;
  r.scene = def.name;
  r.variant = variant;
  omp_set_num_threads(1);
  scene::Scene s = scene::build(def);
  auto& sys = *s.system;
  auto integ = sim::make_integrator(s.integrator);
  r.particles = sys.model().num_particles();
  for (const auto& p : sys.profile()) {
    r.effects.push_back(p.name);
    r.profile.emplace_back(p.name, 0.0);
  }
  const sim::Effect* seam = nullptr;
  for (const auto& e : sys.effects())
    if (std::string(e->name()) == "seam") seam = e.get();
  sim::State st = sim::initial_state(sys.model());
  std::optional<Mark> closed;
  const sim::RunSummary sum = sim::run(sys, *integ, st, s.run, {}, [&](const sim::Progress& p) {
    if (seam && !closed && seam->finished()) closed = mark(sys, *integ, p.t, p.wall_s);
  });
  if (!sum.ok) {
    r.status = "failed";
    r.message = sum.error;
  }
  const Mark end = mark(sys, *integ, sum.simulated_s, sum.wall_s);
  const Mark start{0.0, 0.0, 0, 0, std::vector<double>(r.profile.size(), 0.0)};
  if (!split_at_seams) return {phase(r, variant, start, end)};
  if (!closed) {
    r.status = "partial";
    r.message = "the seams did not close within " + vgd::format_fixed(def.run.duration, 1) + " s";
    return {phase(r, "seams open", start, end)};
  }
  return {phase(r, "seams open", start, *closed), phase(r, "after the last merge", *closed, end)};
}

nlohmann::json to_json(const EffectsRecord& r) {
  auto prof = nlohmann::json::object();
  for (const auto& [name, sec] : r.profile) prof[name] = prof.value(name, 0.0) + sec;
  nlohmann::json j{{"scene", r.scene},         {"variant", r.variant},     {"effects", r.effects},
                   {"particles", r.particles}, {"simulated_s", r.simulated_s}, {"steps", r.steps},
                   {"rhs", r.rhs},             {"wall_s", r.wall_s},       {"ms_per_step", r.ms_per_step()},
                   {"wall_per_simulated_s", r.per_simulated_s()}, {"effect_seconds", prof}, {"status", r.status}};
  if (!r.message.empty()) j["message"] = r.message;
  return j;
}

// `vgd bench effects`: the step cost of a scene against the effects it calls for.
int effects_bench(bool json, bool quick) {
  std::vector<EffectsRecord> records;
  if (!json)
    std::printf("1 thread; %s\n%-13s %-30s %6s %6s %7s %8s %9s %10s  %s\n",
                quick ? "--quick: 0.4 s of flag and drape-sphere" : "each scene's own duration", "scene", "variant",
                "parts", "sim s", "steps", "wall s", "ms/step", "wall/sim-s", "seconds per effect (System::profile)");
  auto add = [&](std::vector<EffectsRecord> rs) {
    for (auto& r : rs) {
      if (!json) {
        std::string prof;
        for (const auto& [effect, sec] : r.profile) prof += effect + " " + vgd::format_fixed(sec, 3) + "  ";
        std::printf("%-13s %-30s %6d %6.2f %7ld %8.3f %9.3f %10.3f  %s%s%s\n", r.scene.c_str(), r.variant.c_str(),
                    r.particles, r.simulated_s, r.steps, r.wall_s, r.ms_per_step(), r.per_simulated_s(), prof.c_str(),
                    r.status == "ok" ? "" : r.status.c_str(), r.message.empty() ? "" : (": " + r.message).c_str());
        std::fflush(stdout);
      }
      records.push_back(std::move(r));
    }
  };
  auto shipped = [&](const char* name) {
    scene::SceneDef def = scene::load_scene(scene::shipped_scene(name));
    def.outputs.clear();
    if (quick && def.name != "sew-cylinder") def.run.duration = 0.4;
    return def;
  };
  // The flag with and without its wind.
  const scene::SceneDef flag = shipped("flag");
  add(effects_run("with wind", flag, false));
  add(effects_run("no wind", [&] { auto d = flag; d.effects.wind.reset(); return d; }(), false));
  // The drape with and without self-collision.
  const scene::SceneDef drape = shipped("drape-sphere");
  add(effects_run("no self-collision", drape, false));
  add(effects_run("self-collision", [&] { auto d = drape; d.effects.self_collision = sim::SelfCollisionDef{}; return d; }(),
                  false));
  // A static body against one moving (the sphere rising into the cloth at
  // 5 cm/s): a rigid motion keeps the distance grid built once, each query
  // moves into the body's frame.
  add(effects_run("moving sphere", [&] { auto d = drape; d.effects.collision->velocity = sim::Vec3(0, 0.05, 0); return d; }(),
                  false));
  // The sewing scene while its seams work and after the last merge (seam
  // effect gone), and without seams at all.
  scene::SceneDef sew = shipped("sew-cylinder");
  sew.run.duration += 1.0;  // a second after the scene's end, for the closed phase
  add(effects_run("seams", sew, true));
  add(effects_run("no seams listed", [&] { auto d = sew; d.effects.seams.reset(); return d; }(), false));
  omp_set_num_threads(std::max(1, omp_get_num_procs()));
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& r : records) list.push_back(to_json(r));
    vgd::cli::print_json(list);
  }
  return vgd::cli::kOk;
}

vgd::cli::Registrar reg{"bench", 90, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("bench", "Measure speed on the shipped scenes");
  sub->require_subcommand(1);
  auto o = std::make_shared<Options>();
  auto* engine = sub->add_subcommand(
      "engine", "The flag for every cloth model x integrator, 1 thread and all cores, and the cost of each effect");
  engine->add_flag("--json", o->json, "Print the records as a JSON list on stdout");
  engine->add_flag("--quick", o->quick, "0.2 s of simulated time instead of 2 s (a smoke test)");
  engine->add_option("--scene", o->scene_file, "Another scene file instead of the shipped flag");
  auto scene_duration = std::make_shared<double>(0.0);
  auto scene_self = std::make_shared<bool>(false);
  auto* effects = sub->add_subcommand(
      "effects", "Step cost against the effects a scene calls for: flag +/- wind, drape +/- self-collision, static/moving sphere, seams open/closed");
  effects->add_flag("--json", o->json, "Print the records as a JSON list on stdout");
  effects->add_flag("--quick", o->quick, "0.4 s of the flag and the drape instead of their full durations");
  auto* accuracy = sub->add_subcommand(
      "accuracy", "Error against CPU time for every integrator on problems with a known answer (CSV + PNG diagrams)");
  accuracy->add_flag("--json", o->json, "Print the records as a JSON list on stdout");
  accuracy->add_flag("--quick", o->quick, "Coarse grids, short runs and fewer steps (well under a minute)");
  auto accuracy_out = std::make_shared<std::string>("accuracy");
  auto accuracy_problems = std::make_shared<std::vector<std::string>>();
  accuracy->add_option("--problems", *accuracy_problems, "Only these problems (default all)")
      ->check(CLI::IsMember({"flag", "hanging", "cantilever", "drape"}))
      ->delimiter(',');
  accuracy->add_option("-o,--output", *accuracy_out, "Folder for accuracy.csv and the work-precision PNGs")
      ->capture_default_str();
  auto* dress = sub->add_subcommand(
      "dress", "The A-line skirt and the T-shirt over it, flat pieces to rest on the size-38 mannequin (about 5 000 "
               "particles), 1 thread and every core, per stage and per effect, against the 10 s target");
  dress->add_flag("--json", o->json, "Print the records as a JSON list on stdout");
  auto dress_spacing = std::make_shared<double>(0.019);
  auto dress_size = std::make_shared<std::string>("38");
  auto dress_limit = std::make_shared<double>(8.0);
  dress->add_option("--spacing", *dress_spacing, "Mesh spacing, m (0.019: about 5 000 particles; the drape's default is 0.015)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  dress->add_option("--size", *dress_size, "Garment and mannequin size")->capture_default_str();
  dress->add_option("--time-limit", *dress_limit, "Simulated seconds at most")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  std::vector<CLI::App*> scene_cmds;
  for (const auto& [name, what] :
       {std::pair{"drape-sphere", "A 71 x 71 cloth dropped on a 4 992-triangle sphere, 2.4 s (data/scenes/drape-sphere.json)"},
        std::pair{"sew-cylinder", "Two 40 x 30 panels sewn into a tube round a cylinder, 2 s (data/scenes/sew-cylinder.json)"}}) {
    auto* c = sub->add_subcommand(name, std::string(what) + "; 1 thread and every core, against Blender's figures");
    c->add_flag("--json", o->json, "Print the records as a JSON list on stdout");
    c->add_option("--duration", *scene_duration, "Simulated seconds instead of the scene's (a smoke test)")
        ->check(CLI::PositiveNumber);
    c->add_flag("--self-collision", *scene_self,
                "Also keep the cloth from passing through itself (against Blender's self-collision figures where known)");
    scene_cmds.push_back(c);
  }
  return vgd::cli::Command{sub, [o, &common, engine, effects, accuracy, accuracy_out, accuracy_problems, scene_cmds,
                                 scene_duration, scene_self, dress, dress_spacing, dress_size, dress_limit]() -> int {
    if (effects->parsed()) return effects_bench(o->json, o->quick);
    if (dress->parsed()) return vgd::cli::bench_dress(*dress_spacing, *dress_size, *dress_limit, o->json);
    if (accuracy->parsed()) return vgd::cli::bench_accuracy(o->quick, o->json, *accuracy_out, *accuracy_problems);
    for (auto* c : scene_cmds)
      if (c->parsed()) return scene_bench(c->get_name(), o->json, *scene_duration, *scene_self);
    if (!engine->parsed()) return vgd::cli::kUsage;
    const auto file = o->scene_file.empty() ? scene::shipped_scene("flag") : std::filesystem::path(o->scene_file);
    scene::SceneDef base = scene::load_scene(file);
    base.run.duration = o->quick ? 0.2 : 2.0;
    base.outputs.clear();
    const double budget = o->quick ? 10.0 : 60.0;
    const int cores = std::max(1, omp_get_num_procs());
    std::vector<int> thread_counts{1};
    if (cores > 1) thread_counts.push_back(cores);

    std::vector<Record> records;
    if (!o->json) {
      std::printf("%s: %s s simulated per run, wall-time budget %s s per run, %d cores\n", file.string().c_str(),
                  vgd::format_fixed(base.run.duration, 1).c_str(), vgd::format_fixed(budget, 0).c_str(), cores);
      std::printf("%-15s %-17s %3s %10s %7s %8s %11s %9s %9s  %s\n", "model", "integrator", "thr", "step s", "steps",
                  "wall s", "p-steps/s", "RHS/sim-s", "Jac/sim-s", "status");
    }
    auto add = [&](Record r) {
      if (!o->json) print_row(r);
      records.push_back(std::move(r));
    };

    // Every model x integrator x thread count.
    for (const auto model : {scene::ClothModel::mass_spring, scene::ClothModel::strain_rosette}) {
      scene::SceneDef def = base;
      for (auto& c : def.cloth) c.model = model;
      for (const auto method : {sim::Method::symplectic_euler, sim::Method::midpoint, sim::Method::rk4,
                                sim::Method::implicit_euler, sim::Method::bdf})
        for (const int t : thread_counts) {
          add(run_one(def, method, t, budget));
        }
    }

    // The cost of each listed effect: the flag with it switched off (1 thread).
    if (!o->json)
      std::printf("\neffects switched off one at a time (%s, %s, 1 thread):\n%-14s %8s %11s  %s\n",
                  scene::to_string(base.cloth.front().model), sim::to_string(base.integrator.settings.method),
                  "variant", "wall s", "p-steps/s", "seconds per effect (System::profile)");
    auto variant = [&](const std::string& name, scene::SceneDef def) {
      Record r = run_one(def, def.integrator.settings.method, 1, budget);
      r.variant = name;
      if (!o->json) {
        std::string prof;
        for (const auto& [effect, sec] : r.profile) prof += effect + " " + vgd::format_fixed(sec, 3) + "  ";
        std::printf("%-14s %8.3f %11.3g  %s%s\n", name.c_str(), r.wall_s, r.particle_steps_per_s(), prof.c_str(),
                    r.status == "ok" ? "" : r.status.c_str());
      }
      records.push_back(std::move(r));
    };
    variant("all effects", base);
    if (base.effects.wind) variant("no wind", [&] { auto d = base; d.effects.wind.reset(); return d; }());
    if (base.effects.viscosity) variant("no viscosity", [&] { auto d = base; d.effects.viscosity.reset(); return d; }());
    if (base.effects.gravity) variant("no gravity", [&] { auto d = base; d.effects.gravity.reset(); return d; }());
    if (base.effects.damping) variant("no damping", [&] { auto d = base; d.effects.damping.reset(); return d; }());
    omp_set_num_threads(cores);

    if (o->json) {
      auto list = nlohmann::json::array();
      for (const auto& r : records) list.push_back(to_json(r));
      vgd::cli::print_json(list);
    }
    return vgd::cli::kOk;
  }};
}};

}  // namespace
