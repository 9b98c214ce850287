#pragma once
// glTF 2.0 binary (.glb) and Wavefront OBJ (+ MTL) of the final drape, for the
// tools designers use next (Blender, web viewers, marketplaces). Same data as
// the static VRML: one mesh per piece with positions (m, +Y up), smooth
// normals (welded across seams), texture coordinates from the pieces'
// material coordinates, and the piece's colour as a material; the body as
// its own mesh. docs/vrml.md.
#include <string>

#include "vgd/io/vrml/garment.hpp"

namespace vgd::io::vrml {

struct DrapeExportOptions {
  int frame = -1;    // -1 = the last (the final drape)
  bool body = true;  // include the garment's body
};

// The bytes of a .glb file: a JSON chunk (asset, scene, nodes, meshes,
// materials with baseColorFactor and doubleSided, accessors with min/max) and
// one BIN chunk. TEXCOORD_0 is (u, -v) in texture repeats of the piece's
// texture when it has one (glTF has no texture transform in its core), else
// (u, -v) in metres. Written by vgd itself (no library).
std::string glb_bytes(const Garment& garment, const DrapeExportOptions& options = {});

// OBJ text of the drape: `mtllib`, then `v` (welded vertices), `vt` (material
// coordinates, m), `vn`, and per piece `g` + `usemtl` + `f v/vt/vn`; the body
// as group `avatar` with its own vertices.
std::string obj_text(const Garment& garment, const std::string& mtl_file_name, const DrapeExportOptions& options = {},
                     int precision = 5);
// The MTL text that goes with it: one material per piece (Kd, d, map_Kd with
// `-s` scale for textures) and `avatar`.
std::string mtl_text(const Garment& garment);

}  // namespace vgd::io::vrml
