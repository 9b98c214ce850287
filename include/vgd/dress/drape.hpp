#pragma once
// Draping a garment on a body, end to end (docs/drape.md):
//
//   placing   the garment document assembled (seam hems with equal vertex
//             counts), meshed, each piece wrapped round the avatar;
//   sewing    seams pull their pairs together and merge them, the cloth
//             collides with the body (and itself when asked);
//   settling  the garment hangs until the mean kinetic energy per particle
//             stays below a threshold for a number of frames (rest), or the
//             time limit is reached.
//
// A drape is a scene (scene.hpp): drape_scene() writes the SceneDef the
// options describe, so what `vgd drape` runs can be saved and rerun with
// `vgd simulate`. run_drape() builds it, runs it with rest detection, and
// measures the certificate (certificate.hpp).
#include <filesystem>
#include <functional>
#include <string>

#include "vgd/scene/build.hpp"
#include "vgd/dress/certificate.hpp"
#include "vgd/scene/scene.hpp"

namespace vgd::dress {

struct DrapeOptions {
  std::filesystem::path garment;         // the XVC document (with SEAMs)
  // Garments worn over it, in order (layer 1, 2, ...: each starts 15 mm
  // further out), each with its own MATERIAL or vgd's shirting; same size.
  std::vector<std::filesystem::path> over;
  std::string size;                      // "" = the document's sample size
  std::vector<std::string> pieces;       // piece or block names to sew; empty = all of the size
  std::optional<scene::AvatarDef> avatar;       // empty = the mannequin of the garment's size (else 38)
  std::string mannequin_table;           // size table of that mannequin; "" = the default search order
  std::filesystem::path material_xvc;    // "" = the garment's own MATERIAL if it has one, else data/materials/shirting.xvc
  std::string material_id;               // MATERIAL id in material_xvc; "" = its first
  double spacing = 0.0;                  // m; 0 = the document's mesh.spacing, else 0.015
  // The cloth model of every garment: the mass-spring (the default: measured
  // on every shared garment, docs/drape.md) or the strain rosette (seed 002's
  // orthotropic membrane with bending; slower, docs/fabric-model.md).
  scene::ClothModel model = scene::ClothModel::mass_spring;
  bool self_collision = true;  // cloth kept from passing through cloth (docs/drape.md)
  double repulsion_damping = 0.0;  // SelfCollisionDef::damping: fraction of critical (0 = none)
  // The body kept out of the cloth between particles as well (sharp body
  // parts and the cloth's edge midpoints and triangle centres;
  // docs/collisions.md, "Between particles"). Off, a crotch or a heel shows
  // through the cloth between particles that all stay outside the body.
  bool between_particles = true;
  // sim::IntegratorSettings::hold_contacts_once_sewn (false: the corrections
  // after each step alone keep touching cloth out of the body).
  bool hold_contacts_once_sewn = false;
  // Offset contact instead of the body collision and self-collision: no
  // cloth through the body or through cloth at the end of any step
  // (docs/collisions.md, "Offset contact").
  bool offset_contact = false;
  // Each sleeve sewn into a tube round its arm before its cap is pulled to
  // the armhole (docs/seams.md, "Order"): drapes on arms swung forward need
  // it; off by default, it changes which drapes pass elsewhere.
  bool sleeves_first = false;
  double time_limit = 8.0;               // s of simulated time
  // J: mean kinetic energy per particle counted as rest (~1.5 cm/s at 40 mg);
  // the preview preset stops at 10 times it (~5 cm/s): sooner, less settled.
  double rest_energy = 5e-9;
  int rest_frames = 10;                  // consecutive frames below it
  double fps = 25.0;
  scene::Quality quality = scene::Quality::standard;   // implicit Euler at 2 / 4 / 8 steps per frame (quality.hpp)
};

// The fabric a garment's pieces without their own are cut from (a piece
// naming a MATERIAL of its own is cut from that: xvc::piece_material):
// `material_xvc` (its `material_id`, else its first MATERIAL) when given, else
// the document's own (xvc::garment_material, in `garment_file`), else vgd's
// shirting. garment_fabric_of reads it, the document's own from `garment`
// itself. Throw vgd::Error naming the file for a fabric that cannot be read.
scene::MaterialSource garment_fabric(const xvc::Document& garment, const std::filesystem::path& garment_file,
                                     const std::filesystem::path& material_xvc = {},
                                     const std::string& material_id = {});
scene::MaterialDef garment_fabric_of(const xvc::Document& garment, const std::filesystem::path& garment_file,
                                     const std::filesystem::path& material_xvc = {},
                                     const std::string& material_id = {});

// The scene the options describe (materials resolved to files, not read yet).
// Throws vgd::Error for options that cannot make one (no such file, ...).
scene::SceneDef drape_scene(const DrapeOptions& options);

struct DrapeStageProgress {
  std::string stage;      // placing, sewing, settling
  double t = 0.0;         // s simulated
  double time_limit = 0.0;
  double wall_s = 0.0;
  int seams_closed = 0, seam_pairs = 0;
  double kinetic_energy = 0.0;  // J per particle
  // The scene as built, on the placing event only (null on the others): its
  // diagnostics (a garment too small for the body, meshing warnings) and the
  // body's import notes can be shown before the run.
  const scene::Scene* scene = nullptr;
  int seams_waiting = 0;  // seams that wait for others before they pull (sleeves first)
};

struct DrapeResult {
  scene::Scene scene;                 // as built (the system holds the final merges)
  sim::State state;            // final, reduced
  sim::VecX positions;         // final positions of every original particle (3N, m)
  Certificate certificate;
  sim::RunSummary summary;
};

// Builds and runs a drape scene, frames to `sinks`. Never throws for a run
// that fails mid-way: the certificate then says "error" and why. Throws
// vgd::Error for a scene that cannot be built.
DrapeResult run_drape(const scene::SceneDef& def, const std::vector<sim::FrameSink*>& sinks,
                      const std::function<void(const DrapeStageProgress&)>& progress = {});

}  // namespace vgd::dress
