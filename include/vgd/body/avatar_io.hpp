#pragma once
// Avatar meshes from and to files (assimp): OBJ, PLY, STL, glTF/GLB, FBX, Collada.
//
// Import merges every mesh of the file with its node transform, keeps
// triangles only, welds coincident vertices and normalises to vgd's avatar
// frame (avatar.hpp): metres, +Y up, facing +Z, feet on y = 0, centred on the
// Y axis (bounding box centre in x and z). What was guessed is reported.
#include <filesystem>
#include <string>
#include <vector>

#include "vgd/mesh/surface.hpp"
#include "vgd/body/avatar.hpp"
#include "vgd/body/landmarks.hpp"
#include "vgd/body/sizes.hpp"

namespace vgd::body {

struct AvatarImportOptions {
  // File unit: "auto", "m", "dm", "cm", "mm", "in". auto: the file's metadata
  // (glTF is metres by specification, FBX's UnitScaleFactor) when it gives a
  // human height (1.0–2.3 m), else the one of m, dm, cm, mm and in that does
  // (at most one can). A body that is not 0.5–2.5 m tall in the unit chosen is
  // refused: it is no human body, or the unit is wrong.
  std::string unit = "auto";
  // The file's up direction: "auto", "x", "y", "z", "-x", "-y", "-z". auto: the
  // body's own, when it is clear (the axis along which its surface spreads
  // furthest, which a T-pose's arm span does not beat; the end whose slice cuts
  // two legs is down), else the file's metadata (glTF +Y, FBX UpAxis,
  // Collada's up_axis applied by assimp), else the longest extent of the
  // bounding box, pointing to the side holding more of the surface area.
  std::string up = "auto";
  // Where the body faces once up is +Y: "auto" (from the feet, which point
  // forward; +Z when they show nothing), "+z" (no change), "-z", "+x", "-x".
  std::string facing = "auto";
  // false for a prop rather than a body (a drape's sphere, a body already in
  // vgd's frame): no height check, no helper or loose parts left out.
  bool human = true;
  double weld_tolerance = 1e-6;  // m, after unit conversion
  bool recentre = true;          // feet on y = 0, bounding box centred on x = z = 0
  bool segments = true;          // best-effort segments from horizontal slices
  double read_time_limit_s = 0;  // s, assimp's reading (ModelReadOptions::time_limit_s; 0: by the file's size)
};

struct AvatarReport {
  std::string file;
  std::string format;               // the file's extension, lower case
  int meshes = 0;                   // meshes merged
  int vertices = 0, triangles = 0;  // after welding
  int welded_vertices = 0;          // vertices merged into others
  int dropped_primitives = 0;       // points and lines ignored
  mesh::Box3 box;                   // m, after normalisation
  double height = 0.0;              // m
  bool watertight = false;
  int boundary_edges = 0, non_manifold_edges = 0, inconsistent_edges = 0, degenerate_triangles = 0;
  double area = 0.0, volume = 0.0;  // m², m³
  std::string unit;                 // m, cm, mm, in
  bool unit_guessed = false;
  std::string unit_reason;          // why this unit
  std::string up;                   // x, y, z, -x, -y, -z (in the file)
  bool up_guessed = false;
  std::string up_reason;
  std::string facing;               // +z, -z, +x, -x (in the file, once up is +Y)
  bool facing_guessed = false;
  std::string facing_reason;
  std::vector<std::string> segments;  // names of the segments found
  std::optional<BodyMeasuring> measuring;  // landmarks and measurements (bodies; options.segments)
  std::optional<NearestSize> nearest;      // the shipped tables' size nearest to them
  std::vector<std::string> notes;     // anything else worth saying
};

// Imports an avatar. Helper meshes (MakeHuman's "helper-*" and "joint-*") and
// loose parts under 5 % of the body's area (eyes, teeth, hair) are left out
// with a note; a glTF's skinned meshes are taken in their bind pose. Throws
// vgd::Error naming the file for: a missing or empty file, a .gltf whose
// .bin is not beside it, content no importer understands, a file without
// triangles, a coordinate that is NaN or infinite, a flat (zero-height) mesh,
// a body that is not 0.5–2.5 m tall, or a bad option value.
Avatar import_avatar(const std::filesystem::path& path, const AvatarImportOptions& options = {},
                     AvatarReport* report = nullptr);

// The report of an avatar already in memory (a mannequin): counts, box, watertightness.
AvatarReport report_avatar(const Avatar& avatar);

// The report as JSON text (one object; lengths in m).
std::string to_json(const AvatarReport& report);

// Writes the avatar's surface in the format of the path's extension: .obj,
// .ply (binary), .stl (binary), .glb, .gltf (+ .bin beside it), .dae, .fbx (ASCII: assimp 5.2 cannot read back its binary FBX). Every
// file is written atomically (vgd::write_file_atomic). Throws vgd::Error for an
// unknown extension or a failed write.
void export_avatar(const Avatar& avatar, const std::filesystem::path& path);

// Extensions export_avatar understands, with the dot: ".obj", ".ply", ...
std::vector<std::string> avatar_export_extensions();

// Best-effort segments of an avatar in the avatar frame, from horizontal
// slices: hips and torso (the loop around the centre line), neck (same, above
// the shoulders), legs (the two largest loops below the crotch). Arms come
// from landmarks (arm_segments). Returns what was found.
// With `landmarks` (measure_body), the trunk's segments start and end at the
// measured crotch, waist and shoulders.
std::vector<BodySegment> segments_from_slices(const mesh::SurfaceMesh& surface,
                                              const BodyLandmarks* landmarks = nullptr);

}  // namespace vgd::body
