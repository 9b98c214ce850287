// vgd render: headless previews of a draped garment on its body (docs/render.md).
//
//   vgd render out/drape/ --views front,three-quarter --size 1024x1024 -o previews/
//   vgd render garment.obj --avatar body.obj -o previews/
//   vgd render skirt.trj --frame 40 --avatar body.obj -o previews/
//
// INPUT is a drape folder (as `vgd drape -o DIR` writes it: garment.obj with
// one group per piece, avatar.obj), a garment OBJ, or a trajectory (.trj, one
// frame: the last unless --frame says). Writes OUTPUT/<view>.png
// for each view and prints what it wrote. OpenGL 3.3 core in an OSMesa
// off-screen context; no display needed.
//
// Pieces take their looks (colour, texture) from the garment's XVC document:
// --look FILE, or the document a drape folder's certificate.json names.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "previews.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/obj/obj.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/io/vrml/looks.hpp"
#include "vgd/render/fit_map.hpp"
#include "vgd/render/looks.hpp"
#include "vgd/render/offscreen.hpp"
#include "vgd/dress/drape.hpp"
#include "vgd/scene/material.hpp"
#include "vgd/body/avatar_io.hpp"
#include "vgd/xvc/io.hpp"

namespace {

namespace fs = std::filesystem;
namespace render = vgd::render;

using Options = vgd::cli::RenderOptions;

// "1024x1024", "800x600" or "512" (square).
std::pair<int, int> parse_size(const std::string& text) {
  const auto parts = vgd::split(vgd::to_lower(text), 'x');
  const auto w = parts.empty() ? std::nullopt : vgd::parse_int(parts[0]);
  const auto h = parts.size() == 2 ? vgd::parse_int(parts[1]) : parts.size() == 1 ? w : std::nullopt;
  if (!w || !h || *w < 16 || *h < 16 || *w > 4096 || *h > 4096)
    throw CLI::ValidationError("--size", "'" + text + "' is not WIDTHxHEIGHT with 16–4096 pixels each");
  return {static_cast<int>(*w), static_cast<int>(*h)};
}

render::Colour parse_colour_option(const std::string& name, const std::string& text) {
  const auto c = render::parse_colour(text);
  if (!c) throw CLI::ValidationError(name, "'" + text + "' is not a colour (#rrggbb, #rgb or a name such as red)");
  return *c;
}

// One render mesh per group of an OBJ (its own vertices only), with the
// file's texture coordinates (`vt`: metres of pattern in vgd's garment.obj)
// when every face of the group has them. With `sources`: per mesh, each
// render vertex's vertex in the file, and the file's vertex count.
struct ObjSources {
  std::vector<std::vector<int>> vertex;  // per mesh and render vertex
  std::size_t file_vertices = 0;
};
std::vector<render::Mesh> meshes_of_obj(const fs::path& file, render::MeshKind kind, ObjSources* sources = nullptr) {
  const auto obj = vgd::io::obj::read_obj(file);
  if (sources) sources->file_vertices = obj.vertices.size();
  const int n_groups = std::max<int>(1, static_cast<int>(obj.groups.size()));
  auto group_of = [&](std::size_t f) { return static_cast<std::size_t>(std::clamp(obj.face_group[f], 0, n_groups - 1)); };
  std::vector<render::Mesh> meshes(static_cast<std::size_t>(n_groups));
  std::vector<char> textured(meshes.size(), 1);
  for (std::size_t f = 0; f < obj.faces.size(); ++f)
    if (obj.face_texcoords[f][0] < 0) textured[group_of(f)] = 0;
  // (vertex, texture coordinate) -> render vertex: a vertex with two texture
  // coordinates (a cut in texture space) becomes two render vertices.
  std::vector<std::map<std::pair<int, int>, int>> remap(meshes.size());
  std::vector<std::vector<int>> source(meshes.size());  // per render vertex: its vertex in the file
  for (std::size_t f = 0; f < obj.faces.size(); ++f) {
    const std::size_t g = group_of(f);
    auto& m = meshes[g];
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const int v = obj.faces[f][k], t = textured[g] ? obj.face_texcoords[f][k] : -1;
      const auto [it, fresh] = remap[g].try_emplace({v, t}, static_cast<int>(m.positions.size()));
      if (fresh) {
        const auto& p = obj.vertices[static_cast<std::size_t>(v)];
        m.positions.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
        source[g].push_back(v);
        if (t >= 0) {
          const auto& c = obj.texcoords[static_cast<std::size_t>(t)];
          m.uv.push_back({static_cast<float>(c[0]), static_cast<float>(c[1])});
        }
      }
      tri[k] = it->second;
    }
    m.triangles.push_back(tri);
  }
  for (std::size_t g = 0; g < meshes.size(); ++g) {
    meshes[g].kind = kind;
    meshes[g].name = g < obj.groups.size() ? obj.groups[g] : file.stem().string();
  }
  std::vector<render::Mesh> kept;
  for (std::size_t g = 0; g < meshes.size(); ++g) {
    if (meshes[g].triangles.empty()) continue;
    kept.push_back(std::move(meshes[g]));
    if (sources) sources->vertex.push_back(std::move(source[g]));
  }
  return kept;
}

