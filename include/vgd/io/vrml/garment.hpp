#pragma once
// What the exporters of this stage (VRML97, glTF binary, OBJ, the web page)
// read: a draped garment as plain data — the cloth's topology with its
// material coordinates, its frames, how each piece looks, and the body.
//
// The structs mirror a .trj trajectory (io/trj/trj.hpp: Topology, frames as
// float32) without depending on its reader, so a test, the GUI or a drape in
// memory can hand a garment to the writers directly. Units: metres, seconds.
//
//   io::vrml::Garment g;
//   g.cloth.triangles = ...; g.cloth.uv = ...;          // from the model / .trj
//   g.frames.times = {0.0}; g.frames.positions = {x};   // 3N floats per frame
//   std::string wrl = io::vrml::static_vrml(g);         // vrml.hpp
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace vgd::io::vrml {

// A colour with opacity, each in [0, 1] (XVC COLORRGBA).
struct Rgba {
  double r = 0.8, g = 0.8, b = 0.8, a = 1.0;
};

// The fabric colour of a piece the document gives no colour: a mid indigo
// (denim), far from skin and background colours so a screenshot can find it.
inline constexpr Rgba kDefaultFabric{0.18, 0.30, 0.62, 1.0};
// The body's colour when none is given: a light warm grey (a dress form).
inline constexpr Rgba kDefaultBody{0.82, 0.78, 0.72, 1.0};

// How one piece looks (XVC MATERIAL's COLORRGBA, TEXTURE with SCALE2D and
// ROTATION2D, assigned to the PATTERN by ASSOCIATIONs; looks.hpp reads them).
struct PieceLook {
  Rgba colour = kDefaultFabric;
  std::string texture;        // image file (as the document names it; a URL relative to the output), "" = none
  double repeat_u = 0.1;      // m of fabric per texture repeat along u (the warp, grain line); SCALE2D x
  double repeat_v = 0.1;      // m along v (the weft); SCALE2D y
  double rotation_deg = 0.0;  // texture rotation on the fabric, degrees counter-clockwise (ROTATION2D)
  std::string source;         // where the look came from ("material1 (cotton)", "default"), for reports
};

// The cloth's topology (what does not change from frame to frame).
struct Cloth {
  std::vector<std::array<int, 3>> triangles;  // particle indices, counter-clockwise in material space
  std::vector<int> triangle_piece;            // piece of each triangle; empty = one piece
  std::vector<std::string> pieces;            // piece names (at least one when triangle_piece is set)
  // Material coordinates of each particle, m: u along the warp (grain line), v
  // along the weft (sim::Model::uv). Texture coordinates are these values.
  std::vector<std::array<double, 2>> uv;
  // Seam merges at the last frame: representative[i] is the particle that
  // particle i is a copy of (itself when not merged). Empty = no merges.
  std::vector<int> representative;

  int num_particles() const { return static_cast<int>(uv.size()); }
  int num_pieces() const { return pieces.empty() ? 1 : static_cast<int>(pieces.size()); }
  int piece_of(std::size_t triangle) const {
    return triangle_piece.empty() ? 0 : triangle_piece[triangle];
  }
};

// Frames of the run: times (s) and 3N float32 positions (m) each.
struct Frames {
  std::vector<double> times;
  std::vector<std::vector<float>> positions;
  int count() const { return static_cast<int>(positions.size()); }
};

// A body (avatar or mannequin) as a triangle mesh, metres, +Y up.
struct Body {
  std::string name = "avatar";
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;
  Rgba colour = kDefaultBody;
};

struct Garment {
  std::string name = "garment";  // a title for pages and DEF names
  Cloth cloth;
  Frames frames;                 // at least one
  std::vector<PieceLook> looks;  // one per piece; missing entries get PieceLook{}
  std::optional<Body> body;

  const PieceLook& look(int piece) const;
  // Checks sizes and indices (particles of uv and every frame agree, triangles
  // and pieces index what exists, merges point inside); throws vgd::Error
  // naming `name` and the first problem.
  void validate() const;
};

// ---- the mesh a viewer gets ---------------------------------------------------

// One piece's faces for an IndexedFaceSet: coordIndex into the output vertices,
// texCoordIndex into the particles' uv.
struct PieceFaces {
  std::vector<std::array<int, 3>> coord;  // output vertex indices
  std::vector<std::array<int, 3>> tex;    // particle indices (uv)
};

// The garment as written: the output vertices (one per particle, or one per
// merged group when welded) and each piece's faces. Triangles whose corners
// were merged into fewer than three vertices are dropped.
struct OutputMesh {
  std::vector<int> vertex_particle;  // particle each output vertex takes its position from
  std::vector<int> particle_vertex;  // output vertex of each particle
  std::vector<PieceFaces> pieces;    // one per piece (may be empty)
  int face_count() const;
};

// Welded (merged particles share one vertex, so normals are smooth across
// seams) or one vertex per particle (what an animation needs: seams close
// during the run).
OutputMesh output_mesh(const Cloth& cloth, bool welded);

// Per-vertex normals of the output mesh at positions x (3N, m): area-weighted
// face normals over every piece, unit length ((0, 1, 0) for an isolated vertex).
std::vector<std::array<double, 3>> vertex_normals(const OutputMesh& mesh, const std::vector<float>& x);

// ---- creaseAngle from the mesh resolution (seed 000 §4.1.1) ----------------------

// The median edge length of the triangles in material space (uv), m.
double median_edge_length(const Cloth& cloth);
// Median edge length of a body mesh, m.
double median_edge_length(const Body& body);

// The smallest fold radius a drape shows as a rounded fold rather than a
// sharp crease, m: about the bending length of light garment fabric.
inline constexpr double kCreaseRadius = 0.006;

// creaseAngle (rad) for a mesh of median edge length h (m). Neighbouring faces
// across a fold of radius R meet at an angle of about h / R, so a coarse mesh
// needs a large threshold to smooth its folds and a fine one can keep sharp
// real creases: creaseAngle = clamp(h / kCreaseRadius, 0.5, 3.14). docs/vrml.md.
double crease_angle(double median_edge_m);

}  // namespace vgd::io::vrml
