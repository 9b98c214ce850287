// vgd export: a draped garment for viewers and the tools designers use next
// (docs/vrml.md).
//
//   vgd export skirt.trj --vrml static -o skirt.wrl [--avatar body.obj] [--document skirt.xvc]
//   vgd export skirt.trj --vrml animated --decimate 4 --precision 3 -o skirt-anim.wrl
//   vgd export skirt.trj --vrml live -o skirt-live.wrl         the viewer simulates it
//   vgd export skirt.trj --gltf skirt.glb --obj skirt.obj      the final drape
//   vgd export a.trj b.trj --web catalogue/ [--live-flag]      index.html, a page per garment, X_ITE
//   vgd export --live-flag -o flag.wrl.gz                       the seed's flag, 5 kB
//
// INPUT is a trajectory (.trj: every frame, material coordinates, merges) or,
// without one, a drape's output folder (DIR/garment.obj and DIR/avatar.obj)
// or a garment .obj: one frame, material coordinates approximated.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/io/wvt/wvt.hpp"
#include "vgd/io/vrml/gltf.hpp"
#include "vgd/io/vrml/looks.hpp"
#include "vgd/io/vrml/sources.hpp"
#include "vgd/io/vrml/vrml.hpp"
#include "vgd/io/vrml/web.hpp"
#include "vgd/body/avatar_io.hpp"
#include "vgd/xvc/io.hpp"

