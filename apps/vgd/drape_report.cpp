// Running a drape and reporting it: progress per stage on stderr, the
// outputs written, the summary and the certificate's failures printed
// (vgd drape, vgd dress).
#include "drape_report.hpp"

#include <unistd.h>

#include <cstdio>
#include <memory>

#include "vgd/body/avatar_io.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/obj/obj.hpp"
#include "vgd/io/trj/trj.hpp"

namespace {

std::string fixed(double v, int d) { return vgd::format_fixed(v, d); }

// One line per stage on stderr, redrawn in place on a terminal.
class StageBar {
 public:
  explicit StageBar(bool enabled) : enabled_(enabled), tty_(isatty(2) == 1) {}
  void operator()(const vgd::dress::DrapeStageProgress& p) {
    if (!enabled_) return;
    const bool new_stage = p.stage != stage_;
    if (new_stage && drawn_) std::fprintf(stderr, "\n");
    stage_ = p.stage;
    const double f = p.time_limit > 0 ? std::min(1.0, p.t / p.time_limit) : 0.0;
    const int width = 20, filled = static_cast<int>(width * f);
    std::string line = "[" + std::string(filled, '#') + std::string(width - filled, '.') + "] " + p.stage;
    if (p.stage != "placing") {
      line += "  t " + fixed(p.t, 2) + " s  seams " + std::to_string(p.seams_closed) + "/" +
              std::to_string(p.seam_pairs) +
              (p.seams_waiting > 0 ? " (" + std::to_string(p.seams_waiting) + " seams waiting)" : std::string()) +
              "  KE " + vgd::format_significant(p.kinetic_energy, 3) + " J/particle";
    }
    line += "  wall " + fixed(p.wall_s, 1) + " s";
    const int tenth = static_cast<int>(10 * f);
    if (tty_) {
      std::fprintf(stderr, "\r%s\033[K", line.c_str());
      drawn_ = true;
    } else if (new_stage || tenth != tenth_) {
      std::fprintf(stderr, "%s\n", line.c_str());
    }
    tenth_ = tenth;
    std::fflush(stderr);
  }
  void finish() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  bool enabled_, tty_, drawn_ = false;
  std::string stage_;
  int tenth_ = -1;
};

// Keeps the last frame only (the garment as draped).
class LastFrame : public vgd::sim::FrameSink {
 public:
  void frame(int, double time, const vgd::sim::VecX& positions) override {
    t = time;
    x = positions;
  }
  double t = 0;
  vgd::sim::VecX x;
};

}  // namespace

