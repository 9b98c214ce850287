#pragma once
// 3-D model files (OBJ, PLY, STL, glTF/GLB, FBX, Collada, ...) read and written
// through assimp, which lives in a module of its own (vgd_assimp, a shared
// object) opened on first use: assimp and its codecs cost every process that
// links them several milliseconds of start-up, and most vgd commands read no
// body (docs/performance.md, "Start-up").
//
// The module is looked for in $VGD_MODULE_DIR, then in this build's tree, then
// in the installed library directory (<prefix>/lib/vgd). Units: whatever the
// file holds (no conversion here; avatar_io.hpp normalises).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vgd/mesh/surface.hpp"

namespace vgd::body {

struct ModelFile {
  // Every triangle mesh of the node tree, each vertex moved by its node's
  // accumulated transform, merged into one surface (vertices not welded).
  mesh::SurfaceMesh surface;
  int meshes = 0;   // meshes that gave triangles
  int dropped = 0;  // faces that were points or lines
  // The file's numeric metadata (FBX's UnitScaleFactor, UpAxis, UpAxisSign, ...).
  std::map<std::string, double> metadata;
};

// Reads `path`. Throws vgd::Error naming the file when it cannot be read or
// understood, with assimp's reason.
ModelFile read_model_file(const std::filesystem::path& path);

// Writes `surface` (with per-vertex `normals`, one per vertex) as one mesh
// named "body" to `path` in assimp's format `format_id` (objnomtl, plyb,
// stlb, glb2, gltf2, collada). assimp writes straight to its path (and glTF a
// .bin beside it): not atomic; avatar_io.hpp writes into a private folder and
// moves the files. Throws vgd::Error naming the file.
void write_model_file(const mesh::SurfaceMesh& surface, const std::vector<Eigen::Vector3d>& normals,
                      const std::filesystem::path& path, const std::string& format_id);

}  // namespace vgd::body
