#pragma once
// Wavefront OBJ frames: one file per frame (frame_0000.obj, frame_0001.obj, ...)
// holding the cloth's vertices (`v x y z`, metres) and triangles (`f a b c`,
// 1-based), one `g` group per piece. When the model handed over has pattern
// coordinates (sim::Model::uv, as `vgd drape` writes garment.obj), each vertex
// also gets a `vt u v` (metres of fabric, u along the grain line) with the
// same index, and faces read `f a/a b/b c/c`; readers that ignore `vt` still
// see the same vertices and triangles. Each file is written atomically
// (vgd::write_file_atomic), so files already written stay valid whatever
// happens to the run after them.
//
// This stage sees only what the engine hands a frame sink: the model's
// topology (triangles, pieces) and positions.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "vgd/sim/run.hpp"

namespace vgd::io::obj {

// A triangle mesh as an OBJ file holds it (what read_obj returns).
struct ObjMesh {
  std::vector<std::array<double, 3>> vertices;  // m
  std::vector<std::array<int, 3>> faces;        // 0-based vertex indices
  std::vector<std::string> groups;              // `g` names in file order
  std::vector<int> face_group;                  // per face, its index in groups (-1: before any group)
  std::vector<std::array<double, 2>> texcoords; // `vt u v` in file order (a third value is dropped)
  // Per face, 0-based indices into texcoords, or {-1, -1, -1} for a face
  // without them (`f a b c`, `f a//n ...`).
  std::vector<std::array<int, 3>> face_texcoords;
};

// OBJ text of one frame: a comment with the time, `v` per particle, `vt` per
// particle when topology.uv has one per particle, then per piece a `g` line
// and its faces.
std::string frame_text(const sim::Model& topology, double t, const sim::VecX& x);

// Reads the `v`, `vt`, `g`/`o` and `f` lines of an OBJ file (triangles;
// `f a/b/c` forms and negative indices accepted). Throws vgd::Error naming the file and line for a
// malformed line, a polygon that is not a triangle or an index out of range.
ObjMesh read_obj(const std::filesystem::path& file);

// The file name of frame `index`: <prefix><index, 4 digits or more>.obj.
std::string frame_file_name(int index, const std::string& prefix = "frame_");

// Writes every frame it is handed to directory/frame_NNNN.obj.
class ObjSequenceSink : public sim::FrameSink {
 public:
  explicit ObjSequenceSink(std::filesystem::path directory, std::string prefix = "frame_");
  void begin(const sim::Model& model) override;
  void frame(int index, double t, const sim::VecX& x) override;

  const std::filesystem::path& directory() const { return directory_; }
  int files_written() const { return written_; }

 private:
  std::filesystem::path directory_;
  std::string prefix_;
  sim::Model topology_;  // triangles and pieces only (positions come with each frame; no vt, frames stay small)
  int written_ = 0;
};

}  // namespace vgd::io::obj
