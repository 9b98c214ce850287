#pragma once
// What the renderer draws: triangle meshes with a colour each, in vgd's frame
// (metres, +Y up, the body facing +Z; docs/avatar.md).
//
// A render::Scene is plain data, filled by whoever has the geometry: the `vgd
// render` command from a drape folder or a trajectory, the studio from its
// live simulation. The renderer never reads files.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/render/image.hpp"

namespace vgd::render {

// An sRGB colour, components 0–1.
struct Colour {
  float r = 0, g = 0, b = 0;
};

// "#rrggbb", "rrggbb", "#rgb" or a name (docs/render.md lists them). Empty
// optional when the text is not a colour.
std::optional<Colour> parse_colour(std::string_view text);

// "#rrggbb".
std::string to_hex(const Colour& c);

// The default fabric (a mid blue), the body (a neutral light grey with a little
// warmth), and a palette of distinct colours for pieces.
inline constexpr Colour kFabric{0.25f, 0.42f, 0.68f};
inline constexpr Colour kBody{0.80f, 0.78f, 0.75f};
Colour piece_colour(int index);

enum class MeshKind {
  garment,  // cloth: lit on both sides
  body,     // the avatar: what the camera presets are framed on
};

// A fabric image repeated over a piece (XVC TEXTURE, docs/xvc.md): the mesh's
// pattern coordinates (Mesh::uv, m) are turned by `rotation_rad` and divided by
// `repeat_m`, so one copy of the image covers repeat_m[0] × repeat_m[1] metres
// of fabric, u along the grain line. The image's top row is at v = 0 and its
// rows go down as v falls, as in the VRML and glTF exports.
struct Texture {
  Image image;                               // sRGB pixels, row 0 at the top; alpha is ignored
  std::array<double, 2> repeat_m{0.1, 0.1};  // m of fabric per repeat along u, v (XVC SCALE2D)
  double rotation_rad = 0;                   // counter-clockwise on the fabric (XVC ROTATION2D)
};

struct Mesh {
  std::string name;  // a piece's name, "body", ...
  MeshKind kind = MeshKind::garment;
  std::vector<std::array<float, 3>> positions;  // m
  std::vector<std::array<int, 3>> triangles;    // 0-based indices into positions
  // Per-vertex unit normals, or empty: the renderer then computes them
  // (compute_normals). Their sign does not matter: garments are lit on the
  // side facing the camera.
  std::vector<std::array<float, 3>> normals;
  Colour colour = kFabric;
  // Optional pattern coordinates per vertex, m (sim::Model::uv; `vt` in
  // garment.obj), and the texture drawn with them. The texture multiplies
  // `colour` (set it white to show the image as it is). A mesh with a texture
  // needs uv; pieces of one garment may share one texture.
  std::vector<std::array<float, 2>> uv;
  std::shared_ptr<const Texture> texture;
  // Optional sRGB colour per vertex (a fit map, render/fit_map.hpp),
  // multiplying `colour` (set it white to show them as they are); used when
  // there is one per position.
  std::vector<Colour> vertex_colours;
};

struct Scene {
  std::vector<Mesh> meshes;
};

// Axis-aligned bounds, m. Empty (min > max) when nothing was added.
struct Box {
  std::array<double, 3> min{1e300, 1e300, 1e300};
  std::array<double, 3> max{-1e300, -1e300, -1e300};
  bool empty() const { return min[0] > max[0] || min[1] > max[1] || min[2] > max[2]; }
  void extend(const std::array<float, 3>& p);
  void extend(const Box& b);
};

// Bounds of every mesh, or of the meshes of one kind only.
Box bounds(const Scene& scene, std::optional<MeshKind> kind = std::nullopt);

// Fills the missing normals: area-weighted means of the adjacent triangles'
// normals. Vertices at exactly the same position in meshes of the same kind
// (the two sides of a sewn seam) share one normal, so seams shade smoothly;
// neighbours wound the other way round are turned to agree first.
void compute_normals(Scene& scene);

// Checks the scene: finite positions, indices in range. Throws vgd::Error
// naming the mesh.
void check_scene(const Scene& scene);

}  // namespace vgd::render
