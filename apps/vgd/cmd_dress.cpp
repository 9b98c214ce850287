// vgd dress: a pattern file to a draped garment in one command (docs/drape.md,
// "vgd dress").
//
//   vgd dress polo.DXF --size 44 -o out/polo
//   vgd dress garment.xvc --avatar body.glb -o out/
//
// Imports the DXF (half pieces unfolded) or reads the XVC, decides what the
// file does not say (dress::prepare_garment: seams, the pieces to drape, the
// body's size table), says each decision, writes the document it drapes as
// OUT/garment.xvc with each pattern's role and whether it is draped (correct
// it and run vgd dress on it again),
// drapes it as vgd drape does and writes previews in OUT/previews/.
#include <cstdio>

#include "cli.hpp"
#include "drape_report.hpp"
#include "previews.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/dress/certificate.hpp"
#include "vgd/dress/prepare.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/scene/quality.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace cmd_dress {
namespace {

struct Options {
  std::string input, size, body_table, body_size, avatar, output = "out", views = "front,back,three-quarter", trj;
  std::string avatar_unit = "auto", avatar_up = "auto", avatar_facing = "auto";
  double time_limit = 8.0;
  bool previews = true, json = false, between = true, sleeves_first = false, hold = false;
  bool hold_given = false;  // --hold-contacts or --no-hold-contacts on the command line
  std::string model = "mass-spring";
  std::string material, material_id, quality = "standard", preview_size = "768", seams;
  double spacing = 0.0, repulsion_damping = 0.0;
};

vgd::cli::Registrar reg{"dress", 64, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("dress", "A pattern file (DXF or XVC) to a draped garment in one command: seams, "
                                          "pieces, body, drape, certificate, previews");
  auto o = std::make_shared<Options>();
  sub->add_option("PATTERN", o->input, "AAMA/ASTM DXF (Gerber, Lectra, CLO, Valentina, ...) or XVC document")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--size", o->size, "The garment's size (default: the sample size); the mannequin is of this size");
  sub->add_option("--body-table", o->body_table,
                  "Size table of the mannequin (vgd mannequin --list-sizes; default: men's or women's from the "
                  "style's name, else the table holding most of the style's graded sizes, else the table nearest the "
                  "pattern's girth)");
  sub->add_option("--body-size", o->body_size,
                  "The mannequin's size, when it is not the garment's (default: the garment's; a size no table "
                  "has, as Valentina's 'base': the size nearest the pattern's girth)");
  sub->add_option("--avatar", o->avatar, "Body mesh (OBJ, PLY, STL, glTF/GLB, FBX, Collada) instead of the mannequin")
      ->check(CLI::ExistingFile);
  sub->add_option("--unit", o->avatar_unit, "--avatar's unit: auto, m, dm, cm, mm, in")->capture_default_str();
  sub->add_option("--up", o->avatar_up, "--avatar's up axis: auto, x, y, z, -x, -y, -z")->capture_default_str();
  sub->add_option("--facing", o->avatar_facing, "Where --avatar faces once up is +Y: auto, +z, -z, +x, -x")
      ->capture_default_str();
  sub->add_option("-o,--output", o->output, "Output folder (default: out)");
  sub->add_option("--time-limit", o->time_limit, "Simulated seconds at most (default 8)")->check(CLI::PositiveNumber);
  sub->add_option("--views", o->views, "Preview views (vgd render --views)")->capture_default_str();
  sub->add_flag("!--no-previews", o->previews, "Write no previews");
  sub->add_option("--preview-size", o->preview_size, "Preview size in pixels: N or WxH")->capture_default_str();
  sub->add_flag("--hold-contacts,!--no-hold-contacts", o->hold,
                  "Hold cloth touching the body on its surface inside each step once every seam is sewn (vgd drape "
                  "--hold-contacts). Default: off, and on for a second drape when the first failed only caught "
                  "in the crease between an arm and the torso (said; its certificate kept as "
                  "certificate.first.json, its --trj as FILE.first.trj); --no-hold-contacts: never")
      ->each([o](const std::string&) { o->hold_given = true; });
  sub->add_flag("--between-particles,!--no-between-particles", o->between,
                "Keep the body out of the cloth between particles too (default on; vgd drape --between-particles)");
  sub->add_flag("--sleeves-first", o->sleeves_first,
                "Sew each sleeve into a tube round its arm before pulling its cap to the armhole (vgd drape "
                "--sleeves-first)");
  sub->add_option("--repulsion-damping", o->repulsion_damping,
                  "Damp the self-collision's repulsion, as a fraction of critical (vgd drape --repulsion-damping)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--model", o->model, "Cloth model: mass-spring (the default) or strain-rosette (vgd drape --model)")
      ->check(CLI::IsMember({"mass-spring", "strain-rosette"}))
      ->capture_default_str();
  sub->add_option("--seams", o->seams, "Seam file (JSON, docs/xvc.md \"Seam files\": pieces by name as vgd dress "
                                       "names them, stretches by index) sewing the garment instead of vgd's suggestions")
      ->check(CLI::ExistingFile);
  sub->add_option("--material", o->material, "XVC document holding the fabric's MATERIAL (default: the garment's; "
                                             "for legs with none, the shipped cotton-jersey when they are smaller round "
                                             "the hip than the body, for tops and skirts more than 4 cm smaller round "
                                             "the bust or hip, else data/materials/shirting.xvc; a neckband, "
                                             "cuff or one-piece collar shorter than its opening in the shipped "
                                             "cotton-rib unless this is given)")
      ->check(CLI::ExistingFile);
  sub->add_option("--material-id", o->material_id, "MATERIAL id in --material (default: its first)");
  sub->add_option("--quality", o->quality, "Quality preset: preview, standard or precise (vgd drape --quality)")
      ->check(CLI::IsMember({"preview", "standard", "precise"}))
      ->capture_default_str();
  sub->add_option("--spacing", o->spacing, "Mesh spacing, m (default: the document's mesh.spacing, else 0.015)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--trj", o->trj, "Also record every frame as a trajectory (docs/formats/trj.md); written as "
                                   "FILE.partial while the run goes, renamed to FILE at its end");
  sub->add_flag("--json", o->json, "Print the certificate on stdout");
  sub->footer("Writes OUTPUT/garment.xvc (the document draped: the seams vgd added, each pattern's role and "
              "drape=true/false; correct it and run vgd dress on it again), garment.obj, avatar.obj, "
              "certificate.json and previews/<view>.png.\n"
              "Exit codes: 0 draped and passed, 1 bad input or nothing to drape, 3 a check failed.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    namespace fs = std::filesystem;
    const fs::path out = o->output;
    const std::string ext = vgd::to_lower(fs::path(o->input).extension().string());
    vgd::xvc::Document doc = [&] {
      if (ext != ".dxf") return vgd::xvc::load_file(o->input);
      vgd::dxf::ImportOptions io;
      io.unfold_mirrored = true;
      io.sew_on_sew_lines = true;  // pieces written per side are joined by prepare_garment
      const auto imported = vgd::dxf::import_file(o->input, io);
      vgd::cli::print_diagnostics(imported.diagnostics, common);
      const auto& s = imported.summary;
      vgd::cli::say(common, "vgd: " + o->input + ": " + std::to_string(s.pieces) +
                                (s.pieces == 1 ? " piece" : " pieces") + ", sizes " +
                                std::to_string(s.sizes.size()) + " (sample " + s.sample_size + "), " +
                                s.producer);
      for (const auto& note : vgd::dxf::import_notes(imported)) vgd::cli::say(common, "vgd: " + note);
      // Named after the file, so that what is said about it names the file.
      return vgd::xvc::Document(vgd::xvc::Node(vgd::xvc::from_style(imported.style).root()), o->input);
    }();
    vgd::dress::PrepareOptions po;
    po.size = o->size;
    po.body_table = o->body_table;
    po.body_size = o->body_size;
    po.avatar = o->avatar;
    po.seams_file = o->seams;
    po.fabric_given = !o->material.empty();
    const vgd::dress::Preparation prep = vgd::dress::prepare_garment(doc, po);
    for (const auto& d : prep.decisions) vgd::cli::say(common, "vgd: " + d);
    for (const auto& w : prep.warnings) vgd::cli::say(common, "vgd: warning: " + w);
    if (!prep.missing.empty()) {
      std::string list;
      for (const auto& m : prep.missing) list += (list.empty() ? "" : ", ") + m;
      vgd::cli::say(common, "vgd: warning: the garment is draped without " + list +
                                ": what passes below is the rest of it");
    }
    std::error_code ec;
    fs::create_directories(out, ec);
    const fs::path prepared = out / "garment.xvc";
    // A garment.xvc there already (a document corrected after an earlier run)
    // is kept beside the new one, unless it is the input itself.
    if (fs::exists(prepared, ec) && !fs::equivalent(prepared, o->input, ec)) {
      const fs::path kept = out / "garment.previous.xvc";
      fs::rename(prepared, kept, ec);
      if (ec)
        throw vgd::Error(prepared.string(), "",
                         "cannot keep the document already there as " + kept.string() + ": " + ec.message() +
                             "; nothing written");
      vgd::cli::say(common, "vgd: the document already in " + prepared.string() + " is kept as " + kept.string());
    }
    vgd::xvc::save_file(doc, prepared);
    vgd::cli::say(common, "vgd: wrote " + prepared.string() +
                              " (the document draped, each piece's role and whether it is draped in it; correct it "
                              "and run vgd dress " + prepared.string() + " again)");

    vgd::cli::DrapeRun run;
    run.options.garment = fs::absolute(prepared);
    run.options.size = prep.size;
    run.options.pieces = prep.pieces;
    run.options.mannequin_table = prep.body_table;
    run.options.time_limit = o->time_limit;
    run.options.between_particles = o->between;
    run.options.hold_contacts_once_sewn = o->hold;
    run.options.sleeves_first = o->sleeves_first;
    run.options.repulsion_damping = o->repulsion_damping;
    run.options.model = vgd::scene::parse_cloth_model(o->model);
    run.options.material_xvc = o->material;
    run.options.material_id = o->material_id;
    run.options.quality = vgd::scene::parse_quality(o->quality);
    run.options.spacing = o->spacing;
    if (o->avatar.empty() && prep.body_size != prep.size) {
      vgd::scene::AvatarDef a;
      a.kind = vgd::scene::AvatarDef::Kind::mannequin;
      a.size = prep.body_size;
      a.table = prep.body_table;
      run.options.avatar = a;
    }
    if (!o->avatar.empty())
      run.options.avatar = vgd::cli::avatar_file(o->avatar, o->avatar_unit, o->avatar_up, o->avatar_facing);
    run.names = o->input;
    run.avatar_label = o->avatar;
    run.output = out;
    run.json = o->json;
    run.trj = o->trj;
    fs::remove(out / "certificate.first.json", ec);  // an earlier run's
    run.json_later = o->json;  // with --json, the certificate kept is printed once
    int code = vgd::cli::drape_and_report(run, common);
    bool again = false;
    // Failed only caught at an armpit, touching cloth not held and the user
    // not having said: draped again holding it once sewn, said, the first
    // certificate kept beside the second.
    if (code == vgd::cli::kCheckFailed && !o->hold && !o->hold_given) {
      const fs::path cert = out / "certificate.json";
      const auto first = vgd::dress::certificate_from_json(vgd::read_file(cert), cert.string());
      if (const auto at = vgd::dress::caught_at_armpit(first)) {
        const fs::path kept = out / "certificate.first.json";
        std::error_code rec;
        fs::rename(cert, kept, rec);
        if (rec)
          throw vgd::Error(cert.string(), "", "cannot keep it as " + kept.string() + ": " + rec.message());
        vgd::cli::say(common, "vgd: the drape failed only where the cloth is caught in the crease between " + *at +
                                  " (its certificate kept as " + kept.string() +
                                  "); draped again, the cloth touching the body held on it once every seam is "
                                  "sewn (--hold-contacts)");
        if (!run.trj.empty() && fs::exists(run.trj, rec)) {  // its trajectory kept too
          fs::path first_trj = run.trj;
          first_trj.replace_extension(".first" + first_trj.extension().string());
          fs::rename(run.trj, first_trj, rec);
          if (!rec) vgd::cli::say(common, "vgd: its trajectory kept as " + first_trj.string());
        }
        run.options.hold_contacts_once_sewn = true;
        run.json_later = false;
        again = true;
        code = vgd::cli::drape_and_report(run, common);
      }
    }
    if (o->json && !again) std::fputs(vgd::read_file(out / "certificate.json").c_str(), stdout);
    if (code == vgd::cli::kFailed || !o->previews) return code;
    vgd::cli::RenderOptions ro;
    ro.input = out.string();
    ro.output = (out / "previews").string();
    ro.views = o->views;
    ro.size = o->preview_size;
    ro.look = prepared.string();
    ro.list_files = !o->json && !common.quiet;
    const int rendered = vgd::cli::write_previews(ro, common);
    return rendered == vgd::cli::kOk ? code : rendered;
  }};
}};

}  // namespace
}  // namespace cmd_dress