// One render mesh per piece of one frame of a trajectory (-1: the last).
std::vector<render::Mesh> meshes_of_trj(const fs::path& file, int frame, const vgd::cli::Common& common) {
  const vgd::io::trj::TrjReader reader(file);
  vgd::cli::print_diagnostics(reader.warnings(), common);
  const int n = reader.frame_count();
  if (n == 0) throw vgd::Error(file.string(), "", "the trajectory holds no frame");
  if (frame < -1 || frame >= n)
    throw vgd::Error(file.string(), "frame " + std::to_string(frame),
                     "no such frame (the trajectory holds frames 0 to " + std::to_string(n - 1) + ")");
  const int f = frame < 0 ? n - 1 : frame;
  const auto x = reader.positions(f);
  const auto& topo = reader.topology();
  const bool pieces = !topo.pieces.empty() && topo.triangle_piece.size() == topo.triangles.size();
  const bool uv = topo.uv.size() == static_cast<std::size_t>(topo.num_particles);
  std::vector<render::Mesh> meshes(pieces ? topo.pieces.size() : 1);
  std::vector<std::vector<int>> remap(meshes.size(), std::vector<int>(static_cast<std::size_t>(topo.num_particles), -1));
  for (std::size_t t = 0; t < topo.triangles.size(); ++t) {
    const std::size_t g = pieces ? static_cast<std::size_t>(topo.triangle_piece[t]) : 0;
    auto& m = meshes[g];
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const int p = topo.triangles[t][k];
      int& r = remap[g][static_cast<std::size_t>(p)];
      if (r < 0) {
        r = static_cast<int>(m.positions.size());
        m.positions.push_back({x[3 * p], x[3 * p + 1], x[3 * p + 2]});
        if (uv) m.uv.push_back({static_cast<float>(topo.uv[p][0]), static_cast<float>(topo.uv[p][1])});
      }
      tri[k] = r;
    }
    m.triangles.push_back(tri);
  }
  for (std::size_t g = 0; g < meshes.size(); ++g) meshes[g].name = pieces ? topo.pieces[g] : file.stem().string();
  std::erase_if(meshes, [](const render::Mesh& m) { return m.triangles.empty(); });
  vgd::cli::say(common, "vgd: " + file.string() + ": frame " + std::to_string(f) + " of " + std::to_string(n) +
                            " (t = " + vgd::format_fixed(reader.time(f), 3) + " s)");
  return meshes;
}

