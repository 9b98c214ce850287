#pragma once
// Landmarks and measurements found on a body's surface (docs/avatar.md),
// whatever made it: an imported scan or model, or vgd's mannequin. The body
// must be upright in vgd's frame (metres, +Y up, facing +Z, feet on y = min).
//
// Girths are what a tape measures: the convex-hull perimeter of the slice's
// loop around the trunk's centre line (ISO 8559-1: horizontal). Heights are
// above the lowest point of the body. Arms are found from slices across them
// (planes x = const beyond the trunk), so any pose from T to A gives them;
// arms held in front of the trunk are not found.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/body/avatar.hpp"
#include "vgd/body/model_file.hpp"
#include "vgd/mesh/surface.hpp"

namespace vgd::body {

struct BodyMeasuring {
  BodyLandmarks landmarks;
  // What a tailor would measure on this body (m; label "measured"). Fields
  // not found are 0.
  BodyMeasurements measurements;
  std::vector<std::string> notes;  // what was not found, and why
  // The arm segments (arm_segments() of these landmarks), empty where no arm
  // was found. They run shoulder to wrist: a skeleton's elbow does not move them.
  std::vector<BodySegment> arms;
};

// The trunk's centre line (x, z), m: the bounding box's x (bodies are
// symmetric) and the z of the centroid of the largest loop at 62 % of the
// height (the waist; arms hanging there are loops of their own or lobes at
// the sides), not the box's z, which arms held forward move out of the neck.
mesh::Vec2d trunk_centre(const mesh::SurfaceMesh& upright);

// Landmarks and measurements of an upright body.
BodyMeasuring measure_body(const mesh::SurfaceMesh& upright);

// The joint a skeleton's bone stands for, from its name as rigs spell it
// (Mixamo "mixamorig:LeftForeArm", SMPL "L_Elbow", MakeHuman "lowerarm01.L",
// Rigify "forearm.L", 3ds Max "Bip01 L Forearm"): "shoulder" (the upper arm's
// bone: Mixamo "LeftArm", SMPL "L_Shoulder", "upperarm01.L", "upper_arm.L",
// "Bip01 L UpperArm"; not a collarbone), "elbow", "wrist", "knee", "ankle",
// or "" for any other bone.
std::string skeleton_joint_kind(std::string_view bone_name);

// Takes from a file's skeleton (joints in the body's upright frame, m) what
// the surface can only estimate: the shoulder and wrist joints (each within
// 8 cm of the arm's axis found on the surface and a quarter of the arm's
// length of where the surface put it), then the elbows (on the arm, within
// 8 cm of its axis, 20-90 % of the way to the wrist) and the knees (between
// ankle and crotch). Says in `notes` what it took and what it refused.
// Returns how many joints it took; arm_segments then follows the joints.
int landmarks_from_skeleton(BodyLandmarks& landmarks, const std::vector<ModelJoint>& joints,
                            std::vector<std::string>& notes);

// The arm segments (left-arm, right-arm) of an upright body from its
// landmarks and slices: the axis from shoulder to wrist, rings from the
// slices across the arm. Empty where an arm was not found.
std::vector<BodySegment> arm_segments(const mesh::SurfaceMesh& upright, const BodyLandmarks& landmarks);

}  // namespace vgd::body
