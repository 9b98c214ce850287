#pragma once
// Dressing: where each assembled garment piece starts in 3-D. Every piece is
// wrapped round the avatar where its arrangement says (POSITION
// type="arrangement" in its PATTERN, docs/xvc.md), or, when it has none, where
// vgd suggests from its name (xvc/arrangement.hpp). dress/placement.hpp does
// the geometry.
//
// A scene with garments (scene::GarmentDef entries) is built here: the body
// first, then every garment assembled and placed round it in layer order
// (dress_garments), then scene::build with the made pieces.
#include <map>
#include <string>
#include <vector>

#include "vgd/body/avatar.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/dress/garment.hpp"
#include "vgd/dress/placement.hpp"
#include "vgd/scene/build.hpp"
#include "vgd/scene/scene.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::dress {

struct PlacedPiece {
  std::vector<body::Vec3> positions;  // per mesh node, m, world frame
  bool flipped = false;         // the placement mirrored the piece: its triangles must be reversed
  std::string arrangement;      // how it was placed, for reports ("torso front 1.25 m, 30 mm clear, suggested")
  std::string segment;          // the body segment it was placed on (for garments worn over it)
  // m: how much higher than its arrangement says the whole garment was placed
  // so that it starts above the body's soles (place_garment); 0 mostly.
  double lifted = 0.0;
  // m: the lift the garment needed when that was more than place_garment
  // raises one (it was raised by `lifted`, the most); 0 mostly.
  double too_long = 0.0;
};

// Every PATTERN's arrangements: those stored in the document, else vgd's
// suggestions from the piece's name, with heights taken from the avatar (its
// landmarks for a mannequin; its torso for another body). Patterns for which
// no rule fits are missing from the map (place_garment then refuses a piece
// of theirs that is draped, naming it and saying how to place it).
std::map<std::string, std::vector<xvc::Arrangement>> garment_arrangements(const xvc::Document& doc,
                                                                         const body::Avatar& avatar);

// One PlacedPiece per garment piece, in order: piece k of a pattern takes the
// pattern's k-th arrangement. Throws vgd::Error naming the document and the
// PATTERN when a piece has no arrangement, or names a segment the avatar lacks.
// `under`: the cloth of garments already placed that this one is worn over.
// A garment that would start below the body's soles or within kAboveSoles of
// them (trousers cut to the floor, wrapped round the feet) is placed higher as
// a whole, every piece by the same height, until its lowest point is
// kAboveSoles above them: it falls back to its length under gravity, its hems
// closed round the ankles instead of held open by the feet. By at most
// kMostOfTheFeet times the feet's height (the ankles above the soles): a
// garment that needs more is raised that much and its pieces say what it
// needed (too_long; docs/placement.md, "Feet").
constexpr double kAboveSoles = 0.05;     // m
constexpr double kMostOfTheFeet = 0.75;  // of the ankles' height above the soles
std::vector<PlacedPiece> place_garment(const xvc::Document& doc, const Garment& garment,
                                       const std::map<std::string, std::vector<xvc::Arrangement>>& arrangements,
                                       const body::Avatar& avatar, const std::vector<Underlayer>& under = {},
                                       double nest = 0.0);

// Every garment entry of `def` assembled (dress/garment.hpp) and placed round
// `avatar`, keyed by its index in def.cloth. Garments are taken in cloth
// order; each is placed outside the cloth of those before it with a lower
// layer (Underlayer). With more than one
// garment a piece's name is "<cloth name>/<block>". Throws vgd::Error naming
// the scene file and the field (a missing document) or the document and the
// element (a piece that cannot be assembled or placed).
scene::MadeCloths dress_garments(const scene::SceneDef& def, const body::Avatar& avatar);

// Whether a garment of size `size` fits `avatar`: the size's body
// measurements in the shipped tables (the women's, then the men's, then
// ASTM's; nothing when no table has the label) against the body's own (a
// mannequin's, or those measured on an imported body). A warning per girth
// the garment covers (its pieces on the torso: bust and waist; on the hips:
// waist and hip) that its size is more than 4 cm too small or 12 cm too
// large for, with both figures, named after the document. `table`: the size
// table the garment's size is read in (the mannequin's); "" = the default order.
void check_fit(const std::string& document, const std::string& size, const std::vector<std::string>& segments,
               const body::Avatar& avatar, Diagnostics& diag, const std::string& table = "");

// scene::build for any scene: the body built once, the garments dressed on
// it, then the scene built with them.
scene::Scene build(const scene::SceneDef& def);

}  // namespace vgd::dress
