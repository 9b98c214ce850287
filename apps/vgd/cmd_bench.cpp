// vgd bench engine | drape-sphere | sew-cylinder | effects | accuracy | dress:
// option parsing and printing; the measurements are study/bench.hpp and
// study/accuracy.hpp (docs/performance.md, docs/accuracy-vs-time.md).
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/data.hpp"
#include "vgd/scene/json.hpp"
#include "vgd/study/bench.hpp"

namespace vgd::cli {
// cmd_accuracy.cpp
int bench_accuracy(bool quick, bool json, const std::filesystem::path& out_dir, const std::vector<std::string>& problems);
// cmd_bench_dress.cpp
int bench_dress(double spacing, const std::string& size, double time_limit, bool between_particles, bool json,
                int threads);
int bench_server(int clients, int workers, const std::string& job, bool json);
int bench_robustness(const RobustnessArgs& args);
}  // namespace vgd::cli

namespace cmd_bench {
namespace {

namespace scene = vgd::scene;
namespace sim = vgd::sim;
namespace study = vgd::study;

struct Options {
  bool json = false, quick = false;
  std::string scene_file;
};

nlohmann::json to_json(const study::EngineRecord& r) {
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

void print_row(const study::EngineRecord& r) {
  auto rate = [&](long n) { return r.implicit() && r.simulated_s > 0 ? vgd::format_fixed(n / r.simulated_s, 0) : "-"; };
  std::printf("%-15s %-17s %3d %10.3g %7ld %8.3f %11.3g %9s %9s  %s%s%s\n", r.model.c_str(), r.integrator.c_str(),
              r.threads, r.step_s, r.steps, r.wall_s, r.particle_steps_per_s(), rate(r.rhs).c_str(),
              rate(r.jacobians).c_str(), r.status.c_str(), r.message.empty() ? "" : ": ",
              r.message.substr(0, 90).c_str());
  std::fflush(stdout);
}

nlohmann::json to_json(const study::SceneRecord& r) {
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
                   {"adapt_threads", r.adapt_threads},
                   {"frames_on_fewer_threads", r.frames_on_fewer_threads},
                   {"status", r.status}};
  if (!r.message.empty()) j["message"] = r.message;
  return j;
}

// `vgd bench drape-sphere` / `sew-cylinder`: 1 thread, then every core with
// the threads adapted to the machine's load and (thr "2f") fixed; with
// --threads N, N threads only (adapted, and fixed when N > 1).
int scene_bench(const std::string& name, bool json, double duration, bool self_collision, int threads) {
  std::vector<study::SceneRecord> records;
  if (!json)
    std::printf("%-13s %3s %9s %9s %7s %8s %12s %12s %8s %9s %7s %9s  %s\n", "scene", "thr", "particles", "body tris",
                "sim s", "wall s", "wall/sim-s", "Blender", "speedup", "pen. mm", "seams", "crossings", "status");
  std::vector<std::pair<int, bool>> runs;  // threads, adapted
  for (const int t : study::thread_counts(threads)) {
    runs.emplace_back(t, true);
    if (t > 1) runs.emplace_back(t, false);
  }
  for (const auto& [t, adapt] : runs) {
    study::SceneRecord r = study::run_scene(name, t, duration, self_collision, adapt);
    if (!json) {
      // No Blender figure for this scene (sew-cylinder with self-collision): a dash, not 0.
      const bool known = r.blender_s > 0 && r.per_simulated_s() > 0;
      const std::string blender = known ? vgd::format_fixed(r.blender_s, 1) : "-";
      const std::string speedup = known ? vgd::format_fixed(r.blender_s / r.per_simulated_s(), 1) + "x" : "-";
      std::printf("%-13s %3s %9d %9d %7.2f %8.2f %12.3f %12s %8s %9.3f %7s %9d  %s%s%s\n",
                  (r.scene + (self_collision ? "+self" : "")).c_str(),
                  (std::to_string(r.threads) + (r.adapt_threads || r.threads == 1 ? "" : "f")).c_str(),
                  r.particles, r.body_triangles, r.simulated_s, r.wall_s, r.per_simulated_s(), blender.c_str(),
                  speedup.c_str(), r.max_penetration * 1000,
                  r.seam_pairs ? (std::to_string(r.seams_closed) + "/" + std::to_string(r.seam_pairs)).c_str() : "-",
                  r.crossings, r.status.c_str(), r.message.empty() ? "" : ": ", r.message.substr(0, 80).c_str());
      std::fflush(stdout);
    }
    records.push_back(std::move(r));
  }
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& r : records) list.push_back(to_json(r));
    vgd::cli::print_json(list);
  }
  return vgd::cli::kOk;
}

