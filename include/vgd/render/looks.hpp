#pragma once
// Looks on render meshes (docs/render.md, "Looks and textures"): each
// piece's colour and texture image, as a garment document gives them (the
// callers read them: io::vrml::looks_from_xvc), the images read from their
// files once. `vgd render` and the studio's preview draw a garment with them.
//
//   std::vector<render::Mesh*> pieces = ...;   // with uv (m) for textures
//   std::vector<render::Look> looks = ...;     // one per piece
//   render::apply_looks(pieces, looks, true, diags);
#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/render/scene.hpp"

namespace vgd::render {

struct Look {
  std::optional<Colour> colour;        // none: the mesh keeps its own
  std::filesystem::path texture;       // PNG image; empty: none
  std::array<double, 2> repeat_m{0.1, 0.1};  // m of fabric per repeat along u, v
  double rotation_deg = 0.0;           // counter-clockwise on the fabric
};

// Texture images already read, by file and placement (pass the same cache to
// later calls to read none again).
using TextureCache = std::map<std::string, std::shared_ptr<const Texture>>;

// Gives pieces[i] looks[i]: its colour, and with `textures` its texture,
// shown as the image is (it replaces the colour, as in VRML97), which needs
// the mesh's uv (a mesh without gets its flat colour and a warning in
// `diags`). Throws vgd::Error naming the image and the piece for a texture
// that cannot be read.
void apply_looks(const std::vector<Mesh*>& pieces, const std::vector<Look>& looks, bool textures, Diagnostics& diags,
                 TextureCache* cache = nullptr);

}  // namespace vgd::render
