#pragma once
// A scene: everything a simulation needs and nothing it does not (docs/scene.md).
//
//   cloth pieces (a regular grid like seed 000's flag, or pieces of an XVC
//   document laid flat in a plane), each with its material and cloth model;
//   the effects the scene calls for, with their parameters; the integrator and
//   its settings; the frame rate and duration; where frames go.
//
// Def structs have defaults and are checked when used (validate(), build()):
// a problem is thrown as vgd::Error naming the scene file, the path of the
// field as the JSON file spells it (e.g. `effects.wind.velocity`) and what is
// wrong. Units: SI (m, kg, s, N) throughout; the JSON reader (json.hpp)
// converts quantities written with units.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "vgd/body/avatar.hpp"
#include "vgd/scene/material.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/body_collision.hpp"
#include "vgd/sim/effects/contact.hpp"
#include "vgd/sim/effects/hand.hpp"
#include "vgd/sim/effects/seam.hpp"
#include "vgd/sim/effects/self_collision.hpp"
#include "vgd/sim/integrator.hpp"
#include "vgd/sim/run.hpp"

namespace vgd::scene {

using sim::Vec3;

// ---- cloth --------------------------------------------------------------------

enum class ClothModel {
  mass_spring,     // seed 000 §4.1: springs along warp, weft, bias; bending springs (sim/effects/mass_spring.hpp)
  strain_rosette,  // continuum triangles measuring strain along warp, weft and bias, plus beam bending
};
const char* to_string(ClothModel m);
// "mass-spring", "strain-rosette"; throws std::invalid_argument.
ClothModel parse_cloth_model(const std::string& s);
// True when this build has the model's effects (false: choosing it is refused).
bool model_available(ClothModel m);

// A regular grid of particles (seed 000's Garment PROTO: warp × weft particles).
// Particle (i, j), i along u (the warp), j along v (the weft), has index j·nu + i
// within its piece.
struct GridDef {
  int nu = 30, nv = 30;  // particles along u and v, each ≥ 2
  double width = 1.0;    // m, extent along u (particle spacing width/(nu-1))
  double height = 1.0;   // m, extent along v
};

// How pieces of an XVC document are laid in the plane (placement below).
enum class Layout {
  row,  // side by side along u, in document order, `gap` apart, each piece's lowest-left corner on the row
  own,  // the pattern's own coordinates (pieces as the CAD system placed them)
};

// Pieces of an XVC document, meshed (mesh::mesh_piece) and laid flat.
struct XvcPiecesDef {
  std::filesystem::path file;       // XVC document; a relative path is relative to the scene file's folder
  std::string size;                 // "" = the sample size, else the first size
  std::vector<std::string> pieces;  // piece or block names; empty = every piece of the size
  double spacing = 0.0;             // m, mesh spacing; 0 = the document's mesh.spacing, else 0.01
  double min_angle = 0.0;           // deg; 0 = the document's mesh.min_angle, else 25
  Layout layout = Layout::row;
  double gap = 0.05;                // m between pieces in a row
};

// Where a piece lies in 3-D: grid/pattern point (a, b) (m) goes to
// origin + a·u + b·v. u and v are normalised; v is made orthogonal to u.
struct Placement {
  Vec3 origin = Vec3::Zero();  // m
  Vec3 u = Vec3::UnitX();      // grid u (warp) / pattern x, in the world (+Y up)
  Vec3 v = Vec3::UnitY();      // grid v (weft) / pattern y
};

// A garment of an XVC document dressed on the scene's avatar: assembled
// (scene/garment.hpp: hems of a seam get equal vertex counts), each piece
// wrapped round the body where its arrangement (POSITION type="arrangement")
// says, or where vgd suggests from its name when it has none; the document's
// seams become the seams effect's particle pairs.
struct GarmentDef {
  std::filesystem::path file;       // XVC document; relative to the scene file's folder
  std::string size;                 // "" = the sample size
  std::vector<std::string> pieces;  // piece or block names; empty = every pattern of the size
  double spacing = 0.0;             // m between boundary vertices; 0 = the document's mesh.spacing, else 0.015
  // 0 = next to the body; a garment worn over others (a lower layer) starts
  // at least 15 mm outside their placed cloth (scene/placement.hpp,
  // Underlayer), so the two do not start through each other.
  int layer = 0;
};

struct ClothDef {
  std::string name;                  // grid: the piece name; XVC: a label (pieces keep their block names)
  std::optional<GridDef> grid;       // exactly one of grid, xvc and garment
  std::optional<XvcPiecesDef> xvc;
  std::optional<GarmentDef> garment;
  Placement placement;
  ClothModel model = ClothModel::mass_spring;
  bool bending = true;               // strain-rosette: add the bending effect
  std::string material;              // a key of SceneDef::materials
};

// ---- effects --------------------------------------------------------------------

// An axis-aligned box in the world (m): particles whose start position lies inside.
struct Box {
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();
};

// One group of pinned particles, chosen by index, by named set or by region
// (the union of all three), moving together with `velocity`.
struct PinGroupDef {
  std::string piece;                // piece name; "" = every piece (regions) / the only piece (indices, sets)
  std::vector<int> particles;       // indices within the piece
  std::vector<std::string> sets;    // grid sets: corner-u0v0 corner-u1v0 corner-u0v1 corner-u1v1,
                                    // edge-u0 edge-u1 edge-v0 edge-v1, row-J, column-I, all
  std::optional<Box> region;
  Vec3 velocity = Vec3::Zero();     // m/s (a moving pin: a yanked hanger, a tensile test's clamp)
};

// The body: vgd's parametric mannequin, an imported mesh or a simple solid
// (benchmarks). Used by the collision effect and by garment placement.
struct AvatarDef {
  enum class Kind { mannequin, file, sphere, cylinder };
  Kind kind = Kind::mannequin;
  // mannequin: a size from the tables (data/bodies), or measurements
  std::string size;                 // "" = use `measurements`
  std::string table;                // size table; "" = the default search order
  body::BodyMeasurements measurements;  // when size is ""
  int triangles = 0;                // target triangle count, 0 = the generator's default
  // file
  std::filesystem::path file;       // relative to the scene file's folder
  std::string unit = "auto";        // auto, m, dm, cm, mm, in (body/avatar_io.hpp)
  std::string up = "auto";          // auto, x, y, z, -x, -y, -z
  std::string facing = "auto";      // auto, +z, -z, +x, -x
  bool human = true;                // false: a prop (a hand, a table), not checked for a human's height
  // sphere / cylinder (Blender's UV sphere and cylinder)
  Vec3 centre = Vec3::Zero();       // m: sphere centre; cylinder: centre of the bottom cap
  double radius = 0.3;              // m
  double height = 1.0;              // m, cylinder
  int segments = 64, rings = 40;    // sphere: 64 x 40 = 4 992 triangles; cylinder: segments around, rings = stacks
};

// A seam between two particle sets of grid pieces (benchmarks, tests); the
// sets pair in order, so they must hold the same number of particles.
struct GridSeamDef {
  std::string piece_a, set_a;  // e.g. "front", "edge-u1"
  std::string piece_b, set_b;
  bool reverse = false;        // pair the second set backwards
};

// Seams: stitching forces pulling each pair together, merging pairs that
// come closer than merge_distance (sim/effects/seam.hpp). The pairs come from
// the garments' documents and from `grid`; build() fills effect.seams.
struct SeamsDef {
  sim::SeamDef effect;            // law, stiffness, max_force, damping, merge_distance, merge
  std::vector<GridSeamDef> grid;  // extra seams between grid pieces
  // Garments' sleeves sewn first: a seam joining a piece on an arm to a piece
  // elsewhere waits for the seams that close that arm's pieces on themselves
  // (sim::SeamPairs::after; docs/seams.md, "Order"). Off: every seam pulls
  // from the start.
  bool sleeves_first = false;
};

// The effects a scene calls for; an absent effect is never constructed.
struct EffectsDef {
  std::optional<sim::GravityDef> gravity;
  std::optional<sim::ViscosityDef> viscosity;
  std::optional<sim::DampingDef> damping;
  std::optional<sim::WindDef> wind;
  // A cap on particle speed (m/s), not a physical force: drapes switch it on
  // so seams pulling pieces together keep contact and self-collision tests
  // local (sim/effects/basic.hpp).
  std::optional<sim::SpeedLimitDef> speed_limit;
  std::vector<PinGroupDef> pins;
  // Cloth against the avatar (the scene's `avatar` must exist). body is filled by build().
  std::optional<sim::BodyCollisionDef> collision;
  // How seam particles touching the body respond until their pair merges:
  // "glide" (frictionless, inward normal velocity removed, force untouched),
  // "seed" (seed 002: slide keeping |F| and |v|), "slide" (frictionless,
  // inward parts of force and velocity removed) or "body" (like any particle,
  // the default). seed and slide blow up implicit Euler on the shipped
  // garments (the constrained force is unknown to the Jacobian): use them with
  // explicit methods (docs/collisions.md).
  std::string collision_seam_response = "body";
  std::optional<sim::SelfCollisionDef> self_collision;
  // Offset contact (sim/effects/contact.hpp): cloth against the avatar and
  // against itself with no intersection at the end of any step; replaces
  // `collision` and `self_collision` (a scene gives one or the others). The
  // body, seam pairs and pins are filled by build().
  std::optional<sim::ContactDef> contact;
  std::optional<SeamsDef> seams;
  // A hand pulling the cloth (sim/effects/hand.hpp): set by a program that
  // lets its user grab the cloth during a run (the studio), never read from
  // or written to a scene file.
  std::optional<sim::HandDef> hand;
};

// ---- integration, frames, output --------------------------------------------------

// Quality presets (quality.hpp): named integrator settings.
enum class Quality { preview, standard, precise };

struct IntegratorDef {
  std::optional<Quality> preset;     // the preset these settings started from, if any
  sim::IntegratorSettings settings;  // method, step (s), auto_substep, tolerances, ...
  // Seed 000's "iterations": steps per frame. When > 0 the step is
  // 1 / (fps · iterations_per_frame) and settings.step is ignored.
  int iterations_per_frame = 0;
};

struct OutputDef {
  enum class Kind { memory, obj };
  Kind kind = Kind::obj;
  std::filesystem::path directory;  // obj: frame_0000.obj, ... (relative: to the working directory)
};

struct SceneDef {
  std::string name;
  std::filesystem::path source;  // the scene file ("" when built in code); names it in messages
  std::optional<AvatarDef> avatar;
  std::vector<ClothDef> cloth;
  std::map<std::string, MaterialSource> materials;
  EffectsDef effects;
  IntegratorDef integrator;
  sim::RunSettings run{25.0, 2.0};  // fps, duration (s)
  std::vector<OutputDef> outputs;
};

// The step the integrator will be asked to take (s).
double effective_step(const SceneDef& def);

// What a scene may plan; more is refused by validate() naming the field.
inline constexpr double kMaxFps = 10000.0;     // frames per second
inline constexpr double kMaxFrames = 1.0e6;    // frames of one run (duration x fps)
inline constexpr double kMaxSteps = 1.0e9;     // steps of one run (duration / step)

// Checks what can be checked without reading other files (ranges, references
// between fields, exactly one piece source, bounded frame and step counts, ...). Throws vgd::Error naming
// def.source, the field's path and the problem.
void validate(const SceneDef& def);

}  // namespace vgd::scene
