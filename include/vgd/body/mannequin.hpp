#pragma once
// vgd's parametric mannequin: a smooth, watertight body generated from body
// measurements (docs/avatar.md), in the avatar frame (avatar.hpp): metres,
// +Y up, facing +Z, the body's left on +X, feet on y = 0, centred on the Y axis.
//
// The body is a signed-distance function: an elliptic loft for the trunk
// (cross-sections at anthropometric heights, girths from the measurements),
// tapered capsules for neck, arms (A-pose) and legs, ellipsoids for head, hands
// and feet, joined with a polynomial smooth minimum. The girths of the trunk
// are then calibrated on the function itself (slice, convex hull, perimeter:
// what a tape measures) until bust, under-bust, waist and hip match, and the
// crotch and shoulder points are moved to the inseam and shoulder width. The
// zero level set is meshed by CGAL (mesh/implicit_surface.hpp).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/body/avatar.hpp"
#include "vgd/mesh/surface.hpp"

namespace vgd::body {

struct MannequinOptions {
  int target_triangles = 10000;  // aimed at, clamped to 5 000–20 000; the result is within about ±20 %
  double facet_size = 0.0;       // m, CGAL facet size; > 0 overrides target_triangles
  double facet_distance = 0.0;   // m, largest facet-to-surface distance (resolves armpit and crotch gaps); 0 = facet size / 8
  double arm_angle_deg = 45.0;   // angle between each arm and the vertical: 45 an A-pose, 90 a T-pose; opened up to 50° when the chest needs it
  double arm_forward_deg = 0.0;  // arms swung forward about the shoulders' x axis, 0–60: 0 in the frontal plane
  bool calibrate = true;         // false: girths from the closed-form ellipse estimate only (±2–3 %)
  // Keep the meshed surface in the cache and take it from there when it holds
  // it (mannequin_cache_dir()): the same mesh bit for bit, without its meshing.
  bool cache = true;
};

// Where mannequins' surfaces are kept between runs: $VGD_CACHE_DIR, else
// $XDG_CACHE_HOME/vgd, else ~/.cache/vgd; empty (no cache) when VGD_CACHE_DIR
// is "off" or no home is known. Each file holds one surface, keyed by the
// measurements, the options and the executable that meshed it (a rebuilt vgd
// meshes anew); a file that does not read back whole is replaced.
std::filesystem::path mannequin_cache_dir();

// Surfaces this process has meshed (not taken from the cache), for tests.
long mannequin_meshings();

// A cache file's bytes for `surface` kept under `key`, and the surface read
// back from such bytes: nullopt unless the bytes are whole (their header names
// `key`, their counts fit their length, their checksum matches, every
// coordinate is finite and every corner a vertex). The format, for tests and
// the fuzz target; docs/avatar.md, "The cache".
std::string mannequin_cache_file(const mesh::SurfaceMesh& surface, std::string_view key);
std::optional<mesh::SurfaceMesh> read_mannequin_cache_file(std::string_view bytes, std::string_view key);

// Heights of the landmarks the mannequin is built on, m above the floor, and
// where the girths are measured (the calibration and the tests use the same).
struct MannequinLandmarks {
  double height = 0.0;          // top of head
  double chin = 0.0;
  double neck_base = 0.0;       // where the neck meets the shoulders
  double shoulder = 0.0;        // acromion (shoulder point) height
  double shoulder_joint = 0.0;  // centre of the arm's top sphere; the shoulder width is the body's width here
  double bust = 0.0;            // bust (chest) girth height
  double under_bust = 0.0;
  double waist = 0.0;
  double hip = 0.0;             // fullest hip
  double crotch = 0.0;          // = inseam
  double knee = 0.0;
  double ankle = 0.0;
};

// The landmark heights for these measurements (fractions of the height for a
// female or male template; crotch = inseam).
MannequinLandmarks mannequin_landmarks(const BodyMeasurements& m);

// Checks measurements for plausibility (positive, finite, girth order, limbs
// shorter than the body). Throws vgd::Error naming the field and the problem.
void check_measurements(const BodyMeasurements& m, const std::string& where = "");

// The mannequin: surface (watertight, 5 000–20 000 triangles), its seven
// segments (neck, torso, hips, left-arm, right-arm, left-leg, right-leg) with
// rings from the function's analytic cross-sections, triangle_segment and the
// measurements. Deterministic: the same measurements give the same mesh, bit
// for bit. Throws vgd::Error for implausible measurements.
Avatar make_mannequin(const BodyMeasurements& m, const MannequinOptions& options = {});

// The body's signed distance (m, < 0 inside) after calibration, for tests and
// for callers that want the exact surface (e.g. penetration checks).
struct MannequinFunction;  // opaque
class MannequinSdf {
 public:
  explicit MannequinSdf(const BodyMeasurements& m, const MannequinOptions& options = {});
  ~MannequinSdf();
  MannequinSdf(MannequinSdf&&) noexcept;
  MannequinSdf& operator=(MannequinSdf&&) noexcept;
  double operator()(const Vec3& p) const;
  // The same value with every part of the body evaluated: operator() skips
  // the neck, the head or a limb where a lower bound shows it cannot change
  // the value, and must equal this bit for bit.
  double every_part(const Vec3& p) const;
  const MannequinLandmarks& landmarks() const;
  // Girth (m) of the trunk's slice at height y: convex-hull perimeter of the
  // loop around the trunk's centre line.
  double girth_at(double y) const;
  const MannequinFunction& function() const { return *f_; }

 private:
  std::unique_ptr<MannequinFunction> f_;
};

}  // namespace vgd::body