namespace cmd_export {
namespace {

namespace fs = std::filesystem;
namespace vrml = vgd::io::vrml;

struct Options {
  std::vector<std::string> inputs, documents, avatars;
  std::string vrml, output, gltf, obj, web, x_ite, title = "vgd garment catalogue";
  int decimate = 1, precision = -1, frame = -1;
  double speed = 1.0, pin_band = 0.01;
  std::vector<double> wind;
  bool live_flag = false, no_body = false, no_colliders = false, json = false;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string size_text(std::size_t bytes) {
  if (bytes < 10 * 1024) return std::to_string(bytes) + " B";
  if (bytes < 10 * 1024 * 1024) return vgd::format_fixed(bytes / 1024.0, 1) + " kB";
  return vgd::format_fixed(bytes / (1024.0 * 1024.0), 1) + " MB";
}

// The garment of one input: a .trj or .wvt, a drape folder or an .obj.
vrml::Garment load_garment(const std::string& input, vgd::Diagnostics& diag, fs::path& folder_avatar) {
  const fs::path p(input);
  if (fs::is_directory(p)) {
    if (!fs::is_regular_file(p / "garment.obj"))
      throw vgd::Error(input, "", "not a drape folder: no garment.obj (vgd drape writes garment.obj and avatar.obj)");
    if (fs::is_regular_file(p / "avatar.obj")) folder_avatar = p / "avatar.obj";
    diag.info(input, "", "a drape folder: the final frame only, material coordinates approximated (a .trj has them)");
    auto g = vrml::garment_from_obj(p / "garment.obj");
    g.name = p.filename().empty() ? p.parent_path().filename().string() : p.filename().string();
    return g;
  }
  if (p.extension() == ".obj") {
    diag.info(input, "", "an OBJ: one frame, material coordinates approximated (a .trj has them)");
    return vrml::garment_from_obj(p);
  }
  if (vgd::io::wvt::is_wvt_file(p)) {
    diag.info(input, "", "a compressed trajectory (.wvt): positions within the error bound it was written with");
    auto g = vrml::garment_from_trajectory(vgd::io::wvt::read_wvt(p), input);
    g.name = p.stem().string();
    return g;
  }
  vgd::io::trj::TrjReader reader(p);
  diag.append(reader.warnings());
  auto g = vrml::garment_from_trajectory(reader.read_all(), input);
  g.name = p.stem().string();
  return g;
}

// The body: an avatar file in vgd's frame (metres, +Y up), as vgd drape writes it.
vrml::Body load_body(const fs::path& file) {
  vgd::body::AvatarImportOptions o;
  o.unit = "m", o.up = "y", o.facing = "+z", o.recentre = false, o.segments = false, o.human = false;
  const auto avatar = vgd::body::import_avatar(file, o);
  vrml::Body b;
  b.name = "avatar";
  for (const auto& v : avatar.surface.vertices) b.vertices.push_back({v.x(), v.y(), v.z()});
  b.triangles = avatar.surface.triangles;
  return b;
}

// Looks from the document; texture images are copied beside the outputs.
void apply_document(vrml::Garment& g, const fs::path& doc_file, const std::vector<fs::path>& out_dirs,
                    vgd::Diagnostics& diag) {
  const auto doc = vgd::xvc::load_file(doc_file);
  g.looks = vrml::looks_from_xvc(doc, g.cloth.pieces, &diag);
  for (auto& look : g.looks) {
    if (look.texture.empty()) continue;
    const fs::path image = doc_file.parent_path() / look.texture;
    if (!fs::is_regular_file(image)) {
      diag.warn(doc_file.string(), look.source, "texture image " + image.string() + " not found: the colour is used");
      look.texture.clear();
      continue;
    }
    for (const auto& dir : out_dirs) {
      std::error_code ec;
      fs::create_directories(dir, ec);
      fs::copy_file(image, dir / image.filename(), fs::copy_options::update_existing, ec);
      if (ec) throw vgd::Error(image.string(), "", "cannot copy the texture beside the output: " + ec.message());
    }
    look.texture = image.filename().string();
  }
}

// The live flavour's settings for a garment (not the seed's flag): a light
// breeze, the top row pinned, the body as colliders, a step small enough for
// light fabric (the script raises masses where it must to stay stable).
vrml::LiveOptions garment_live_options(const vrml::Garment& g, const Options& o) {
  vrml::LiveOptions l;
  l.particle_mass = 0.0;  // density × area
  l.density = 0.2;
  l.wind = {0.0, 0.0, -4.0};
  l.wind_coefficient = 2.4;  // ~ air: ½ ρ v² over v at 4 m/s
  l.wind_turbulence = 0.5;
  l.viscosity = 0.0;
  l.viscosity_rate = 0.5;
  l.step = 0.002;
  l.max_steps = 12;
  l.max_strain = 0.03;  // woven fabric barely stretches
  if (o.wind.size() == 3) l.wind = {o.wind[0], o.wind[1], o.wind[2]};
  l.pinned = vrml::top_particles(g, o.pin_band);
  if (!o.no_colliders) l.colliders = vrml::body_colliders(g);
  if (o.precision >= 0) l.precision = o.precision;
  l.body = !o.no_body;
  return l;
}

std::string vrml_text(const vrml::Garment& g, const std::string& flavour, const Options& o) {
  if (flavour == "animated") {
    vrml::AnimatedOptions a;
    a.decimate = o.decimate, a.speed = o.speed, a.body = !o.no_body;
    if (o.precision >= 0) a.precision = o.precision;
    return vrml::animated_vrml(g, a);
  }
  if (flavour == "live") return vrml::live_vrml(g, garment_live_options(g, o), o.frame);
  vrml::StaticOptions s;
  s.frame = o.frame, s.body = !o.no_body;
  if (o.precision >= 0) s.precision = o.precision;
  return vrml::static_vrml(g, s);
}

vrml::FlagOptions flag_options(const Options& o) {
  vrml::FlagOptions f;
  if (o.wind.size() == 3) f.live.wind = {o.wind[0], o.wind[1], o.wind[2]};
  return f;
}

vgd::cli::Registrar reg{"export", 72, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("export", "Export a draped garment: VRML (static, animated, live), glTF, OBJ, a web page");
  auto o = std::make_shared<Options>();
  sub->add_option("INPUT", o->inputs,
                  "Trajectory (.trj, or .wvt: positions within its error bound), or a drape folder (garment.obj, avatar.obj), or a garment .obj; several with --web");
  sub->add_option("--vrml", o->vrml, "VRML97 flavour: static (final drape), animated (every frame), live (the viewer "
                                     "simulates it); default static with -o or --web")
      ->check(CLI::IsMember({"static", "animated", "live"}));
  sub->add_option("-o,--output", o->output, "The .wrl file to write (gzip-compressed when it ends in .wrl.gz or .wrz)");
  sub->add_option("--gltf", o->gltf, "Also write the final drape as binary glTF 2.0 (.glb)");
  sub->add_option("--obj", o->obj, "Also write the final drape as OBJ (+ .mtl beside it)");
  sub->add_option("--web", o->web, "Write a web catalogue into this folder: index.html, a page per garment (X_ITE), "
                                   "the .wrl, .glb and .obj files, and X_ITE itself (x_ite/)");
  sub->add_option("--x-ite", o->x_ite, "X_ITE's dist/ folder to copy into the catalogue (default: the one "
                                       ".ci/install-deps installed, " + vrml::default_x_ite_dir().string() + ")");
  sub->add_option("--title", o->title, "Title of the catalogue's index page");
  sub->add_option("--document", o->documents, "XVC document with the garment's colours and textures (COLORRGBA, "
                                              "TEXTURE, ASSOCIATION); one for all inputs or one per input");
  sub->add_option("--avatar", o->avatars, "Body mesh in vgd's frame (m, +Y up; e.g. the drape's avatar.obj); one for "
                                          "all inputs or one per input (default: a drape folder's avatar.obj)");
  sub->add_flag("--no-avatar", o->no_body, "Leave the body out");
  sub->add_option("--decimate", o->decimate, "Animated: keep every Nth frame (and the last)")->check(CLI::Range(1, 100000));
  sub->add_option("--precision", o->precision,
                  "Decimals of coordinates in metres (default: 4 static and live = 0.1 mm, 3 animated = 1 mm)")
      ->check(CLI::Range(0, 9));
  sub->add_option("--speed", o->speed, "Animated: playback speed (1 = real time)")->check(CLI::PositiveNumber);
  sub->add_option("--frame", o->frame, "Static, live, glTF, OBJ: frame to write (default: the last)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--wind", o->wind, "Live: wind velocity x y z, m/s (garments 0 0 -4; the flag 10 10 -100)")
      ->expected(3);
  sub->add_option("--pin-band", o->pin_band, "Live: particles within this height of the top are pinned, m (0.01)")
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("--no-colliders", o->no_colliders, "Live: no ellipsoids standing in for the body");
  sub->add_flag("--live-flag", o->live_flag, "The seed's flag (a live VRML of a few kB): to -o without INPUT, or "
                                             "added to the --web catalogue");
  sub->add_flag("--json", o->json, "Print what was written (files, bytes, seconds) as JSON on stdout");
  sub->footer("A .trj keeps every frame, the pieces' material coordinates and the seams' merges; a drape folder has "
              "the final frame only. Exit codes: 0 ok, 1 bad input or a failed write, 2 usage. docs/vrml.md");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    auto usage = [](const std::string& why) {
      std::fprintf(stderr, "vgd export: %s (see vgd export --help)\n", why.c_str());
      return vgd::cli::kUsage;
    };
    const bool to_file = !o->output.empty();
    const bool any_output = to_file || !o->gltf.empty() || !o->obj.empty() || !o->web.empty();
    if (!any_output) return usage("nothing to write: give -o, --gltf, --obj or --web");
    if (o->inputs.empty() && !o->live_flag) return usage("give a trajectory or --live-flag");
    if (o->inputs.size() > 1 && (to_file || !o->gltf.empty() || !o->obj.empty()))
      return usage("several inputs go to a --web catalogue only");
    if (o->live_flag && o->inputs.empty() && (!o->gltf.empty() || !o->obj.empty()))
      return usage("the flag is a live VRML only (no glTF or OBJ)");
    for (const auto* list : {&o->documents, &o->avatars})
      if (list->size() > 1 && list->size() != o->inputs.size())
        return usage("--document and --avatar: give one for all inputs or one per input");
    const std::string flavour = o->vrml.empty() ? "static" : o->vrml;

    nlohmann::json written = nlohmann::json::array();
    auto note = [&](const fs::path& file, std::size_t bytes, double seconds, const std::string& what) {
      written.push_back({{"file", file.string()}, {"bytes", bytes}, {"seconds", seconds}, {"what", what}});
      if (!o->json)
        vgd::cli::say(common, "vgd: wrote " + file.string() + " (" + what + ", " + size_text(bytes) + ", " +
                                  vgd::format_fixed(seconds, 3) + " s)");
    };
    // Every file atomically; gzip-compressed when its name ends in .gz or .wrz.
    auto write = [&](const fs::path& file, const std::string& bytes, double seconds, const std::string& what) {
      const auto t0 = std::chrono::steady_clock::now();
      const bool gz = file.extension() == ".gz" || file.extension() == ".wrz";
      const std::string data = gz ? vrml::gzip(bytes) : bytes;
      vgd::write_file_atomic(file, data);
      note(file, data.size(), seconds + seconds_since(t0), gz ? what + ", gzip" : what);
    };

    // The seed's flag alone.
    if (o->inputs.empty() && to_file) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::string text = vrml::live_flag_vrml(flag_options(*o));
      write(o->output, text, seconds_since(t0), "live flag");
    }

