#pragma once
// Triangle meshes of pattern pieces (seed 002 §2): the cloth the engine simulates.
//
// A piece's outline and cutouts are resampled (pattern/resample.hpp), then filled
// with a constrained Delaunay triangulation refined until every triangle meets a
// minimum-angle and a maximum-size bound (Shewchuk's Delaunay refinement as CGAL
// implements it; E-Fabric used Shewchuk's Triangle program the same way).
//
// Units: metres, m², degrees. Coordinates stay in the pattern's 2-D frame, so the
// nodes double as texture coordinates and, through the grain line, as material
// (warp/weft) coordinates.
//
// Guarantees of a returned mesh: every contour vertex is a node, bit for bit; the
// triangles are counter-clockwise and cover exactly the piece (outline minus
// cutouts, area equal to 1e-9 relative); each interior edge is shared by two
// triangles and each boundary edge by one. The angle bound holds except in
// triangles near contour corners sharper than the bound (and, with
// split_boundary = false, possibly next to the boundary): check_mesh measures it.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/pattern/piece.hpp"
#include "vgd/pattern/resample.hpp"

namespace vgd::mesh {

using Vec2 = pattern::Vec2;

// Boundary markers, as Triangle writes them in .node and .poly files. Later stages
// may overwrite markers with their own codes (belt/sleeve points, seam hems).
inline constexpr int kInteriorMarker = 0;   // a node inside the piece
inline constexpr int kOutlineMarker = 1;    // on the outline
inline constexpr int kFirstCutoutMarker = 2;  // contour 1 + k (a cutout) carries kFirstCutoutMarker + k

// One closed contour handed to the mesher.
struct Contour {
  std::vector<Vec2> points;  // closed (the last point joins the first), no duplicates, m
  std::vector<int> sides;    // per edge i (points[i] -> points[i+1]): resampling side; may be empty
  int cutout = -1;           // index in Piece::cutouts, -1 for the outline
};

// One edge of the mesh boundary and where it came from.
struct BoundaryEdge {
  int a = -1, b = -1;     // nodes; the piece lies on the left of a -> b
  int contour = 0;        // index in PieceMesh::contours: 0 = outline, 1 + k = k-th meshed cutout
  int contour_edge = -1;  // edge i of that contour (points[i] -> points[i+1]) holding this edge
  int side = -1;          // that contour edge's side (Contour::sides), -1 when unknown
  int marker = kOutlineMarker;
};

// Warp/weft frame of a piece, from its grain line (seed 002 §3: the strain rosette
// measures angles from the warp).
struct MaterialFrame {
  Vec2 origin = Vec2::Zero();  // m: the grain line's start, or the pattern origin
  Vec2 warp = Vec2::UnitX();   // unit vector along the grain line
  Vec2 weft = Vec2::UnitY();   // warp turned +90°
};

// The mesh of one piece.
struct PieceMesh {
  std::string piece;                           // block name, for messages
  std::vector<Contour> contours;               // what was meshed: [0] outline (CCW), then the cutouts kept
  std::vector<Vec2> nodes;                     // pattern coordinates, m
  std::vector<int> node_markers;               // per node: kInteriorMarker or its contour's marker
  std::vector<std::array<int, 3>> triangles;   // node indices, counter-clockwise
  std::vector<BoundaryEdge> boundary;          // each contour in turn, piece on the left
  std::vector<std::vector<int>> contour_nodes;  // [c][i]: node of contours[c].points[i]
  MaterialFrame frame;
  // Node order: contour vertices first (outline, then cutouts; a vertex shared by
  // two contours once), then the lines' points, then Steiner nodes on the
  // boundary, then interior nodes.
  int boundary_steiner_nodes = 0;  // nodes the refinement added on contour edges
  std::vector<std::vector<int>> line_nodes;  // [k][i]: node of MeshOptions::lines[k][i]
};

struct MeshOptions {
  // Contour resampling before meshing: spacing (m) and side-split angle (deg).
  pattern::ResampleOptions resample;
  bool resample_contour = true;  // false: mesh the outline's vertices as they are
  // Smallest triangle angle wanted, degrees. CGAL proves termination up to 20.7°;
  // 25–30 works in practice; above 33 refinement may not end (refused).
  double min_angle_deg = 25.0;
  // Largest triangle area, m². 0 = (1+√2)/4 · spacing² ≈ 0.60 spacing² when
  // resampling by spacing, else no bound. That default is the largest triangle on a
  // spacing-long edge whose circumcentre does not encroach on the edge, so the size
  // bound alone never splits the resampled contour; mean triangle edge ≈ spacing.
  double max_area_m2 = 0.0;
  // Longest triangle edge, m. 0 = no bound.
  double max_edge_m = 0.0;
  // Allow Steiner points on contour edges where the refinement needs them (counted
  // in PieceMesh::boundary_steiner_nodes). false keeps the boundary exactly as given
  // (Triangle's -Y), at the price of bad triangles next to it.
  bool split_boundary = true;
  // Refinement stops with an error beyond this many nodes (runaway guard).
  std::size_t max_nodes = 2'000'000;
  // Open polylines inside the piece (m, pattern frame) meshed as constraints:
  // every point a node, bit for bit (PieceMesh::line_nodes), and no triangle
  // across them; a seam sewn onto the piece's face runs along one. Not
  // resampled. With split_boundary the refinement may add nodes on them
  // (interior nodes); without, it does not.
  std::vector<std::vector<Vec2>> lines;
};

// The area bound meshing will use, m² (0 = none): max_area_m2 or its default.
double effective_max_area(const MeshOptions& options);

// Meshes contours as given (no resampling): contours[0] is the outline, CCW; the
// rest are holes lying inside it, either orientation. Throws vgd::Error naming
// `piece` when the contours cross each other or themselves, are degenerate, or
// refinement exceeds max_nodes. Adds no frame (identity).
PieceMesh triangulate(const std::vector<Contour>& contours, const MeshOptions& options,
                      const std::string& piece = "");

// Meshes one piece: resamples outline and closed cutouts (as options say), checks
// the cutouts (open ones, ones outside the outline or crossing it are skipped with
// a warning in `diag`), triangulates, and sets the frame from the grain line.
// Throws vgd::Error naming the block when the piece cannot be meshed (open or
// self-intersecting outline, fewer than 3 vertices, crossing after resampling).
PieceMesh mesh_piece(const pattern::Piece& piece, const MeshOptions& options, Diagnostics& diag);

// Meshes every piece of one size (empty = the style's sample size, else its first
// size). Pieces that are open or self-intersecting are skipped with a warning;
// pieces that fail are reported as errors in `diag`; the rest are returned in file
// order. This is the unit a benchmark should time.
std::vector<PieceMesh> mesh_style(const pattern::Style& style, const std::string& size,
                                  const MeshOptions& options, Diagnostics& diag);

// ---- material frame ---------------------------------------------------------------

// Frame of a piece: warp along its grain line (+x when it has none).
MaterialFrame material_frame(const pattern::Piece& piece);
// (warp, weft) coordinates of a pattern point, m.
Vec2 to_material(const MaterialFrame& frame, const Vec2& p);
// to_material of every node.
std::vector<Vec2> material_coordinates(const PieceMesh& mesh);

// A point strictly inside a simple polygon (either orientation), e.g. a hole seed
// for Triangle's .poly files. Found on a horizontal line through the polygon.
Vec2 interior_point(const std::vector<Vec2>& polygon);

}  // namespace vgd::mesh
