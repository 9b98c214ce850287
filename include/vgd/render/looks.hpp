#pragma once
// The looks of a garment document on render meshes (docs/render.md,
// "Looks"): each piece's colour and texture as its XVC document gives them
// (io/vrml/looks.hpp reads them), the texture images read from files named
// relative to the document. `vgd render` and the studio's preview draw a
// garment with them.
//
//   std::vector<render::Mesh*> pieces = ...;   // named by piece, with uv (m) for textures
//   render::apply_looks(pieces, doc, true, diags);
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/render/scene.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::render {

// Texture images already read, by file and placement (one read per file and
// placement; pass the same cache to later calls to read none again).
using TextureCache = std::map<std::string, std::shared_ptr<const Texture>>;

// Colours each mesh (matched by piece, block name or id) as the document
// says, as the VRML and glTF exports do: its MATERIAL's colour (a piece the
// document does not colour keeps its own), and with `textures` its TEXTURE,
// shown as the image is (it replaces the colour, as in VRML97), which needs
// the mesh's uv (a mesh without gets its flat colour and a warning in `diags`). Throws
// vgd::Error naming the image and the piece for a texture that cannot be read.
void apply_looks(const std::vector<Mesh*>& pieces, const xvc::Document& doc, bool textures, Diagnostics& diags,
                 TextureCache* cache = nullptr);

}  // namespace vgd::render
