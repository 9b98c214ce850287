#pragma once
// Building clean closed outlines from what CAD files contain.
//
// Real exports split a piece's boundary into several open polylines, repeat
// vertices, repeat the first vertex at the end, and wind either way
// (shared/data/dxf/README.md). These functions turn such parts into one
// counter-clockwise outline and say what they had to do. Units: metres.
#include <optional>
#include <vector>

#include "vgd/pattern/piece.hpp"

namespace vgd::pattern {

// Outcome of chaining open parts into one outline.
struct ChainResult {
  std::vector<Vec2> outline;  // chained vertices, first vertex not repeated at the end
  bool closed = false;        // the chain returned to its start
  double closing_gap_m = 0.0; // distance between the chain's ends before closing
  int parts_used = 0;
  int parts_duplicate = 0;    // parts identical to another part (dropped)
  int parts_unused = 0;       // parts that could not be joined to the chain
  int joins_bridged = 0;      // joins made across a gap larger than join_tol_m
  double largest_bridge_m = 0.0;
};

struct ChainOptions {
  double join_tol_m = 1e-6;     // end points closer than this are the same point (1 µm)
  double repair_gap_m = 1e-3;   // gaps up to this are bridged (and reported); 1 mm
};

// Chains open polylines end to end, reversing parts as needed. Parts repeated
// point for point (same direction) are dropped as duplicates. Starts with the
// longest part so that a stray fragment cannot become the seed of the chain.
ChainResult chain_parts(std::vector<std::vector<Vec2>> parts, const ChainOptions& opts = {});

// Removes consecutive vertices closer than tol_m (and a last vertex equal to the
// first). Kinds are merged: a turn point wins over curve over plain. Returns the
// number of vertices removed.
int remove_duplicate_vertices(std::vector<ContourPoint>& outline, double tol_m = 1e-6);

// Removes zero-width spikes: an outline that goes out to a point and straight
// back (a slit drawn into the boundary) cannot be meshed. Returns the number removed.
int remove_spikes(std::vector<ContourPoint>& outline, double tol_m = 1e-6);

// Marks the outline's corners as turn points, for files that mark none
// (Valentina): a vertex where the direction over the `window` of arc
// before it and that after it differ by `min_angle_deg` or more, and by more
// than at any vertex within `window` of it (one corner per sharp turn, not
// every vertex of a tight curve). Polylines' vertices of real files are
// 1–20 mm apart on curves; a 30° turn within 5 mm each way is a corner a
// pattern maker drew. Returns the number of turn points set.
int mark_corners(std::vector<ContourPoint>& outline, double min_angle_deg = 30.0, double window_m = 0.005);

// Reverses the outline if it winds clockwise. Returns true when it reversed.
bool make_counter_clockwise(std::vector<ContourPoint>& outline);

// Even-odd test: whether `p` lies inside the closed outline.
bool point_in_outline(const std::vector<ContourPoint>& outline, const Vec2& p);

// Whether the outline is its own mirror image across the line along `up`
// through the middle of its extent across `up`: every vertex reflected lies
// within `tol_m` of the outline (a whole piece with straight sides, not a half).
bool mirror_symmetric(const std::vector<ContourPoint>& outline, const Vec2& up, double tol_m);

// Index of the vertex nearest to p, and its distance; {-1, inf} for an empty outline.
struct Nearest {
  int index = -1;
  double distance = 0.0;
};
Nearest nearest_vertex(const std::vector<ContourPoint>& outline, const Vec2& p);
// Nearest point on the outline's edges: edge index i (from vertex i to i+1) and distance.
struct NearestEdge {
  int edge = -1;
  double t = 0.0;       // parameter along the edge in [0, 1]
  double distance = 0.0;
  Vec2 point = Vec2::Zero();
};
NearestEdge nearest_edge(const std::vector<ContourPoint>& outline, const Vec2& p);

// Unfolds a half piece about its mirror (fold) line: the outline's side of the
// line is reflected and joined, notches, internal lines, drill holes and sew
// lines are mirrored too. Both fold-line ends must be boundary vertices (within
// tol_m); returns false (and leaves the piece unchanged) when they are not.
bool unfold_about_mirror_line(Piece& piece, double tol_m = 1e-4);

// Sews a piece on its sew line: a piece with exactly one closed sew line
// (ASTM layer 14) of at least 3 points lying inside its outline, no point of
// it nearer the outline than `min_m` nor farther than `max_m`, takes the sew
// line as its outline (counter-clockwise; the cut line's turn points at the
// sew line's nearest vertices, or where the cut line has none, corners marked
// from its shape as mark_corners does), its notches moved onto it; the seam allowance is cut
// off. Returns the allowance's range (m, nearest and farthest point of the
// sew line from the cut line), nothing when the piece has no such sew line
// (the piece is then unchanged).
struct Allowance {
  double min = 0.0, max = 0.0;
};
std::optional<Allowance> sew_on_sew_line(Piece& piece, double min_m = 0.002, double max_m = 0.08);

// Removes small loops where the outline crosses itself (a typical defect of
// graded sizes): each crossing of two edges that encloses at most
// max_loop_fraction of the piece area is cut at the crossing point.
// Returns the number of loops removed; the outline stays counter-clockwise.
int remove_small_self_loops(std::vector<ContourPoint>& outline, double max_loop_fraction = 0.05);

// The outline's width across `up` (unit) at height `v` along it: between its
// outermost crossings of that line (m), 0 where it does not reach.
double width_at(const std::vector<ContourPoint>& outline, const Vec2& up, double v);

// The outline's widths across `up` (unit) among its vertices in its bottom 15 %
// and its top 15 % along `up`, and its length along `up` (m).
struct EndWidths {
  double bottom = 0, top = 0, length = 0;
};
EndWidths end_widths(const std::vector<ContourPoint>& outline, const Vec2& up);

// Whether the outline is wider at its top end than at its bottom one
// (end_widths): a leg's waist end against its hem.
bool wider_at_top(const std::vector<ContourPoint>& outline, const Vec2& up);

// A line or an outline drawn by clicks, smoothed: `points` (m) with their
// kinds, `turn` a corner and `curve` a point a smooth curve passes through.
// Between two corners the line is straight; a run with curve points is a
// centripetal Catmull-Rom spline through its points (at a corner it starts
// or ends heading for its neighbour), sampled so that no piece of a curved
// part is longer than `spacing` (m); a straight side stays one edge. Every clicked point is kept, with its kind;
// the samples between are `curve`. `closed`: the last point joins the
// first. Fewer than two points come back as they are.
std::vector<ContourPoint> smooth_through(const std::vector<ContourPoint>& points, bool closed, double spacing = 0.005);

}  // namespace vgd::pattern
