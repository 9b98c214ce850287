#pragma once
// What the renderer draws: triangle meshes with a colour each, in vgd's frame
// (metres, +Y up, the body facing +Z; docs/avatar.md).
//
// A render::Scene is plain data, filled by whoever has the geometry: the `vgd
// render` command from a drape folder or a trajectory, the studio from its
// live simulation. The renderer never reads files.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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
