#pragma once
// Building a scene: SceneDef -> sim::Model + exactly the effects the scene
// lists -> sim::System, with the integrator and run settings it asks for.
//
//   model    every piece's particles and triangles: grids as make_grid lays
//            them, XVC pieces meshed (mesh::mesh_piece) in their pattern
//            coordinates and laid flat (Placement), garments as the dress
//            stage made them (MadeCloth: assembled and placed round the
//            body); rest shape = material (warp, weft) coordinates; masses =
//            particle_mass (mass-spring) or lumped triangle area x density;
//   effects  the cloth models of the pieces (mass-spring, strain-rosette,
//            bending), then gravity, viscosity, damping, wind and one pins
//            effect per pin group, in that order, each only when listed.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/body/avatar.hpp"
#include "vgd/scene/scene.hpp"
#include "vgd/sim/system.hpp"

namespace vgd::scene {

// One piece of the model: a range of particles and what it was made from.
struct PieceInfo {
  std::string name;            // grid: the cloth's name; XVC: the block name
  int cloth = 0;               // index in SceneDef::cloth
  int first = 0, count = 0;    // particles [first, first + count)
  int first_triangle = 0, triangles = 0;
  int nu = 0, nv = 0;          // grid: particles along u and v; 0 for meshed pieces
  ClothModel model = ClothModel::mass_spring;
  MaterialDef material;
  std::string segment;         // made cloth: the body segment it was placed on ("" otherwise)
  double raised = 0.0;         // made cloth: m its garment was placed higher than arranged (MadePiece::raised)
  int face_layer = 0;          // made cloth: MadePiece::face_layer
};

// A scene ready to run.
struct Scene {
  std::string name;
  std::unique_ptr<sim::System> system;
  sim::IntegratorSettings integrator;   // settings.step is the effective step
  sim::RunSettings run;
  std::vector<OutputDef> outputs;
  std::vector<PieceInfo> pieces;
  std::vector<int> pinned;              // every pinned particle, sorted
  Diagnostics diagnostics;              // meshing warnings
  std::optional<body::Avatar> avatar;   // the scene's body, when it has one
  std::vector<sim::SeamPairs> seams;    // every seam's particle pairs (global indices)
};

// The scene's body as AvatarDef says: the mannequin generated, the file
// imported, or the solid built. Throws vgd::Error naming the scene file and
// the field for anything wrong.
body::Avatar build_avatar(const SceneDef& def);

// The pieces of one cloth entry made outside this stage: a garment (GarmentDef)
// assembled and placed round the body by the dress stage (dress::build). Each
// piece's model holds x0 (world frame, m), v0, uv and triangles; build() sets
// the masses from the cloth's material. Seams pair particles of the entry,
// numbered from its first piece's first particle (pieces in order).
struct MadePiece {
  std::string name;
  sim::Model model;
  std::string segment;  // the body segment it was placed on (PieceInfo::segment)
  // The MATERIAL id, in the cloth's garment document, the piece is cut from
  // when it names its own (xvc::piece_material); "" = the cloth's material.
  std::string material;
  // Layers of that fabric it hangs as (a rib cut double and folded: 2); its
  // mass and stiffnesses are the fabric's times this (scene::layered).
  int layers = 1;
  std::string pattern;  // the PATTERN it was cut from, in its garment document
  int copy = 0;         // which copy of that pattern (its arrangement's index)
  // The particles (of this piece) its document's pins hold where they were
  // placed (xvc::Pin), each with its POSITION's id: held there by a pin
  // group of their own.
  std::vector<std::pair<int, std::string>> pinned;
  // m: how much higher than arranged its garment was placed (a garment that
  // reaches the body's soles, dress::place_garment); 0 mostly.
  double raised = 0.0;
  // Sewn onto another piece's face, this many faces out (a pocket 1, a flap
  // over it 2; dress::GarmentPiece::face_layer): a layer of its own over
  // its garment's, in the order the self-collision keeps. 0 mostly.
  int face_layer = 0;
};
struct MadeCloth {
  std::vector<MadePiece> pieces;
  std::vector<sim::SeamPairs> seams;  // particle indices within the cloth; `after` indices into this list
  Diagnostics diagnostics;  // warnings made while making the pieces
};
using MadeCloths = std::map<int, MadeCloth>;  // by index in SceneDef::cloth

// `p` from the scene file: a relative path is relative to the scene file's folder.
std::filesystem::path resolve_path(const SceneDef& def, const std::filesystem::path& p);

// The particles of a model the scene has not built effects for yet: pieces
// and the model, as build() makes them. Throws vgd::Error like build(), and
// for a garment entry that `made` lacks. Made cloths' seams are appended to
// `seams` (when given) as global particle pairs.
sim::Model build_model(const SceneDef& def, std::vector<PieceInfo>& pieces, Diagnostics& diag,
                       const MadeCloths& made = {}, std::vector<sim::SeamPairs>* seams = nullptr);

// The particles a pin group names (global indices, sorted, unique). `path` is
// the group's JSON path for messages (e.g. "effects.pins[0]"). Throws
// vgd::Error for an unknown piece or set, an index out of range, or a group
// that names no particle.
std::vector<int> pin_particles(const SceneDef& def, const sim::Model& model, const std::vector<PieceInfo>& pieces,
                               const PinGroupDef& group, const std::string& path);

// validate()s, reads the XVC files and materials, meshes, and builds the
// system. Throws vgd::Error naming the scene file and the field's JSON path
// (or the XVC file and element) for anything wrong. A scene with garments is
// built by dress::build, which dresses them on the body and calls the second
// form; the first refuses a garment entry.
Scene build(const SceneDef& def);
// The same with the body already built (def.avatar's) and the made cloths.
Scene build(const SceneDef& def, std::optional<body::Avatar> avatar, const MadeCloths& made);

// Names of the effects build() constructs for `def`, in order (what
// System::profile will list).
std::vector<std::string> effect_names(const SceneDef& def);

}  // namespace vgd::scene
