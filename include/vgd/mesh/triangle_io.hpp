#pragma once
// Shewchuk's Triangle file formats, as E-Fabric exchanged meshes (seed 002 §2):
//   base.node  nodes with one boundary marker each
//   base.ele   triangles (3 nodes, counter-clockwise)
//   base.poly  the boundary segments with their markers, and one point per hole
// Format: https://www.cs.cmu.edu/~quake/triangle.node.html (and .ele, .poly).
// Lines are whitespace-separated numbers; '#' starts a comment. Files are written
// 1-based as Triangle does; the reader takes the base (0 or 1) from the first node
// number as Triangle does. Coordinates are written with 17 significant digits, so
// a round trip is exact. Units: whatever the mesh holds (metres in vgd).
#include <array>
#include <filesystem>
#include <vector>

#include "vgd/mesh/mesh.hpp"

namespace vgd::mesh {

// The content of one .node/.ele/.poly triple, indices 0-based.
struct TriangleData {
  std::vector<Vec2> nodes;
  std::vector<int> node_markers;                // one per node (0 when the file has none)
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 2>> segments;
  std::vector<int> segment_markers;             // one per segment (0 when the file has none)
  std::vector<Vec2> holes;                      // one point inside each hole
};

// Nodes, markers, triangles, boundary edges as segments and a point inside each cutout.
TriangleData to_triangle_data(const PieceMesh& mesh);

// Writes base.node, base.ele and base.poly, each atomically (vgd::write_file_atomic).
// `base` is a path without extension, e.g. out/FRONT.1 as Triangle names its output.
// Throws vgd::Error naming the file that could not be written.
void write_triangle_files(const TriangleData& data, const std::filesystem::path& base);
void write_triangle_files(const PieceMesh& mesh, const std::filesystem::path& base);

// Reads base.node and base.ele, and base.poly when it exists (vertices listed in
// the .poly itself are used when there is no .node file). Node attributes are
// skipped. Throws vgd::Error naming the file and line of the first problem.
TriangleData read_triangle_files(const std::filesystem::path& base);

}  // namespace vgd::mesh
