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
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/obj/obj.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/render/offscreen.hpp"
#include "vgd/scene/avatar_io.hpp"

namespace {

namespace fs = std::filesystem;
namespace render = vgd::render;

struct Options {
  std::string input, avatar, output = "previews", views = "front,back,left,right,three-quarter", size = "1024x1024";
  std::string colour, body_colour, fit = "body";
  bool piece_colours = false, no_floor = false, no_shadow = false;
  int supersample = 3, frame = -1;
};

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

// Per face of an OBJ file, the index of the `g`/`o` group it follows (read_obj
// keeps faces and group names in file order; this pairs them).
std::vector<int> face_groups(const fs::path& file) {
  std::ifstream in(file);
  std::vector<int> groups;
  int group = -1;
  for (std::string line; std::getline(in, line);) {
    const auto t = vgd::trim(line);
    if (t.size() > 1 && (t[0] == 'g' || t[0] == 'o') && (t[1] == ' ' || t[1] == '\t')) ++group;
    else if (t.size() > 1 && t[0] == 'f' && (t[1] == ' ' || t[1] == '\t')) groups.push_back(std::max(group, 0));
  }
  return groups;
}

// One render mesh per group of an OBJ (its own vertices only).
std::vector<render::Mesh> meshes_of_obj(const fs::path& file, render::MeshKind kind) {
  const auto obj = vgd::io::obj::read_obj(file);
  const auto groups = face_groups(file);
  const int n_groups = std::max<int>(1, static_cast<int>(obj.groups.size()));
  std::vector<render::Mesh> meshes(static_cast<std::size_t>(n_groups));
  std::vector<std::vector<int>> remap(meshes.size(), std::vector<int>(obj.vertices.size(), -1));
  for (std::size_t f = 0; f < obj.faces.size(); ++f) {
    const int g = f < groups.size() ? std::min(groups[f], n_groups - 1) : 0;
    auto& m = meshes[static_cast<std::size_t>(g)];
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      int& r = remap[static_cast<std::size_t>(g)][static_cast<std::size_t>(obj.faces[f][k])];
      if (r < 0) {
        r = static_cast<int>(m.positions.size());
        const auto& v = obj.vertices[static_cast<std::size_t>(obj.faces[f][k])];
        m.positions.push_back({static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])});
      }
      tri[k] = r;
    }
    m.triangles.push_back(tri);
  }
  for (std::size_t g = 0; g < meshes.size(); ++g) {
    meshes[g].kind = kind;
    meshes[g].name = g < obj.groups.size() ? obj.groups[g] : file.stem().string();
  }
  std::erase_if(meshes, [](const render::Mesh& m) { return m.triangles.empty(); });
  return meshes;
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
render::Mesh body_mesh(const fs::path& file) {
  const auto avatar = vgd::scene::import_avatar(file);
  render::Mesh m;
  m.name = "body";
  m.kind = render::MeshKind::body;
  for (const auto& v : avatar.surface.vertices)
    m.positions.push_back({static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
  m.triangles = avatar.surface.triangles;
  return m;
}

// The scene: the garment's pieces and the body, coloured.
render::Scene load_scene(const Options& o, const vgd::cli::Common& common) {
  render::Scene scene;
  const fs::path input = o.input;
  std::error_code ec;
  fs::path garment = input, avatar_obj;
  if (fs::is_directory(input, ec)) {
    garment = input / "garment.obj";
    if (!fs::exists(garment, ec))
      throw vgd::Error(input.string(), "", "not a drape folder: garment.obj is missing (vgd drape GARMENT -o DIR writes it)");
    if (fs::exists(input / "avatar.obj", ec)) avatar_obj = input / "avatar.obj";
  } else if (!fs::exists(input, ec)) {
    throw vgd::Error(input.string(), "", "file not found");
  } else if (const auto ext = vgd::to_lower(input.extension().string()); ext != ".obj" && ext != ".trj") {
    throw vgd::Error(input.string(), "", "vgd render reads a drape folder, a garment .obj or a trajectory .trj");
  }
  const bool trj = vgd::to_lower(input.extension().string()) == ".trj";
  if (!trj && o.frame != -1) throw vgd::Error(input.string(), "", "--frame applies to a trajectory (.trj) only");
  const render::Colour fabric = o.colour.empty() ? render::kFabric : parse_colour_option("--colour", o.colour);
  int index = 0;
  auto pieces = trj ? meshes_of_trj(input, o.frame, common) : meshes_of_obj(garment, render::MeshKind::garment);
  for (auto& m : pieces) {
    m.kind = render::MeshKind::garment;
    m.colour = o.piece_colours ? render::piece_colour(index) : fabric;
    ++index;
    scene.meshes.push_back(std::move(m));
  }
  const render::Colour body = o.body_colour.empty() ? render::kBody : parse_colour_option("--body-colour", o.body_colour);
  if (!o.avatar.empty()) {
    scene.meshes.push_back(body_mesh(o.avatar));
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
  sub->add_option("--views", o->views, "Comma-separated views: front, back, left, right, three-quarter, or all")
      ->capture_default_str();
  sub->add_option("--size", o->size, "Image size, WIDTHxHEIGHT pixels (or one number, square)")->capture_default_str();
  sub->add_option("-o,--output", o->output, "Output folder for <view>.png")->capture_default_str();
  sub->add_option("--colour,--color", o->colour, "Garment colour: #rrggbb, #rgb or a name (red, navy, denim, ...)");
  sub->add_flag("--piece-colours,--piece-colors", o->piece_colours, "A distinct colour per piece");
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
              "from the front-left. Same input, same bytes (docs/render.md).\n"
              "Exit codes: 0 written, 1 bad input or rendering failed, 2 usage.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    // Views and size first: a typo should not wait for the files to load.
    std::vector<render::ViewPreset> views;
    for (const auto& name : vgd::split(o->views, ',')) {
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
      size = parse_size(o->size);
      if (!o->colour.empty()) parse_colour_option("--colour", o->colour);
      if (!o->body_colour.empty()) parse_colour_option("--body-colour", o->body_colour);
    } catch (const CLI::ValidationError& e) {
      std::fprintf(stderr, "vgd render: %s\n", e.what());
      return vgd::cli::kUsage;
    }

    const auto t0 = std::chrono::steady_clock::now();
    const render::Scene scene = load_scene(*o, common);
    render::OffscreenOptions opts;
    opts.supersample = o->supersample;
    opts.frame_on_garment = o->fit == "garment";
    opts.look.floor = !o->no_floor;
    opts.look.shadow = !o->no_shadow;
    render::OffscreenRenderer renderer;
    renderer.set_scene(scene);
    if (common.verbose) vgd::cli::say(common, "vgd: " + renderer.gl_description());

    // One PNG per view.
    const fs::path out = o->output;
    for (const auto& v : views) {
      const render::Image image = renderer.render(v, size.first, size.second, opts);
      const fs::path file = out / (v.name + ".png");
      render::write_png(image, file);
      std::printf("wrote %s (%d x %d, %s view)\n", file.string().c_str(), image.width, image.height, v.name.c_str());
    }
    std::fflush(stdout);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    vgd::cli::say(common, "vgd: rendered " + std::to_string(views.size()) + " view(s) of " +
                              std::to_string(scene.meshes.size()) + " meshes in " + vgd::format_fixed(s, 2) + " s");
    return vgd::cli::kOk;
  }};
}};

}  // namespace