// An avatar file through the same import as `vgd drape --avatar` (normalised to
// vgd's frame), so a garment draped on it lands where it was draped.
// The importer's decisions and notes are printed, as vgd drape prints them.
render::Mesh body_mesh(const fs::path& file, const Options& o, const vgd::cli::Common& common) {
  vgd::body::AvatarImportOptions io;
  io.unit = o.unit, io.up = o.up, io.facing = o.facing;
  const auto avatar = vgd::body::import_avatar(file, io);
  for (const auto& n : avatar.notes) vgd::cli::say(common, "vgd: " + file.string() + ": " + n);
  render::Mesh m;
  m.name = "body";
  m.kind = render::MeshKind::body;
  for (const auto& v : avatar.surface.vertices)
    m.positions.push_back({static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
  m.triangles = avatar.surface.triangles;
  return m;
}

// The garment document the pieces take their looks from: --look, else the
// one a drape folder's certificate.json names (inputs.garment), when the drape
// had a single garment and its document can still be read (else a warning,
// and flat colours). The path is as the drape was given it: tried as it is,
// then relative to the folder.
std::optional<vgd::xvc::Document> look_document(const Options& o, const fs::path& folder, vgd::Diagnostics& diags) {
  if (!o.look.empty()) return vgd::xvc::load_file(o.look);
  if (folder.empty()) return std::nullopt;
  const fs::path cert = folder / "certificate.json";
  std::error_code ec;
  if (!fs::exists(cert, ec)) return std::nullopt;
  const auto j = nlohmann::json::parse(vgd::read_file(cert), nullptr, /*allow_exceptions=*/false);
  const auto inputs = j.is_object() ? j.find("inputs") : j.end();
  if (inputs == j.end() || !inputs->is_object() || !inputs->contains("garment") || !(*inputs)["garment"].is_string())
    return std::nullopt;
  if (inputs->contains("garment_2")) {
    diags.info(cert.string(), "", "several garments: flat colours (--look FILE applies one document's looks)");
    return std::nullopt;
  }
  const fs::path named = (*inputs)["garment"].get<std::string>();
  fs::path file = named;
  if (!fs::exists(file, ec) && named.is_relative() && fs::exists(folder / named, ec)) file = folder / named;
  try {
    return vgd::xvc::load_file(file);
  } catch (const vgd::Error& e) {
    diags.warn(cert.string(), "", "the garment document cannot be read (" + std::string(e.what()) +
                                      "): flat colours; --look FILE gives it");
    return std::nullopt;
  }
}

// The fabrics of a stress map: the garment document (--look, else the one the
// folder's certificate names) for the pieces' own MATERIALs, and the
// garment's fabric: the certificate's `material` input (what the drape used),
// else as a drape would choose it (dress::garment_fabric).
struct StressFabrics {
  std::optional<vgd::xvc::Document> doc;
  vgd::scene::MaterialDef garment;
};

StressFabrics stress_fabrics(const Options& o, const fs::path& folder, const vgd::cli::Common& common) {
  StressFabrics out;
  vgd::Diagnostics diags;
  out.doc = look_document(o, folder, diags);
  vgd::cli::print_diagnostics(diags, common);
  std::string source;
  std::error_code ec;
  if (!folder.empty() && fs::exists(folder / "certificate.json", ec)) {
    const auto j = nlohmann::json::parse(vgd::read_file(folder / "certificate.json"), nullptr, false);
    if (j.is_object() && j.contains("inputs") && j["inputs"].is_object() && j["inputs"].contains("material") &&
        j["inputs"]["material"].is_string()) {
      const std::string m = j["inputs"]["material"].get<std::string>();
      const auto hash = m.rfind('#');
      if (hash != std::string::npos) {
        out.garment = vgd::scene::load_xvc_material(m.substr(0, hash), m.substr(hash + 1));
        source = m;
      }
    }
  }
  if (source.empty()) {
    const vgd::xvc::Document none;
    const vgd::xvc::Document& doc = out.doc ? *out.doc : none;
    const fs::path file = out.doc ? fs::path(out.doc->name()) : fs::path();
    const auto src = vgd::dress::garment_fabric(doc, file);
    source = src.xvc.string() + "#" + src.id;
    out.garment = vgd::dress::garment_fabric_of(doc, file);
  }
  vgd::cli::say(common, "vgd: stress from the fabrics' sheet moduli: the garment's " + source +
                            (out.doc ? ", each piece's own from " + out.doc->name() : std::string()));
  return out;
}

// Each piece's look in the document (io::vrml::looks_from_xvc, as the VRML
// and glTF exports read them): the colour the document gives it (none: the
// default fabric colour stays), its texture file relative to the document.
std::vector<render::Look> looks_of(const vgd::xvc::Document& doc, const std::vector<render::Mesh*>& pieces,
                                   vgd::Diagnostics& diags) {
  std::vector<std::string> names;
  for (const auto* m : pieces) names.push_back(m->name);
  const fs::path dir = fs::path(doc.name()).parent_path();
  std::vector<render::Look> out;
  for (const auto& l : vgd::io::vrml::looks_from_xvc(doc, names, &diags)) {
    render::Look k;
    if (l.source.rfind("default", 0) != 0)  // looks_from_xvc marks a look the document did not colour "default"
      k.colour = render::Colour{static_cast<float>(l.colour.r), static_cast<float>(l.colour.g), static_cast<float>(l.colour.b)};
    if (!l.texture.empty()) k.texture = fs::path(l.texture).is_absolute() || dir.empty() ? fs::path(l.texture) : dir / l.texture;
    k.repeat_m = {l.repeat_u, l.repeat_v};
    k.rotation_deg = l.rotation_deg;
    out.push_back(std::move(k));
  }
  return out;
}

// --map-range, else the map's default.
render::FitScale fit_scale(const Options& o) {
  render::FitScale scale = render::default_scale(*render::parse_fit_map(o.map));
  if (o.map_range.empty()) return scale;
  const auto parts = vgd::split(o.map_range, ',');
  const auto lo = parts.size() == 2 ? vgd::parse_double(parts[0]) : std::nullopt;
  const auto hi = parts.size() == 2 ? vgd::parse_double(parts[1]) : std::nullopt;
  if (!lo || !hi || !(*hi > *lo))
    throw CLI::ValidationError("--map-range", "'" + o.map_range + "' is not LO,HI with LO < HI (e.g. 0,40)");
  return {*lo, *hi};
}

// The scene: the garment's pieces and the body, coloured (and textured).
render::Scene load_scene(const Options& o, const vgd::cli::Common& common) {
  render::Scene scene;
  const fs::path input = o.input;
  std::error_code ec;
  fs::path garment = input, avatar_obj, folder;
  if (fs::is_directory(input, ec)) {
    folder = input;
    garment = input / "garment.obj";
    if (!fs::exists(garment, ec))
      throw vgd::Error(input.string(), "", "not a drape folder: garment.obj is missing (vgd drape GARMENT -o DIR writes it)");
    if (fs::exists(input / "avatar.obj", ec)) avatar_obj = input / "avatar.obj";
  } else if (!fs::exists(input, ec)) {
    throw vgd::Error(input.string(), "", "file not found");
  } else if (const auto ext = vgd::to_lower(input.extension().string()); ext != ".obj" && ext != ".trj") {
    if (ext == ".wvt")
      throw vgd::Error(input.string(), "", "a compressed trajectory (.wvt): vgd decompress turns it into a .trj, "
                                           "which vgd render reads");
    throw vgd::Error(input.string(), "", "vgd render reads a drape folder, a garment .obj or a trajectory .trj");
  }
  const bool trj = vgd::to_lower(input.extension().string()) == ".trj";
  if (!trj && o.frame != -1) throw vgd::Error(input.string(), "", "--frame applies to a trajectory (.trj) only");
  const render::Colour fabric = o.colour.empty() ? render::kFabric : parse_colour_option("--colour", o.colour);
  int index = 0;
  ObjSources sources;  // per piece and render vertex: its vertex of garment.obj
  auto pieces = trj ? meshes_of_trj(input, o.frame, common) : meshes_of_obj(garment, render::MeshKind::garment, &sources);
  std::vector<render::Mesh*> garment_meshes;
  for (auto& m : pieces) {
    m.kind = render::MeshKind::garment;
    m.colour = o.piece_colours ? render::piece_colour(index) : fabric;
    ++index;
    scene.meshes.push_back(std::move(m));
  }
  for (auto& m : scene.meshes) garment_meshes.push_back(&m);
  // Colours asked for on the command line win over the document's looks.
  if (o.colour.empty() && !o.piece_colours && o.map.empty()) {
    vgd::Diagnostics diags;
    if (const auto doc = look_document(o, folder, diags)) {
      render::apply_looks(garment_meshes, looks_of(*doc, garment_meshes, diags), !o.no_texture, diags);
      vgd::cli::say(common, "vgd: looks from " + doc->name());
    }
    vgd::cli::print_diagnostics(diags, common);
  }
  if (!o.map.empty()) {
    // A fit map: each piece coloured by its strain; the figures said per piece.
    const auto map = *render::parse_fit_map(o.map);
    const render::FitScale scale = fit_scale(o);
    // The pressure map's values: the drape's contact-pressure.json beside
    // garment.obj, one per vertex of it (Pa; drawn in kPa).
    std::vector<double> pressure;
    if (map == render::FitMap::pressure) {
      if (trj)
        throw vgd::Error(input.string(), "", "a contact-pressure map needs a drape folder (its contact-pressure.json), "
                                             "not a trajectory");
      const fs::path file = garment.parent_path() / "contact-pressure.json";
      if (!fs::exists(file, ec))
        throw vgd::Error(file.string(), "", "not found: a contact-pressure map needs the drape's contact-pressure.json "
                                            "(vgd drape and vgd dress write it beside garment.obj)");
      pressure = vgd::dress::contact_pressure_from_json(vgd::read_file(file), file.string());
      const std::size_t obj_vertices = sources.file_vertices;
      if (pressure.size() != obj_vertices)
        throw vgd::Error(file.string(), "values", "holds " + std::to_string(pressure.size()) + " pressures for the " +
                                                      std::to_string(obj_vertices) + " vertices of " + garment.string() +
                                                      ": not the same drape");
    }
    // The stress map's fabrics: each piece's own, else the garment's.
    std::optional<StressFabrics> fabrics;
    if (map == render::FitMap::stress) fabrics = stress_fabrics(o, folder, common);
    for (std::size_t k = 0; k < garment_meshes.size(); ++k) {
      render::Mesh* m = garment_meshes[k];
      std::optional<render::Membrane> membrane;
      std::string fabric_name;
      if (fabrics) {
        const vgd::scene::MaterialDef f =
            fabrics->doc ? vgd::scene::piece_fabric(*fabrics->doc, m->name, fabrics->garment, fabrics->doc->name())
                         : fabrics->garment;
        const auto ortho = vgd::scene::orthotropic_of(f);
        membrane = render::Membrane{ortho.E_warp, ortho.E_weft, ortho.G, ortho.nu_warp_weft};
        fabric_name = " (" + f.name + ")";
      }
      std::vector<double> values;
      if (map == render::FitMap::pressure)
        for (int v : sources.vertex[k]) values.push_back(pressure[static_cast<std::size_t>(v)] / 1000.0);
      else
        values = render::fit_values(*m, map, membrane ? &*membrane : nullptr);
      render::colour_by(*m, values, scale);
      std::vector<double> sorted = values;
      std::sort(sorted.begin(), sorted.end());
      if (sorted.empty()) continue;
      const auto at = [&](double q) { return sorted[static_cast<std::size_t>(std::lround(q * (sorted.size() - 1)))]; };
      vgd::cli::say(common, "vgd: " + render::title_of(map) + " of " + (m->name.empty() ? "the garment" : m->name) +
                                fabric_name + ": p50 " + vgd::format_fixed(at(0.5), 1) + ", p95 " + vgd::format_fixed(at(0.95), 1) +
                                ", max " + vgd::format_fixed(sorted.back(), 1) + " (per vertex)");
    }
  }
  const render::Colour body = o.body_colour.empty() ? render::kBody : parse_colour_option("--body-colour", o.body_colour);
  if (!o.avatar.empty()) {
    scene.meshes.push_back(body_mesh(o.avatar, o, common));
  } else if (!avatar_obj.empty()) {
    for (auto& m : meshes_of_obj(avatar_obj, render::MeshKind::body)) scene.meshes.push_back(std::move(m));
  }
  for (auto& m : scene.meshes)
    if (m.kind == render::MeshKind::body) m.colour = body;
  return scene;
}

vgd::cli::Registrar reg{"render", 75, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("render", "Headless previews (PNG) of a draped garment on its body");
  auto o = std::make_shared<Options>();
  sub->add_option("INPUT", o->input,
                  "A drape folder (garment.obj, avatar.obj: vgd drape -o DIR), a garment .obj or a trajectory .trj")
      ->required();
  sub->add_option("--frame", o->frame, "Frame of a .trj to draw, from 0 (default: the last)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--avatar", o->avatar, "Body mesh (OBJ, PLY, STL, glTF/GLB, FBX, Collada), normalised as vgd "
                                         "drape --avatar does; default: INPUT/avatar.obj when INPUT is a folder");
  sub->add_option("--unit", o->unit, "--avatar's unit: auto (from the file, else the body's height), m, dm, cm, mm, in")
      ->capture_default_str();
  sub->add_option("--up", o->up, "--avatar's up axis: auto (from the body), x, y, z, -x, -y, -z")->capture_default_str();
  sub->add_option("--facing", o->facing, "Where --avatar faces once up is +Y: auto (from the feet), +z, -z, +x, -x")
      ->capture_default_str();
  sub->add_option("--views", o->views, "Comma-separated views: front, back, left, right, three-quarter, or all")
      ->capture_default_str();
  sub->add_option("--size", o->size, "Image size, WIDTHxHEIGHT pixels (or one number, square)")->capture_default_str();
  sub->add_option("-o,--output", o->output, "Output folder for <view>.png")->capture_default_str();
  sub->add_option("--colour,--color", o->colour, "Garment colour: #rrggbb, #rgb or a name (red, navy, denim, ...)");
  sub->add_flag("--piece-colours,--piece-colors", o->piece_colours, "A distinct colour per piece");
  sub->add_option("--look", o->look, "Garment document (.xvc) whose piece colours and textures to draw; default: the "
                                     "one a drape folder's certificate.json names");
  sub->add_flag("--no-texture", o->no_texture, "Flat colours: draw no texture");
  sub->add_option("--map", o->map, "A fit map instead of the looks: the garment coloured by warp, weft or largest "
                                   "stretch strain (%), shear (deg), stress (the larger principal tension, N/m, "
                                   "from each piece's fabric) or pressure (on the body, kPa, from a drape folder's "
                                   "contact-pressure.json), with a legend (docs/render.md)")
      ->check(CLI::IsMember({"warp", "weft", "shear", "stretch", "stress", "pressure"}));
  sub->add_option("--map-range", o->map_range, "LO,HI: the values the map's colours span (default 0,40 for strain "
                                               "in %, 0,20 for shear in deg, 0,100 for stress in N/m, 0,5 for "
                                               "pressure in kPa)");
  sub->add_option("--body-colour,--body-color", o->body_colour, "Body colour (default a neutral light grey)");
  sub->add_option("--fit", o->fit, "Frame the views on the body (default) or on the garment (closer)")
      ->check(CLI::IsMember({"body", "garment"}))
      ->capture_default_str();
  sub->add_option("--supersample", o->supersample, "Anti-aliasing: draw at N x the size, then filter down (1–4)")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  sub->add_flag("--no-floor", o->no_floor, "No ground (and so no shadow)");
  sub->add_flag("--no-shadow", o->no_shadow, "No floor shadow");
  sub->footer("Views look at the body's bounding box: front from +Z, left from the body's left (+X), three-quarter "
              "from the front-left. Pieces take the document's colours and textures (PNG) unless --colour or "
              "--piece-colours is given. Same input, same bytes (docs/render.md).\n"
              "Exit codes: 0 written, 1 bad input or rendering failed, 2 usage.");
  return vgd::cli::Command{sub, [o, &common]() -> int { return vgd::cli::write_previews(*o, common); }};
}};

}  // namespace

