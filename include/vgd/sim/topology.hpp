#pragma once
// The cloth's mesh after seam merges (seed 002 §3.3, "Handling Seams"): when
// the two particles of a seam pair merge, E-Fabric's server removes one vertex,
// re-points the edges and triangles that used it to the surviving particle and
// removes the duplicate edges that appear. vgd keeps the original Model (and
// the effects' original indexing, like E-Fabric's client) and describes the
// merged mesh by a representative map: representative[i] is the reduced index
// (0 .. particles − 1) of original particle i; particles with the same
// representative are one particle (System::apply_merges). This header derives
// the restructured mesh from that map, and checks it.
#include <array>
#include <vector>

#include "vgd/sim/model.hpp"

namespace vgd::sim {

// The restructured mesh, in reduced particle indices.
struct MergedMesh {
  int particles = 0;                            // reduced particle count
  std::vector<std::array<int, 3>> triangles;    // re-pointed, collapsed ones removed, original order
  std::vector<int> source_triangle;             // original triangle of each kept triangle
  std::vector<std::array<int, 2>> edges;        // every undirected edge once, smaller index first, sorted
  int collapsed_triangles = 0;                  // removed: two of their corners became one particle
  int merged_edges = 0;                         // duplicate edges removed (edges of the original mesh − edges)
};

// The identity map of a model (no merges).
std::vector<int> identity_representative(int particles);

// Sets the copies of each merged particle (equal `representative` values) in
// x (3 per particle) to their mass-weighted mean: where System puts the merged
// particle. For effects that remember positions between steps.
void average_merged_copies(const std::vector<int>& representative, const VecX& mass, VecX& x);

// Re-points the model's triangles through `representative` (size
// Model::num_particles(), values 0 .. max), drops triangles whose corners are
// no longer three distinct particles, and lists the edges once.
MergedMesh merged_topology(const Model& m, const std::vector<int>& representative);

// Defects of a (merged) mesh. A cloth mesh is a manifold with boundary: every
// edge borders one triangle (boundary) or two (interior).
struct MeshCheck {
  int triangles = 0;
  int edges = 0;
  int boundary_edges = 0;       // edges of exactly one triangle
  int interior_edges = 0;       // edges of exactly two triangles
  int non_manifold_edges = 0;   // edges of three or more triangles
  int degenerate_triangles = 0; // a particle repeated in a triangle
  int duplicate_triangles = 0;  // two triangles on the same three particles
  std::vector<std::array<int, 2>> non_manifold;  // the non-manifold edges (reduced indices)
  bool ok() const { return non_manifold_edges == 0 && degenerate_triangles == 0 && duplicate_triangles == 0; }
};

MeshCheck check_mesh(const std::vector<std::array<int, 3>>& triangles);
inline MeshCheck check_merged_mesh(const MergedMesh& mesh) { return check_mesh(mesh.triangles); }

}  // namespace vgd::sim
