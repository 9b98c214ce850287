#pragma once
// The body a garment is draped on: an imported avatar mesh (assimp) or vgd's
// parametric mannequin generated from body measurements.
//
// Every Avatar is in vgd's world frame: metres, +Y up, facing +Z (the body's
// left is +X), feet on y = 0, centred on the Y axis. Segments (neck, torso,
// hips, arms, legs) are axes with elliptic cross-sections along them; the
// placement stage wraps pattern pieces around them.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/mesh/surface.hpp"

namespace vgd::body {

using Vec3 = Eigen::Vector3d;

// Body measurements, m (ISO 8559-1 definitions; girths horizontal).
struct BodyMeasurements {
  std::string label = "custom";  // size label ("38", "M", "10") or "custom"
  std::string sex = "female";    // "female" or "male": which body template
  double height = 1.68;          // top of head to floor
  double bust = 0.88;            // bust girth (women), chest girth (men)
  double under_bust = 0.75;      // just below the breasts (women); = bust for men
  double waist = 0.72;           // natural waist girth
  double hip = 0.97;             // hip girth at the fullest part
  double shoulder_width = 0.38;  // shoulder point to shoulder point across the back
  double neck = 0.34;            // neck base girth
  double arm_length = 0.59;      // shoulder point to wrist, arm hanging
  double inseam = 0.78;          // crotch to floor
};

// One elliptic cross-section of a segment, in the plane normal to its axis.
struct SegmentRing {
  double s = 0.0;                 // m along the axis from BodySegment::start
  Vec3 centre = Vec3::Zero();     // m
  double half_width = 0.0;        // m, semi-axis along side() (the body's left)
  double half_depth = 0.0;        // m, semi-axis along front
};

// A part of the body: neck, torso, hips, left-arm, right-arm, left-leg, right-leg.
struct BodySegment {
  std::string name;
  Vec3 start = Vec3::Zero();      // m: torso/hips/neck: bottom; arms: shoulder; legs: hip joint
  Vec3 axis = Vec3::UnitY();      // unit: torso/hips/neck up, arms towards the wrist, legs down
  Vec3 front = Vec3::UnitZ();     // unit, normal to axis: where the body faces
  double length = 0.0;            // m
  std::vector<SegmentRing> rings;  // by increasing s, first at 0, last at length
  // The body's left as seen along this segment: front × axis for upward axes.
  Vec3 side() const { return axis.cross(front).normalized(); }
};

// The cross-section at s (m), linearly interpolated, clamped to [0, length].
SegmentRing ring_at(const BodySegment& segment, double s);

// Landmarks found on a body's surface (landmarks.hpp, measure_body). Heights
// are above the floor.
struct ArmLandmarks {
  Vec3 shoulder = Vec3::Zero();  // m: the shoulder joint, on the arm's axis 3 cm inside the chest's half-width
  // m: on the shoulder–wrist line where the arm's girth profile bends (the
  // forearm tapering faster than the upper arm), else 56 % of the way
  Vec3 elbow = Vec3::Zero();
  Vec3 wrist = Vec3::Zero();     // m: the arm's thinnest slice before the hand
  double wrist_girth = 0.0;      // m
  bool elbow_on_surface = false;     // the elbow was found on the surface, not put at 56 %
  bool elbow_from_skeleton = false;  // the elbow is the file's elbow joint
  bool shoulder_from_skeleton = false;  // the shoulder is the file's (the upper arm bone's start)
  bool wrist_from_skeleton = false;     // the wrist is the file's (the hand bone's start); wrist_girth stays the surface's
};

struct BodyLandmarks {
  double height = 0.0;  // m, top of the head above the floor
  // Heights above the floor, m (0 where not found).
  double neck = 0.0;        // the neck's thinnest slice
  double shoulder = 0.0;    // top of the shoulders beside the neck
  double bust = 0.0;        // fullest slice of the chest
  double under_bust = 0.0;  // 3 % of the height below the bust
  double waist = 0.0;       // thinnest slice of the trunk between hips and chest
  double hip = 0.0;         // fullest slice between crotch and waist
  double crotch = 0.0;      // lowest slice whose loop encloses the trunk's centre line
  double ankle = 0.0;       // thinnest slice of a leg at 3–10 % of the height (the foot's top on a mannequin)
  double knee = 0.0;        // mean of the legs' knees: where the girth profile bends between the calf's
                            // fullest slice and the thigh, or the file's skeleton's knee joints; 0 if neither
  std::optional<ArmLandmarks> left_arm, right_arm;  // the body's left is +X
};

struct Avatar {
  std::string source;              // the file, or "mannequin <label>"
  mesh::SurfaceMesh surface;       // world frame, m
  std::vector<BodySegment> segments;
  std::vector<int> triangle_segment;  // per triangle: index in segments, -1 when unknown
  std::optional<BodyMeasurements> measurements;  // mannequins: what they were made from
  // Imported bodies: what the importer decided (unit, up, facing, each with
  // its reason) and what it left out, for the commands to print.
  std::vector<std::string> notes;
  // Imported bodies: landmarks measured on the surface (placement measures
  // from them); mannequins are placed from their measurements instead.
  std::optional<BodyLandmarks> landmarks;
  // Imported bodies: the girths measured on the surface (label "measured").
  std::optional<BodyMeasurements> measured;

  // The segment with this name, or nullptr.
  const BodySegment* segment(std::string_view name) const;
};

// The body's segments beside point p (m), nearest first: the nearest, and
// a second within `within` m of it (two at a crease: an armpit is the torso
// and an arm). A segment's distance is that of its nearest triangle centre
// where the body's triangles are labelled (a mannequin), else of its
// elliptic cross-sections (an imported body, its segments from landmarks).
std::vector<std::string> segments_beside(const Avatar& body, const Vec3& p, double within);

}  // namespace vgd::body
