#pragma once
// Building a scene: SceneDef -> sim::Model + exactly the effects the scene
// lists -> sim::System, with the integrator and run settings it asks for.
//
//   model    every piece's particles and triangles: grids as make_grid lays
//            them, XVC pieces meshed (mesh::mesh_piece) in their pattern
//            coordinates and laid flat (Placement); rest shape = material
//            (warp, weft) coordinates; masses = particle_mass (mass-spring)
//            or lumped triangle area x density;
//   effects  the cloth models of the pieces (mass-spring, strain-rosette,
//            bending), then gravity, viscosity, damping, wind and one pins
//            effect per pin group, in that order, each only when listed.
#include <memory>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/scene/avatar.hpp"
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
  std::optional<Avatar> avatar;         // the scene's body, when it has one
  std::vector<sim::SeamPairs> seams;    // every seam's particle pairs (global indices)
};

// The scene's body as AvatarDef says: the mannequin generated, the file
// imported, or the solid built. Throws vgd::Error naming the scene file and
// the field for anything wrong.
Avatar build_avatar(const SceneDef& def);

// The particles of a model the scene has not built effects for yet: pieces
// and the model, as build() makes them. Throws vgd::Error like build().
// Garments are dressed on `avatar` (required when the scene has one) and their
// seams' particle pairs appended to `seams` (when given).
sim::Model build_model(const SceneDef& def, std::vector<PieceInfo>& pieces, Diagnostics& diag,
                       const Avatar* avatar = nullptr, std::vector<sim::SeamPairs>* seams = nullptr);

// The particles a pin group names (global indices, sorted, unique). `path` is
// the group's JSON path for messages (e.g. "effects.pins[0]"). Throws
// vgd::Error for an unknown piece or set, an index out of range, or a group
// that names no particle.
std::vector<int> pin_particles(const SceneDef& def, const sim::Model& model, const std::vector<PieceInfo>& pieces,
                               const PinGroupDef& group, const std::string& path);

// validate()s, reads the XVC files and materials, meshes, and builds the
// system. Throws vgd::Error naming the scene file and the field's JSON path
// (or the XVC file and element) for anything wrong.
Scene build(const SceneDef& def);

// Names of the effects build() constructs for `def`, in order (what
// System::profile will list).
std::vector<std::string> effect_names(const SceneDef& def);

}  // namespace vgd::scene
