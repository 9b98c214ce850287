// vgd simulate: runs a scene file (docs/scene.md) and writes its frames.
//
// Progress goes to stderr (redrawn in place on a terminal, one line per ~10 %
// otherwise); the summary (or --json) to stdout. A run the engine stops early
// (a blow-up, a step refused as unstable) exits 1 with the engine's message;
// the frames written until then are kept.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/obj/obj.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/dress/dress.hpp"
#include "vgd/scene/build.hpp"
#include "vgd/scene/json.hpp"
#include "vgd/scene/quality.hpp"
#include "vgd/scene/units.hpp"

namespace cmd_simulate {
namespace {

struct Options {
  std::string scene, output, quality, integrator, step, duration, trj;
  bool profile = false, json = false;
};

// "4ms", "0.004", "2 s" -> seconds; a bare number is in seconds. nullopt when
// the text is not a non-negative time.
std::optional<double> seconds(const std::string& text) {
  if (const auto v = vgd::parse_double(text)) return *v >= 0 ? std::optional<double>(*v) : std::nullopt;
  const auto q = vgd::scene::parse_quantity(text);
  if (!q || q->dimension != vgd::scene::dim::time || !(q->value >= 0.0)) return std::nullopt;
  return q->value;
}

// A CLI11 check for seconds().
std::string time_text(const std::string& text) {
  return seconds(text) ? "" : "expected a time in seconds, e.g. 0.004, 4ms or 2s (got '" + text + "')";
}

std::string fixed(double v, int d) { return vgd::format_fixed(v, d); }

// Progress on stderr: in place on a terminal, else a line per ~10 %.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), tty_(isatty(2) == 1) {}
  void operator()(const vgd::sim::Progress& p) {
    if (!enabled_ || p.frames == 0) return;
    const int decile = 10 * p.frame / p.frames;
    if (!tty_ && decile == last_decile_ && p.frame != p.frames) return;
    last_decile_ = decile;
    const int width = 24, filled = width * p.frame / p.frames;
    std::string bar(filled, '#');
    bar += std::string(width - filled, '.');
    const std::string line = "[" + bar + "] frame " + std::to_string(p.frame) + "/" + std::to_string(p.frames) +
                             "  t " + fixed(p.t, 2) + "/" + fixed(p.duration, 2) + " s  wall " + fixed(p.wall_s, 1) +
                             " s  ETA " + fixed(p.eta_s, 1) + " s";
    if (tty_) {
      std::fprintf(stderr, "\r%s\033[K", line.c_str());
      drawn_ = true;
    } else {
      std::fprintf(stderr, "%s\n", line.c_str());
    }
    std::fflush(stderr);
  }
  void finish() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  bool enabled_, tty_;
  bool drawn_ = false;
  int last_decile_ = -1;
};

vgd::cli::Registrar reg{"simulate", 60, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("simulate", "Run a scene file: cloth, effects, integrator; write its frames");
  auto o = std::make_shared<Options>();
  sub->add_option("SCENE", o->scene, "Scene file (JSON, docs/scene.md)")->required();
  sub->add_option("-o,--output", o->output, "Write frames as OBJ files (frame_0000.obj, ...) into this folder, "
                                            "instead of the scene's OBJ output");
  sub->add_option("--quality", o->quality,
                  "Quality preset, replacing the scene's integrator: preview, standard or precise "
                  "(docs/accuracy-vs-time.md; --integrator and --step then override it)")
      ->check(CLI::IsMember({"preview", "standard", "precise"}));
  sub->add_option("--integrator", o->integrator, "Integrator: euler, midpoint, rk4, implicit-euler, bdf")
      ->check(CLI::IsMember({"euler", "symplectic-euler", "midpoint", "rk4", "implicit-euler", "bdf", "cvode"}));
  sub->add_option("--step", o->step, "Integration step, s (e.g. 0.004 or 4ms); replaces the scene's")
      ->check(time_text);
  sub->add_option("--duration", o->duration, "Simulated time, s (e.g. 2 or 500ms); replaces the scene's")
      ->check(time_text);
  sub->add_option("--trj", o->trj, "Also record every frame as a trajectory (docs/formats/trj.md); written as "
                                   "FILE.partial while the run goes, renamed to FILE at its end; a run that stops "
                                   "early leaves FILE as it was and its frames in NAME.failed.trj");
  sub->add_flag("--profile", o->profile, "Print calls and time per effect (System::profile)");
  sub->add_flag("--json", o->json, "Print the summary (and profile) as JSON on stdout");
  sub->footer("Exit codes: 0 the run finished, 1 the scene is bad or the run stopped early (frames so far are kept).");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    namespace scene = vgd::scene;
    namespace body = vgd::body;
    namespace dress = vgd::dress;
    scene::SceneDef def = scene::load_scene(o->scene);

    // Command-line overrides, then the checks again.
    if (!o->quality.empty())
      def.integrator = scene::quality_integrator(scene::parse_quality(o->quality), scene::has_contact(def.effects));
    if (!o->integrator.empty()) def.integrator.settings.method = vgd::sim::parse_method(o->integrator);
    if (!o->step.empty()) {
      def.integrator.settings.step = *seconds(o->step);
      def.integrator.iterations_per_frame = 0;
    }
    if (!o->duration.empty()) def.run.duration = *seconds(o->duration);
    if (!o->output.empty()) {
      std::erase_if(def.outputs, [](const auto& out) { return out.kind == scene::OutputDef::Kind::obj; });
      def.outputs.push_back({scene::OutputDef::Kind::obj, o->output});
    }
    scene::Scene s = dress::build(def);  // garments dressed on the body, then the scene
    vgd::cli::print_diagnostics(s.diagnostics, common);

    std::unique_ptr<vgd::sim::Integrator> integrator;
    try {
      integrator = vgd::sim::make_integrator(s.integrator);
    } catch (const vgd::sim::SimulationError& e) {
      throw vgd::Error(o->scene, "integrator.method", e.what());
    }

    // Sinks, as the scene (or -o) asks.
    std::vector<std::unique_ptr<vgd::sim::FrameSink>> owned;
    std::vector<vgd::sim::FrameSink*> sinks;
    std::vector<std::string> folders;
    for (const auto& out : s.outputs) {
      if (out.kind == scene::OutputDef::Kind::obj) {
        owned.push_back(std::make_unique<vgd::io::obj::ObjSequenceSink>(out.directory));
        folders.push_back(out.directory.string());
      } else {
        owned.push_back(std::make_unique<vgd::sim::MemorySink>());
      }
      sinks.push_back(owned.back().get());
    }
    vgd::io::trj::TrjWriter* trj = nullptr;
    if (!o->trj.empty()) {
      owned.push_back(std::make_unique<vgd::io::trj::TrjWriter>(o->trj));
      trj = static_cast<vgd::io::trj::TrjWriter*>(owned.back().get());
      sinks.push_back(trj);
      folders.push_back(o->trj);
    }

    // Run.
    auto& sys = *s.system;
    const int particles = sys.model().num_particles();
    vgd::sim::State state = vgd::sim::initial_state(sys.model());
    ProgressBar bar(!common.quiet && !o->json);
    const auto r = vgd::sim::run(sys, *integrator, state, s.run, sinks, std::ref(bar));
    bar.finish();
    if (trj && !trj->written().empty() && trj->written() != trj->path()) {
      folders.back() = trj->written().string();
      std::fprintf(stderr, "vgd: the run stopped early: its %d frames are in %s; %s is unchanged\n",
                   trj->frames_written(), trj->written().c_str(), o->trj.c_str());
    }

    const double pps = r.wall_s > 0 ? static_cast<double>(particles) * r.stats.steps / r.wall_s : 0.0;
    const std::string where = folders.empty() ? "" : " in " + folders.front();
    if (o->json) {
      auto profile = nlohmann::json::array();
      for (const auto& p : sys.profile())
        profile.push_back({{"effect", p.name},
                           {"force_calls", p.force_calls},
                           {"jacobian_calls", p.jacobian_calls},
                           {"after_step_calls", p.after_step_calls},
                           {"seconds", p.seconds}});
      nlohmann::json j{{"scene", o->scene},
                       {"name", s.name},
                       {"ok", r.ok},
                       {"integrator", vgd::sim::to_string(s.integrator.method)},
                       {"step_s", integrator->step() > 0 ? integrator->step() : s.integrator.step},
                       {"particles", particles},
                       {"triangles", sys.model().triangles.size()},
                       {"frames", r.frames},
                       {"steps", r.stats.steps},
                       {"rhs_evaluations", r.stats.rhs_evaluations},
                       {"jacobian_evaluations", r.stats.jacobian_evaluations},
                       {"linear_iterations", r.stats.linear_iterations},
                       {"convergence_failures", r.stats.convergence_failures},
                       {"simulated_s", r.simulated_s},
                       {"wall_s", r.wall_s},
                       {"particle_steps_per_s", pps},
                       {"outputs", folders},
                       {"profile", profile}};
      if (!r.ok) j["error"] = r.error;
      vgd::cli::print_json(j);
    } else {
      std::printf("%s: %d frames (%s s simulated), %ld steps of %.4g s (%s), %ld RHS and %ld Jacobian evaluations\n",
                  s.name.empty() ? o->scene.c_str() : s.name.c_str(), r.frames, fixed(r.simulated_s, 3).c_str(),
                  r.stats.steps, r.stats.last_step > 0 ? r.stats.last_step : s.integrator.step,
                  vgd::sim::to_string(s.integrator.method), r.stats.rhs_evaluations, r.stats.jacobian_evaluations);
      std::printf("%d particles, %zu triangles; wall %s s, %.3g particle-steps/s%s\n", particles,
                  sys.model().triangles.size(), fixed(r.wall_s, 3).c_str(), pps,
                  folders.empty() ? "" : ("; frames" + where).c_str());
      if (o->profile) {
        double total = 0;
        for (const auto& p : sys.profile()) total += p.seconds;
        std::printf("%-16s %12s %12s %12s %10s %6s\n", "effect", "force calls", "jacobians", "after-step", "seconds",
                    "share");
        for (const auto& p : sys.profile())
          std::printf("%-16s %12ld %12ld %12ld %10.4f %5.1f%%\n", p.name.c_str(), p.force_calls, p.jacobian_calls,
                      p.after_step_calls, p.seconds, total > 0 ? 100.0 * p.seconds / total : 0.0);
      }
      std::fflush(stdout);
    }
    if (!r.ok) {
      std::fprintf(stderr, "vgd: error: %s: the run stopped after %d frames: %s\n", o->scene.c_str(), r.frames,
                   r.error.c_str());
      if (!folders.empty() && r.frames > 0)
        std::fprintf(stderr, "vgd: the %d frames written%s are complete\n", r.frames, where.c_str());
      return vgd::cli::kFailed;
    }
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_simulate
