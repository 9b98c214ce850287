#pragma once
// Contour resampling (seed 002 §2, E-Fabric): even out the vertices of a piece's
// outline before meshing, so the triangles along it have one size.
//
// The closed contour is cut into sides at its corners — every AAMA turn point, every
// vertex where the direction turns by more than `turn_angle_deg`, and every vertex
// the caller asks to keep — and new points are spread evenly by arc length along
// each side.
//
// Guarantees (units: metres, degrees):
//   - side end points are copied bit for bit with their kind (a turn stays a turn);
//   - every new point lies on the input polyline, so a polygon keeps its perimeter
//     and its straight sides stay straight;
//   - along a side, points are equally spaced in arc length (to rounding), at most
//     `spacing_m` apart;
//   - the orientation of the input is kept (CCW in, CCW out) and no two neighbouring
//     points are equal.
#include <vector>

#include "vgd/pattern/piece.hpp"

namespace vgd::pattern {

struct ResampleOptions {
  // Largest arc-length distance between neighbouring points of a side, m. Typical
  // 0.005–0.02; E-Fabric meshed garments at about 1 cm. Each side gets
  // ceil(length / spacing_m) segments. Must be > 0 unless segments_per_side is set.
  double spacing_m = 0.01;
  // A vertex where the contour turns by more than this starts a new side, degrees in
  // [0, 180]. E-Fabric used 30. AAMA turn points split whatever this is.
  double turn_angle_deg = 30.0;
  // When > 0, every side is cut into exactly this many equal segments (E-Fabric's
  // "number of new points is a parameter") and spacing_m is ignored.
  int segments_per_side = 0;
  // resample_piece only: keep the boundary vertex of every notch (Notch::boundary_index)
  // as a side end, so the notch still sits on a vertex for seam matching.
  bool keep_notch_vertices = true;
};

// One closed contour after resampling, with where each point came from.
struct ResampledContour {
  std::vector<ContourPoint> points;  // closed (last joins first), input orientation
  std::vector<int> side;             // per point i: side holding the edge points[i] -> points[i+1]
  std::vector<int> source;           // per point: input vertex kept exactly here, -1 for a new point
  int side_count = 0;
};

// Resamples one closed contour. `keep` lists input vertex indices that must stay
// (they become side ends). Exact duplicate neighbours in the input are merged first
// (a merged turn point stays a turn). A contour with fewer than 3 distinct points is
// returned as it is, as one side. New points are `curve` when their side holds curve
// points, else `plain`. The output has at least 3 points when the input has.
ResampledContour resample_contour(const std::vector<ContourPoint>& contour, const ResampleOptions& options = {},
                                  const std::vector<int>& keep = {});

// The same for a plain closed polygon (cutouts carry no point kinds).
std::vector<Vec2> resample_polygon(const std::vector<Vec2>& polygon, const ResampleOptions& options = {});

// Resamples a piece's boundary and its closed cutouts (open ones are copied), and
// re-points every notch's boundary_index at its vertex in the new boundary.
// Everything else is copied unchanged.
Piece resample_piece(const Piece& piece, const ResampleOptions& options = {});

}  // namespace vgd::pattern