nlohmann::json to_json(const study::EffectsRecord& r) {
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
  if (!json)
    std::printf("1 thread; %s\n%-13s %-30s %6s %6s %7s %8s %9s %10s  %s\n",
                quick ? "--quick: 0.4 s of flag and drape-sphere" : "each scene's own duration", "scene", "variant",
                "parts", "sim s", "steps", "wall s", "ms/step", "wall/sim-s", "seconds per effect (System::profile)");
  const auto records = study::effects_study(quick, [&](const study::EffectsRecord& r) {
    if (json) return;
    std::string prof;
    for (const auto& [effect, sec] : r.profile) prof += effect + " " + vgd::format_fixed(sec, 3) + "  ";
    std::printf("%-13s %-30s %6d %6.2f %7ld %8.3f %9.3f %10.3f  %s%s%s\n", r.scene.c_str(), r.variant.c_str(),
                r.particles, r.simulated_s, r.steps, r.wall_s, r.ms_per_step(), r.per_simulated_s(), prof.c_str(),
                r.status == "ok" ? "" : r.status.c_str(), r.message.empty() ? "" : (": " + r.message).c_str());
    std::fflush(stdout);
  });
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
               "particles), 1 thread and every core (only --threads N when given), per stage and per effect, against the "
               "10 s target");
  dress->add_flag("--json", o->json, "Print the records as a JSON list on stdout");
  auto dress_spacing = std::make_shared<double>(0.019);
  auto dress_size = std::make_shared<std::string>("38");
  auto dress_limit = std::make_shared<double>(8.0);
  dress->add_option("--spacing", *dress_spacing, "Mesh spacing, m (0.019: about 5 000 particles; the drape's default is 0.015)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  dress->add_option("--size", *dress_size, "Garment and mannequin size")->capture_default_str();
  auto dress_between = std::make_shared<bool>(true);
  dress->add_flag("--between-particles,!--no-between-particles", *dress_between,
                  "Keep the body out of the cloth between particles (the drape's default) or not");
  dress->add_option("--time-limit", *dress_limit, "Simulated seconds at most")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  auto* robust = sub->add_subcommand(
      "robustness", "The T-shirt and the A-line skirt draped over a sweep of mesh spacings (1.2-2.5 cm), sizes "
                    "(34-42), fabrics, cloth models and 1 um jitters of the start, one thread: clean runs, failure "
                    "classes and how far jittered runs end apart (hours; --quick: 8 runs, a few minutes)");
  robust->add_flag("--json", o->json, "Print the records as a JSON list on stdout");
  robust->add_flag("--quick", o->quick, "The T-shirt and the skirt at 1.5 and 1.9 cm, size 38, one jitter");
  auto ra = std::make_shared<vgd::cli::RobustnessArgs>();
  robust->add_option("--time-limit", ra->time_limit, "Simulated seconds at most per run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  robust->add_flag("--between-particles,!--no-between-particles", ra->between_particles,
                   "Drape with vgd drape --between-particles (the default) or --no-between-particles");
  robust->add_flag("--sleeves-first", ra->sleeves_first, "Drape with vgd drape --sleeves-first");
  robust->add_option("--garments", ra->garments, "Only these garment documents (default: data/garments/t-shirt.xvc and a-line-skirt.xvc)")
      ->delimiter(',');
  robust->add_option("--spacings", ra->spacings, "Only these mesh spacings, m")->delimiter(',')->check(CLI::PositiveNumber);
  robust->add_option("--sizes", ra->sizes, "Only these sizes")->delimiter(',');
  robust->add_option("--fabrics", ra->fabrics, "Only these files of data/materials ('own': the garment's)")->delimiter(',');
  robust->add_option("--models", ra->models, "Only these cloth models")
      ->delimiter(',')
      ->check(CLI::IsMember({"mass-spring", "strain-rosette"}));
  robust->add_option("--jitters", ra->jitters, "Jittered runs per case (default 2; --quick 1)")->check(CLI::NonNegativeNumber);
  auto* server = sub->add_subcommand(
      "server", "vgd-server under load: N clients at once submit a small job each (a scene or a drape) and read all its frames, then "
                "the same jobs unwatched; jobs/min, first-frame latency, frames lost or corrupted, overhead, memory");
  server->add_flag("--json", o->json, "Print the figures as JSON on stdout");
  auto server_clients = std::make_shared<int>(50);
  auto server_workers = std::make_shared<int>(2);
  auto server_job = std::make_shared<std::string>("scene");
  server->add_option("--clients", *server_clients, "Clients at once, one job each")->check(CLI::Range(1, 1000))
      ->capture_default_str();
  server->add_option("--workers", *server_workers, "The server's workers")->check(CLI::Range(1, 64))->capture_default_str();
  server->add_option("--job", *server_job,
                     "scene (data/scenes/cloth-on-sphere.json: 20 x 20 cloth on a sphere, 0.5 s), drape (the shipped "
                     "skirt, preview quality, 5 cm mesh, 0.5 s) or a self-contained scene file")
      ->capture_default_str();
  std::vector<CLI::App*> scene_cmds;
  for (const auto& [name, what] :
       {std::pair{"drape-sphere", "A 71 x 71 cloth dropped on a 4 992-triangle sphere, 2.4 s (data/scenes/drape-sphere.json)"},
        std::pair{"sew-cylinder", "Two 40 x 30 panels sewn into a tube round a cylinder, 2 s (data/scenes/sew-cylinder.json)"}}) {
    auto* c = sub->add_subcommand(name, std::string(what) +
                                            "; 1 thread and every core (adapted to the load, and fixed; only --threads N "
                                            "when given), against Blender's figures");
    c->add_flag("--json", o->json, "Print the records as a JSON list on stdout");
    c->add_option("--duration", *scene_duration, "Simulated seconds instead of the scene's (a smoke test)")
        ->check(CLI::PositiveNumber);
    c->add_flag("--self-collision", *scene_self,
                "Also keep the cloth from passing through itself (against Blender's self-collision figures where known)");
    scene_cmds.push_back(c);
  }
  return vgd::cli::Command{sub, [o, &common, engine, effects, accuracy, accuracy_out, accuracy_problems, scene_cmds,
                                 scene_duration, scene_self, dress, dress_spacing, dress_size, dress_limit, dress_between, robust,
                                 ra, server, server_clients, server_workers, server_job]() -> int {
    if (server->parsed()) return vgd::cli::bench_server(*server_clients, *server_workers, *server_job, o->json);
    if (robust->parsed()) {
      ra->quick = o->quick;
      ra->json = o->json;
      return vgd::cli::bench_robustness(*ra);
    }
    if (effects->parsed()) return effects_bench(o->json, o->quick);
    if (dress->parsed()) return vgd::cli::bench_dress(*dress_spacing, *dress_size, *dress_limit, *dress_between, o->json,
                                                     common.threads);
    if (accuracy->parsed()) return vgd::cli::bench_accuracy(o->quick, o->json, *accuracy_out, *accuracy_problems);
    for (auto* c : scene_cmds)
      if (c->parsed()) return scene_bench(c->get_name(), o->json, *scene_duration, *scene_self, common.threads);
    if (!engine->parsed()) return vgd::cli::kUsage;
    const auto file = o->scene_file.empty() ? vgd::shipped_scene("flag") : std::filesystem::path(o->scene_file);
    scene::SceneDef base = scene::load_scene(file);
    base.run.duration = o->quick ? 0.2 : 2.0;
    base.outputs.clear();
    const double budget = o->quick ? 10.0 : 60.0;
    const int cores = std::max(1, omp_get_num_procs());
    if (!o->json) {
      std::printf("%s: %s s simulated per run, wall-time budget %s s per run, %d cores\n", file.string().c_str(),
                  vgd::format_fixed(base.run.duration, 1).c_str(), vgd::format_fixed(budget, 0).c_str(), cores);
      std::printf("%-15s %-17s %3s %10s %7s %8s %11s %9s %9s  %s\n", "model", "integrator", "thr", "step s", "steps",
                  "wall s", "p-steps/s", "RHS/sim-s", "Jac/sim-s", "status");
    }
    bool variants = false;
    const auto records = vgd::study::engine_study(base, budget, [&](const vgd::study::EngineRecord& r) {
      if (o->json) return;
      if (r.variant.empty()) return print_row(r);
      // The cost of each listed effect: the scene with it switched off (1 thread).
      if (!variants)
        std::printf("\neffects switched off one at a time (%s, %s, 1 thread):\n%-14s %8s %11s  %s\n",
                    scene::to_string(base.cloth.front().model), sim::to_string(base.integrator.settings.method),
                    "variant", "wall s", "p-steps/s", "seconds per effect (System::profile)");
      variants = true;
      std::string prof;
      for (const auto& [effect, sec] : r.profile) prof += effect + " " + vgd::format_fixed(sec, 3) + "  ";
      std::printf("%-14s %8.3f %11.3g  %s%s\n", r.variant.c_str(), r.wall_s, r.particle_steps_per_s(), prof.c_str(),
                  r.status == "ok" ? "" : r.status.c_str());
      std::fflush(stdout);
    });

    if (o->json) {
      auto list = nlohmann::json::array();
      for (const auto& r : records) list.push_back(to_json(r));
      vgd::cli::print_json(list);
    }
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_bench