namespace vgd::cli {

int write_previews(const RenderOptions& o, const Common& common) {
  // Views and size first: a typo should not wait for the files to load.
  std::vector<render::ViewPreset> views;
  for (const auto& name : vgd::split(o.views, ',')) {
    if (vgd::trim(name).empty()) continue;
    if (vgd::iequals(vgd::trim(name), "all")) {
      views = render::view_presets();
      break;
    }
    const auto v = render::find_view(name);
    if (!v) {
      std::fprintf(stderr, "vgd render: --views: unknown view '%s' (front, back, left, right, three-quarter, all)\n",
                   std::string(vgd::trim(name)).c_str());
      return vgd::cli::kUsage;
    }
    views.push_back(*v);
  }
  if (views.empty()) {
    std::fprintf(stderr, "vgd render: --views: no view given\n");
    return vgd::cli::kUsage;
  }
  std::pair<int, int> size;
  try {
    size = parse_size(o.size);
    if (!o.colour.empty()) parse_colour_option("--colour", o.colour);
    if (!o.body_colour.empty()) parse_colour_option("--body-colour", o.body_colour);
    if (!o.map.empty()) fit_scale(o);
    else if (!o.map_range.empty()) throw CLI::ValidationError("--map-range", "applies to a fit map (--map) only");
  } catch (const CLI::ValidationError& e) {
    std::fprintf(stderr, "vgd render: %s\n", e.what());
    return vgd::cli::kUsage;
  }

  const auto t0 = std::chrono::steady_clock::now();
  const render::Scene scene = load_scene(o, common);
  render::OffscreenOptions opts;
  opts.supersample = o.supersample;
  opts.frame_on_garment = o.fit == "garment";
  opts.look.floor = !o.no_floor;
  opts.look.shadow = !o.no_shadow;
  render::OffscreenRenderer renderer;
  renderer.set_scene(scene);
  if (common.verbose) vgd::cli::say(common, "vgd: " + renderer.gl_description());

  // One PNG per view.
  const fs::path out = o.output;
  for (const auto& v : views) {
    render::Image image = renderer.render(v, size.first, size.second, opts);
    if (!o.map.empty()) render::draw_legend(image, *render::parse_fit_map(o.map), fit_scale(o));
    const fs::path file = out / (v.name + ".png");
    render::write_png(image, file);
    if (o.list_files)
      std::printf("wrote %s (%d x %d, %s view)\n", file.string().c_str(), image.width, image.height, v.name.c_str());
  }
  std::fflush(stdout);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  vgd::cli::say(common, "vgd: rendered " + std::to_string(views.size()) + " view(s) of " +
                            std::to_string(scene.meshes.size()) + " meshes in " + vgd::format_fixed(s, 2) + " s");
  return vgd::cli::kOk;
}

}  // namespace vgd::cli