    std::vector<vrml::WebEntry> entries;
    const fs::path web(o->web);
    vgd::Diagnostics diag;
    for (std::size_t k = 0; k < o->inputs.size(); ++k) {
      const std::string& input = o->inputs[k];
      const auto t_load = std::chrono::steady_clock::now();
      fs::path folder_avatar;
      vrml::Garment g = load_garment(input, diag, folder_avatar);
      const fs::path avatar = !o->avatars.empty() ? fs::path(o->avatars[o->avatars.size() == 1 ? 0 : k]) : folder_avatar;
      if (!o->no_body && !avatar.empty()) g.body = load_body(avatar);
      std::vector<fs::path> out_dirs;
      if (to_file) out_dirs.push_back(fs::path(o->output).parent_path());
      if (!o->web.empty()) out_dirs.push_back(web);
      if (!o->documents.empty()) apply_document(g, o->documents[o->documents.size() == 1 ? 0 : k], out_dirs, diag);
      if (!o->json)
        vgd::cli::say(common, "vgd: " + input + ": " + std::to_string(g.cloth.num_pieces()) + " pieces, " +
                                  std::to_string(g.cloth.num_particles()) + " particles, " +
                                  std::to_string(g.cloth.triangles.size()) + " triangles, " +
                                  std::to_string(g.frames.count()) + " frames (read in " +
                                  vgd::format_fixed(seconds_since(t_load), 2) + " s)");

      vrml::DrapeExportOptions drape;
      drape.frame = o->frame, drape.body = !o->no_body;
      auto timed = [](auto&& make) {
        const auto t0 = std::chrono::steady_clock::now();
        std::string s = make();
        return std::pair{std::move(s), seconds_since(t0)};
      };
      if (to_file) {
        auto [text, s] = timed([&] { return vrml_text(g, flavour, *o); });
        write(o->output, text, s, flavour + " VRML");
      }
      if (!o->gltf.empty()) {
        auto [bytes, s] = timed([&] { return vrml::glb_bytes(g, drape); });
        write(o->gltf, bytes, s, "glTF binary");
      }
      if (!o->obj.empty()) {
        const fs::path obj(o->obj), mtl = fs::path(o->obj).replace_extension(".mtl");
        auto [text, s] = timed([&] { return vrml::obj_text(g, mtl.filename().string(), drape); });
        write(obj, text, s, "OBJ");
        write(mtl, vrml::mtl_text(g), 0.0, "OBJ materials");
      }
      if (!o->web.empty()) {
        // The page's VRML, and the drape as glTF and OBJ to download.
        vrml::WebEntry e;
        e.name = vrml::page_stem(g.name);
        for (const auto& other : entries)
          if (other.name == e.name) e.name += "-" + std::to_string(k + 1);
        e.title = g.name;
        e.wrl = e.name + ".wrl";
        auto [text, s] = timed([&] { return vrml_text(g, flavour, *o); });
        write(web / e.wrl, text, s, flavour + " VRML");
        auto [glb, sg] = timed([&] { return vrml::glb_bytes(g, drape); });
        write(web / (e.name + ".glb"), glb, sg, "glTF binary");
        write(web / (e.name + ".obj"), vrml::obj_text(g, e.name + ".mtl", drape), 0.0, "OBJ");
        write(web / (e.name + ".mtl"), vrml::mtl_text(g), 0.0, "OBJ materials");
        e.downloads = {{"glTF (.glb)", e.name + ".glb"}, {"OBJ", e.name + ".obj"}};
        const auto mesh = vrml::output_mesh(g.cloth, true);
        e.facts = {{"pieces", std::to_string(g.cloth.num_pieces())},
                   {"triangles", std::to_string(mesh.face_count())},
                   {"particles", std::to_string(mesh.vertex_particle.size())},
                   {"frames", std::to_string(g.frames.count())},
                   {"VRML", flavour + ", " + size_text(text.size())}};
        entries.push_back(std::move(e));
      }
    }
    if (!o->web.empty()) {
      if (o->live_flag) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::string text = vrml::live_flag_vrml(flag_options(*o));
        write(web / "flag.wrl", text, seconds_since(t0), "live flag");
        entries.push_back({"flag", "The seed's flag (live: simulated in the browser)", "flag.wrl", {},
                           {{"particles", "30 x 30"}, {"VRML", "live, " + size_text(text.size())}}});
      }
      const fs::path x_ite = o->x_ite.empty() ? vrml::default_x_ite_dir() : fs::path(o->x_ite);
      const auto t0 = std::chrono::steady_clock::now();
      vrml::write_web_catalogue(web, entries, x_ite);
      note(web / "index.html", 0, seconds_since(t0), std::to_string(entries.size()) + " pages and x_ite/");
    }
    vgd::cli::print_diagnostics(diag, common);
    if (o->json) vgd::cli::print_json({{"written", written}, {"diagnostics", vgd::cli::to_json(diag)}});
    return diag.has_errors() ? vgd::cli::kFailed : vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_export
