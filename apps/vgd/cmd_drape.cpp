// vgd drape: sews a garment document and drapes it on a body (docs/drape.md).
//
//   vgd drape garment.xvc --size 38 -o out/          the mannequin of size 38
//   vgd drape garment.xvc --avatar body.glb -o out/  an imported body
//
// Writes into the output folder: garment.obj (the draped garment, one group
// per piece), avatar.obj (the body), certificate.json (why it stopped,
// penetration, seams, strain, contact pressure, per-effect profile,
// kinetic-energy history), and with --frames every frame in frames/.
// Progress per stage (placing, sewing, settling) goes to stderr.
#include <unistd.h>

#include <cstdio>
#include <memory>

#include "cli.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/obj/obj.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/body/avatar_io.hpp"
#include "vgd/dress/drape.hpp"
#include "vgd/scene/quality.hpp"

namespace {

struct Options {
  std::vector<std::string> garments;
  std::string size, avatar, output = "out", material, material_id, table, trj, quality = "standard";
  std::string avatar_unit = "auto", avatar_up = "auto", avatar_facing = "auto";
  std::vector<std::string> pieces;
  double time_limit = 8.0, spacing = 0.0;
  bool self_collision = true, frames = false, json = false;
};

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
              std::to_string(p.seam_pairs) + "  KE " + vgd::format_double(p.kinetic_energy) + " J/particle";
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

vgd::cli::Registrar reg{"drape", 65, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("drape", "Sew a garment document and drape it on a body");
  auto o = std::make_shared<Options>();
  sub->add_option("GARMENT", o->garments,
                  "XVC document with seams (docs/xvc.md); more documents are worn over it, in order (a T-shirt over "
                  "a skirt), each starting 15 mm further out")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--size", o->size, "Garment size to sew, and the mannequin's size (default: the sample size)");
  sub->add_option("--avatar", o->avatar, "Body mesh (OBJ, PLY, STL, glTF/GLB, FBX, Collada) instead of the mannequin")
      ->check(CLI::ExistingFile);
  sub->add_option("--unit", o->avatar_unit, "--avatar's unit: auto (from the file, else the body's height), m, dm, cm, mm, in")
      ->capture_default_str();
  sub->add_option("--up", o->avatar_up, "--avatar's up axis: auto (from the body), x, y, z, -x, -y, -z")
      ->capture_default_str();
  sub->add_option("--facing", o->avatar_facing, "Where --avatar faces once up is +Y: auto (from the feet), +z, -z, +x, -x")
      ->capture_default_str();
  sub->add_option("--pieces", o->pieces, "Sew only these pieces (names or block names; default: every piece)");
  sub->add_option("--size-table", o->table, "Size table of the mannequin (vgd mannequin --list-sizes; default: "
                                           "women's EN 13402, then men's, then ASTM misses)");
  sub->add_option("-o,--output", o->output, "Output folder (default: out)");
  sub->add_option("--material", o->material, "XVC document holding the fabric's MATERIAL (default: the garment's, "
                                             "else data/materials/shirting.xvc)")
      ->check(CLI::ExistingFile);
  sub->add_option("--material-id", o->material_id, "MATERIAL id in --material (default: its first)");
  sub->add_option("--time-limit", o->time_limit, "Simulated seconds at most (default 8)")->check(CLI::PositiveNumber);
  sub->add_option("--quality", o->quality,
                  "Quality preset: preview (no self-collision unless asked), standard (the default: 4 implicit "
                  "steps per frame) or precise (8 steps per frame); measured cost and difference in "
                  "docs/accuracy-vs-time.md")
      ->check(CLI::IsMember({"preview", "standard", "precise"}));
  sub->add_option("--spacing", o->spacing, "Mesh spacing, m (default: the document's mesh.spacing, else 0.015)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--self-collision,!--no-self-collision", o->self_collision,
                "Keep the cloth from passing through itself (default on, off for --quality preview; "
                "--no-self-collision is about 3x faster and may leave cloth crossing cloth)");
  sub->add_flag("--frames", o->frames, "Also write every frame as OBJ into OUTPUT/frames/");
  sub->add_option("--trj", o->trj, "Also record every frame as a trajectory (docs/formats/trj.md); written as "
                                   "FILE.partial while the run goes, renamed to FILE at its end");
  sub->add_flag("--json", o->json, "Print the certificate on stdout");
  sub->footer("Exit codes: 0 draped to rest and every check passed, 1 bad input or the run failed, "
              "3 the drape ended but a check failed (see certificate.json).");
  return vgd::cli::Command{sub, [o, sub, &common]() -> int {
    namespace scene = vgd::scene;
    namespace body = vgd::body;
    namespace dress = vgd::dress;
    namespace fs = std::filesystem;
    dress::DrapeOptions d;
    d.garment = o->garments.front();
    d.over.assign(o->garments.begin() + 1, o->garments.end());
    const std::string garment_names = [&] {
      std::string n;
      for (const auto& g : o->garments) n += (n.empty() ? "" : " + ") + g;
      return n;
    }();
    d.size = o->size;
    d.pieces = o->pieces;
    d.mannequin_table = o->table;
    d.material_xvc = o->material;
    d.material_id = o->material_id;
    d.time_limit = o->time_limit;
    d.spacing = o->spacing;
    d.quality = scene::parse_quality(o->quality);
    // Preview drapes without self-collision unless told otherwise: about 4x
    // faster, cloth may end through cloth (docs/accuracy-vs-time.md).
    const bool told = sub->get_option("--self-collision")->count() > 0;
    d.self_collision = told ? o->self_collision : d.quality != scene::Quality::preview;
    if (!o->avatar.empty()) {
      scene::AvatarDef a;
      a.kind = scene::AvatarDef::Kind::file;
      a.file = fs::absolute(o->avatar);
      a.unit = o->avatar_unit, a.up = o->avatar_up, a.facing = o->avatar_facing;
      d.avatar = a;
    }
    const scene::SceneDef def = dress::drape_scene(d);

    const fs::path out = o->output;
    std::vector<std::unique_ptr<vgd::sim::FrameSink>> owned;
    std::vector<vgd::sim::FrameSink*> sinks;
    auto last = std::make_unique<LastFrame>();
    sinks.push_back(last.get());
    if (o->frames) {
      owned.push_back(std::make_unique<vgd::io::obj::ObjSequenceSink>(out / "frames"));
      sinks.push_back(owned.back().get());
    }
    if (!o->trj.empty()) {
      owned.push_back(std::make_unique<vgd::io::trj::TrjWriter>(o->trj));
      sinks.push_back(owned.back().get());
    }
    StageBar bar(!common.quiet && !o->json);
    // What the build found is said before the run: the body's import notes,
    // a garment too small or too large for it, meshing warnings.
    auto progress = [&](const dress::DrapeStageProgress& p) {
      if (p.scene) {
        if (p.scene->avatar)
          for (const auto& note : p.scene->avatar->notes) vgd::cli::say(common, "vgd: " + o->avatar + ": " + note);
        vgd::cli::print_diagnostics(p.scene->diagnostics, common);
      }
      bar(p);
    };
    dress::DrapeResult r = dress::run_drape(def, sinks, progress);
    bar.finish();

    std::error_code ec;
    fs::create_directories(out, ec);
    const auto& model = r.scene.system->model();
    vgd::write_file_atomic(out / "garment.obj", vgd::io::obj::frame_text(model, r.state.t, r.positions));
    if (r.scene.avatar) body::export_avatar(*r.scene.avatar, out / "avatar.obj");
    const std::string cert = dress::to_json(r.certificate);
    vgd::write_file_atomic(out / "certificate.json", cert);

    const auto& c = r.certificate;
    if (o->json) {
      std::fputs(cert.c_str(), stdout);
    } else if (!common.quiet) {
      int pairs = 0, closed = 0;
      for (const auto& s : c.seams) pairs += s.pairs, closed += s.closed;
      std::printf("%s: stopped at %s after %s s simulated (%s s wall)\n", garment_names.c_str(), c.stop_reason.c_str(),
                  fixed(c.simulated_s, 2).c_str(), fixed(c.wall_s, 2).c_str());
      for (const auto& st : c.stages)
        std::printf("  %-9s %7s s wall %7s s simulated\n", st.name.c_str(), fixed(st.wall_s, 2).c_str(),
                    fixed(st.simulated_s, 2).c_str());
      std::string prof;
      for (const auto& [name, sec] : c.effect_seconds) prof += " " + name + " " + fixed(sec, 2) + " s,";
      if (!prof.empty()) prof.pop_back();
      std::printf("  %ld steps, %ld force evaluations, %ld CG iterations; per effect:%s\n", c.steps,
                  c.force_evaluations, c.linear_iterations, prof.c_str());
      std::printf("  %d particles, %d triangles; seams %d/%d pairs closed; max penetration %s mm; "
                  "%d crossing triangle pairs\n",
                  c.particles, c.triangles, closed, pairs, fixed(c.max_penetration * 1000, 2).c_str(),
                  c.triangle_intersections);
      std::printf("  outputs in %s: garment.obj, avatar.obj, certificate.json%s\n", out.string().c_str(),
                  o->frames ? ", frames/" : "");
      if (!o->trj.empty()) std::printf("  trajectory: %s\n", o->trj.c_str());
      std::fflush(stdout);
    }
    if (c.stop_reason == "error") {
      std::fprintf(stderr, "vgd: error: %s: the drape stopped: %s\n", garment_names.c_str(), c.stop_message.c_str());
      return vgd::cli::kFailed;
    }
    if (!common.quiet) {
      for (const auto& f : c.failures())
        std::fprintf(stderr, "vgd: check failed: %s: %s\n", f.kind.c_str(), f.detail.c_str());
      for (const auto& w : c.warnings()) std::fprintf(stderr, "vgd: warning: %s: %s\n", w.kind.c_str(), w.detail.c_str());
    }
    return c.passed() ? vgd::cli::kOk : vgd::cli::kCheckFailed;
  }};
}};

}  // namespace