namespace vgd::cli {

int drape_and_report(const DrapeRun& run, const Common& common) {
  namespace scene = vgd::scene;
  namespace body = vgd::body;
  namespace dress = vgd::dress;
  namespace fs = std::filesystem;
  const scene::SceneDef def = dress::drape_scene(run.options);

  const fs::path out = run.output;
  std::vector<std::unique_ptr<vgd::sim::FrameSink>> owned;
  std::vector<vgd::sim::FrameSink*> sinks;
  auto last = std::make_unique<LastFrame>();
  sinks.push_back(last.get());
  if (run.frames) {
    owned.push_back(std::make_unique<vgd::io::obj::ObjSequenceSink>(out / "frames"));
    sinks.push_back(owned.back().get());
  }
  vgd::io::trj::TrjWriter* trj = nullptr;
  if (!run.trj.empty()) {
    owned.push_back(std::make_unique<vgd::io::trj::TrjWriter>(run.trj));
    trj = static_cast<vgd::io::trj::TrjWriter*>(owned.back().get());
    sinks.push_back(trj);
  }
  StageBar bar(!common.quiet && !run.json);
  // What the build found is said before the run: the body's import notes,
  // a garment too small or too large for it, meshing warnings.
  auto progress = [&](const dress::DrapeStageProgress& p) {
    if (p.scene) {
      if (p.scene->avatar)
        for (const auto& note : p.scene->avatar->notes)
          vgd::cli::say(common, "vgd: " + run.avatar_label + ": " + note);
      vgd::cli::print_diagnostics(p.scene->diagnostics, common);
    }
    bar(p);
  };
  dress::DrapeResult r = dress::run_drape(def, sinks, progress);
  bar.finish();
  if (trj && !trj->written().empty() && trj->written() != trj->path())
    std::fprintf(stderr, "vgd: the run stopped early: its %d frames are in %s; %s is unchanged\n",
                 trj->frames_written(), trj->written().c_str(), run.trj.c_str());

  std::error_code ec;
  fs::create_directories(out, ec);
  const auto& model = r.scene.system->model();
  vgd::write_file_atomic(out / "garment.obj", vgd::io::obj::frame_text(model, r.state.t, r.positions));
  if (r.scene.avatar) body::export_avatar(*r.scene.avatar, out / "avatar.obj");
  const std::string cert = dress::to_json(r.certificate);
  vgd::write_file_atomic(out / "certificate.json", cert);
  const bool pressure = !r.certificate.contact.particle_pressure.empty();
  if (pressure) vgd::write_file_atomic(out / "contact-pressure.json", dress::contact_pressure_json(r.certificate));

  const auto& c = r.certificate;
  if (run.json) {
    if (!run.json_later) std::fputs(cert.c_str(), stdout);
  } else if (!common.quiet) {
    const auto [closed, pairs] = c.seam_totals();
    std::printf("%s: stopped at %s after %s s simulated (%s s wall)\n", run.names.c_str(),
                c.stop_reason.c_str(), fixed(c.simulated_s, 2).c_str(), fixed(c.wall_s, 2).c_str());
    for (const auto& st : c.stages)
      std::printf("  %-9s %7s s wall %7s s simulated\n", st.name.c_str(), fixed(st.wall_s, 2).c_str(),
                  fixed(st.simulated_s, 2).c_str());
    std::string prof;
    for (const auto& [name, sec] : c.effect_seconds) prof += " " + name + " " + fixed(sec, 2) + " s,";
    if (!prof.empty()) prof.pop_back();
    std::printf("  %ld steps, %ld force evaluations, %ld CG iterations; per effect:%s\n", c.steps,
                c.force_evaluations, c.linear_iterations, prof.c_str());
    std::printf(
        "  %d particles, %d triangles; seams %d/%d pairs closed; max penetration %s mm; "
        "%d crossing triangle pairs\n",
        c.particles, c.triangles, closed, pairs, fixed(c.max_penetration * 1000, 2).c_str(),
        c.triangle_intersections);
    std::printf("  outputs in %s: garment.obj, avatar.obj, certificate.json%s%s\n", out.string().c_str(),
                pressure ? ", contact-pressure.json" : "", run.frames ? ", frames/" : "");
    if (!run.trj.empty()) std::printf("  trajectory: %s\n", run.trj.c_str());
    std::fflush(stdout);
  }
  if (c.stop_reason == "error") {
    std::fprintf(stderr, "vgd: error: %s: the drape stopped: %s\n", run.names.c_str(),
                 c.stop_message.c_str());
    return vgd::cli::kFailed;
  }
  if (!common.quiet) {
    for (const auto& f : c.failures())
      std::fprintf(stderr, "vgd: check failed: %s: %s\n", f.kind.c_str(), f.detail.c_str());
    for (const auto& w : c.warnings())
      std::fprintf(stderr, "vgd: warning: %s: %s\n", w.kind.c_str(), w.detail.c_str());
  }
  return c.passed() ? vgd::cli::kOk : vgd::cli::kCheckFailed;
}

scene::AvatarDef avatar_file(const std::string& file, const std::string& unit, const std::string& up,
                             const std::string& facing) {
  scene::AvatarDef a;
  a.kind = scene::AvatarDef::Kind::file;
  a.file = std::filesystem::absolute(file);
  a.unit = unit, a.up = up, a.facing = facing;
  return a;
}

}  // namespace vgd::cli
