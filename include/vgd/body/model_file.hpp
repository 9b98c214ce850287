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

// One mesh of the file as it lies in ModelFile::surface.
struct ModelMesh {
  std::string name;       // the mesh's name (OBJ: its group or object)
  std::string node;       // the node that holds it
  int first_vertex = 0, vertices = 0;
  int first_triangle = 0, triangles = 0;
  bool skinned = false;   // it has bones
};

// A joint of the file's skeleton: a bone of a skinned mesh, at its bind-pose
// origin (the inverse of its offset matrix), in the frame of `surface`.
struct ModelJoint {
  std::string name;  // as the file names it ("mixamorig:LeftForeArm", "L_Elbow", "lowerarm01.L")
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct ModelFile {
  // Every triangle mesh of the node tree merged into one surface (vertices
  // not welded), each vertex moved by its node's accumulated transform, except
  // skinned meshes when ModelReadOptions::bind_pose (glTF 2.0 §3.7.3: "the
  // transform of the node that the mesh is attached to is ignored"; their
  // vertices are the bind pose).
  mesh::SurfaceMesh surface;
  std::vector<ModelMesh> meshes;  // those that gave triangles, in surface order
  std::vector<ModelJoint> joints;  // the skinned meshes' bones, each once (first mesh that has it)
  int dropped = 0;                // faces that were points or lines
  // The file's numeric metadata (FBX's UnitScaleFactor, UpAxis, UpAxisSign, ...).
  std::map<std::string, double> metadata;
};

struct ModelReadOptions {
  bool bind_pose = false;  // skinned meshes without their node transform (glTF's rule)
  // s: assimp reads in a child process; one still reading after this long is
  // killed and the file refused (assimp loops on some damaged files: a
  // 900-byte PLY for ever). 0: 5 s plus 1 s per MB of file, far more
  // than assimp takes (`vgd avatar report` on a 0.7 MB body: 0.2 s in all).
  double time_limit_s = 0.0;
  // An OBJ face with more corners than this is refused before assimp reads
  // the file (its triangulation's time grows faster than the corner count).
  std::size_t max_face_corners = 1024;
};

// Reads `path`; assimp validates the scene it builds before vgd reads it (a
// file whose scene is inconsistent is refused, not followed). assimp runs in
// a child process (fork), which sends the model back through a pipe: a file
// on which assimp crashes, aborts or hangs past the time limit is refused
// with what happened, and the caller goes on. Throws
// vgd::Error naming the file when it cannot be read or understood, with the
// reason.
ModelFile read_model_file(const std::filesystem::path& path, const ModelReadOptions& options = {});

// Writes `surface` (with per-vertex `normals`, one per vertex) as one mesh
// named "body" to `path` in assimp's format `format_id` (objnomtl, plyb,
// stlb, glb2, gltf2, collada). assimp writes straight to its path (and glTF a
// .bin beside it): not atomic; avatar_io.hpp writes into a private folder and
// moves the files. Throws vgd::Error naming the file.
void write_model_file(const mesh::SurfaceMesh& surface, const std::vector<Eigen::Vector3d>& normals,
                      const std::filesystem::path& path, const std::string& format_id);

}  // namespace vgd::body
