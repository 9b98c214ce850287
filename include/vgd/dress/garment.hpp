#pragma once
// Garment assembly: an XVC document with seams -> meshed pieces whose seam
// hems carry the same number of vertices, and the seams as particle pairs
// (seed 002 §2–3: E-Fabric picked "the same number of vertexes from two of the
// patterns"; vgd makes the mesher do it).
//
// Each PATTERN of the chosen size gives one piece per arrangement it holds
// (POSITION type="arrangement": a sleeve cut twice is placed on both arms),
// at least one. A HEM sewn again (the same stretches in a later SEAM) goes to
// the pattern's next copy, so the right and left armhole seams each get their
// own sleeve. Its outline is
// cut into sides at every corner (turn points and turns sharper than the
// resampling angle), every notch vertex and every hem end. A side that is no
// hem gets ceil(length / spacing) equal segments. The hems of one seam share
// n = ceil(max(length_a, length_b) / spacing) segments, spread over each hem
// by arc length, so the k-th vertex of one hem is sewn to the k-th vertex of
// the other: positions along the two hems are proportional (their ease is
// spread evenly). Corners inside a hem are not kept (the hem is resampled as
// one curve). The boundary is then meshed without Steiner points on it
// (mesh::MeshOptions::split_boundary = false) so the pairing survives.
//
// A SEAM with more than two HEMs sews its first HEM to the others taken in
// document order one after the other (a sleeve cap to the front and back
// armholes). A piece sewn onto another's face (POSITION type="placement",
// xvc::FacePlacement: a patch pocket) is sewn along its outline but its
// mouth (a pocket flap: along its top edge only; a placket: by its two ends,
// a seam each) to a line of the host's mesh where that outline lies on it,
// vertex to vertex (a seam named "POCKET on FRONT"). Units: metres.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/mesh/mesh.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::dress {

struct AssemblyOptions {
  std::string size;           // "" = the document's sample size, else its first size
  double spacing = 0.0;       // m between boundary vertices; 0 = the document's mesh.spacing, else 0.015
  double min_angle = 0.0;     // deg; 0 = the document's mesh.min_angle, else 25
  std::vector<std::string> pieces;  // piece or block names to keep; empty = every pattern of the size
  // PATTERN id -> pieces to make of it; a pattern not listed gets one per
  // arrangement it stores, at least one.
  std::map<std::string, int> copies;
  // PATTERN id -> per copy: placed flipped (cut face down). A HEM's direction
  // runs along the pattern's contour laid face up; on a flipped copy that
  // contour runs the other way round the body, so its hems are sewn in the
  // opposite direction (docs/xvc.md, "SEAM suggestions").
  std::map<std::string, std::vector<bool>> flipped;
  // Where copy `copy` of PATTERN `pattern_id` puts 2-D pattern points round
  // the body (m, one per point; empty when it cannot say). Given, it decides
  // which copy of a piece cut more than once each seam sews (the one whose
  // hem lies nearest the seam's other pieces); unset, copies are taken in
  // the order of the SEAMs.
  std::function<std::vector<Eigen::Vector3d>(const std::string& pattern_id, int copy,
                                             const std::vector<pattern::Vec2>& points)>
      place;
};

struct GarmentPiece {
  std::string pattern_id;  // the PATTERN's id in the document
  int copy = 0;            // which of the pattern's arrangements (0-based)
  std::string name;        // piece name (block name when the piece has none)
  pattern::Piece piece;    // the piece as meshed (resampled outline; a folded piece's half)
  // Layers of fabric it hangs as: 2 for a piece cut double and folded
  // lengthwise (PATTERN folded="true": the half beside the longest edge a
  // seam sews, pattern::fold_lengthwise), else 1.
  int layers = 1;
  mesh::PieceMesh mesh;    // nodes in pattern coordinates
  // A piece sewn onto another's face (a patch pocket, xvc::FacePlacement):
  // that piece's index, and where this piece's pattern points lie in that
  // piece's pattern frame (on_host). -1: a piece of its own.
  int host = -1;
  Eigen::Matrix2d to_host_rotation = Eigen::Matrix2d::Identity();
  pattern::Vec2 to_host_from = pattern::Vec2::Zero(), to_host_at = pattern::Vec2::Zero();
  pattern::Vec2 on_host(const pattern::Vec2& p) const { return to_host_rotation * (p - to_host_from) + to_host_at; }
  double face_gap = 0.0;  // m: how far outside the host's face it starts
  // Faces out from its host's (1 a pocket, 2 a flap over a pocket): the
  // self-collision keeps it on the outside of the pieces below (layers).
  int face_layer = 0;
};

// A vertex of one piece's mesh.
struct PieceNode {
  int piece = -1;  // index in Garment::pieces
  int node = -1;   // node of that piece's mesh
  bool operator==(const PieceNode&) const = default;
};

struct GarmentSeam {
  std::string id, name;                      // the SEAM's id and name
  std::vector<std::array<PieceNode, 2>> pairs;  // sewn together, in sewing order
  double length_a = 0.0, length_b = 0.0;     // m: first hem, and the others together
};

struct Garment {
  std::string name;
  std::string size;
  std::vector<GarmentPiece> pieces;
  std::vector<GarmentSeam> seams;  // seams whose hems all lie on kept pieces
};

// Assembles the garment. Throws vgd::Error naming the document and the element
// (SEAM, HEM or PATTERN id) for hems that overlap, a HEM on a pattern of
// another size, or a piece that cannot be meshed. Seams touching a piece left
// out by options.pieces are skipped with a warning in `diag`.
Garment assemble_garment(const xvc::Document& doc, const AssemblyOptions& options, Diagnostics& diag);

}  // namespace vgd::dress
