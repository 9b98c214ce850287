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

#include "cli.hpp"
#include "drape_report.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/dress/drape.hpp"
#include "vgd/scene/quality.hpp"

namespace cmd_drape {
namespace {

struct Options {
  std::vector<std::string> garments;
  std::string size, avatar, output = "out", material, material_id, table, trj, quality = "standard",
      model = "mass-spring";
  std::string avatar_unit = "auto", avatar_up = "auto", avatar_facing = "auto";
  std::vector<std::string> pieces;
  double time_limit = 8.0, spacing = 0.0, repulsion_damping = 0.0;
  bool self_collision = true, frames = false, json = false, between = true, offset_contact = false, sleeves_first = false,
       hold = false;
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
                  "Quality preset: preview (stops at 10x the rest threshold: sooner, less settled), standard "
                  "(the default: 4 implicit steps per frame) or precise (8 steps per frame); measured cost and "
                  "difference in docs/accuracy-vs-time.md")
      ->check(CLI::IsMember({"preview", "standard", "precise"}));
  sub->add_option("--spacing", o->spacing, "Mesh spacing, m (default: the document's mesh.spacing, else 0.015)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--model", o->model,
                  "Cloth model: mass-spring (the default) or strain-rosette (seed 002's orthotropic membrane with "
                  "bending, about 4x slower; docs/fabric-model.md, docs/drape.md)")
      ->check(CLI::IsMember({"mass-spring", "strain-rosette"}))
      ->capture_default_str();
  sub->add_flag("--self-collision,!--no-self-collision", o->self_collision,
                "Keep the cloth from passing through itself (default on; --no-self-collision is about 3x "
                "faster and leaves cloth crossing cloth)");
  sub->add_option("--repulsion-damping", o->repulsion_damping,
                  "Damp the self-collision's repulsion, as a fraction of critical (default 0: none; 1 took a flap "
                  "standing against other cloth to rest: docs/collisions.md, \"Damped repulsion\")")
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("--hold-contacts,!--no-hold-contacts", o->hold,
                "Hold cloth touching the body on its surface inside each step once every seam is sewn (default off: "
                "the corrections after each step keep it out; on, an armpit pressed into the crease between arm and "
                "torso comes to rest, docs/collisions.md)");
  sub->add_flag("--between-particles,!--no-between-particles", o->between,
                "Keep the body out of the cloth between particles too (default on: sharp parts such as toes, "
                "heels, a crotch under a seam junction; docs/collisions.md)");
  sub->add_flag("--sleeves-first", o->sleeves_first,
                "Sew each sleeve into a tube round its arm before pulling its cap to the armhole: for bodies with the "
                "arms swung forward, where an open sleeve slides off its arm (docs/seams.md, \"Order\"). Off by "
                "default: it changes which drapes pass elsewhere");
  sub->add_flag("--offset-contact", o->offset_contact,
                "Offset contact instead of the body collision and self-collision: no cloth through the body or "
                "through cloth at the end of any step. Experimental: slow, and it does not yet sew the shipped "
                "garments to rest (docs/collisions.md, \"Offset contact\")");
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
    d.self_collision = o->self_collision;
    d.repulsion_damping = o->repulsion_damping;
    d.between_particles = o->between;
    d.hold_contacts_once_sewn = o->hold;
    d.offset_contact = o->offset_contact;
    d.sleeves_first = o->sleeves_first;
    d.model = scene::parse_cloth_model(o->model);
    if (!o->avatar.empty()) {
      d.avatar = vgd::cli::avatar_file(o->avatar, o->avatar_unit, o->avatar_up, o->avatar_facing);
    }
    vgd::cli::DrapeRun run;
    run.options = std::move(d);
    run.names = garment_names;
    run.avatar_label = o->avatar;
    run.output = o->output;
    run.frames = o->frames;
    run.trj = o->trj;
    run.json = o->json;
    return vgd::cli::drape_and_report(run, common);
  }};
}};

}  // namespace
}  // namespace cmd_drape
