#pragma once
// Dressing: where each assembled garment piece starts in 3-D. Every piece is
// wrapped round the avatar where its arrangement says (POSITION
// type="arrangement" in its PATTERN, docs/xvc.md), or, when it has none, where
// vgd suggests from its name (xvc/arrangement.hpp). scene/placement.hpp does
// the geometry.
#include <map>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/scene/avatar.hpp"
#include "vgd/scene/garment.hpp"
#include "vgd/scene/placement.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::scene {

struct PlacedPiece {
  std::vector<Vec3> positions;  // per mesh node, m, world frame
  bool flipped = false;         // the placement mirrored the piece: its triangles must be reversed
  std::string arrangement;      // how it was placed, for reports ("torso front 1.25 m, 30 mm clear, suggested")
  std::string segment;          // the body segment it was placed on (for garments worn over it)
};

// Every PATTERN's arrangements: those stored in the document, else vgd's
// suggestions from the piece's name, with heights taken from the avatar (its
// landmarks for a mannequin; its torso for another body). Patterns for which
// no rule fits are missing from the map.
std::map<std::string, std::vector<xvc::Arrangement>> garment_arrangements(const xvc::Document& doc,
                                                                         const Avatar& avatar, Diagnostics& diag);

// One PlacedPiece per garment piece, in order: piece k of a pattern takes the
// pattern's k-th arrangement. Throws vgd::Error naming the document and the
// PATTERN when a piece has no arrangement, or names a segment the avatar lacks.
// `under`: the cloth of garments already placed that this one is worn over.
std::vector<PlacedPiece> place_garment(const xvc::Document& doc, const Garment& garment,
                                       const std::map<std::string, std::vector<xvc::Arrangement>>& arrangements,
                                       const Avatar& avatar, const std::vector<Underlayer>& under = {});

}  // namespace vgd::scene
