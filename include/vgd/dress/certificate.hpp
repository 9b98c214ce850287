#pragma once
// The drape certificate: the numbers QA and a designer need before trusting a
// picture of a draped garment (docs/drape.md). Written as JSON beside every
// drape's outputs.
//
//   penetration    how deep cloth particles sit inside the body, measured
//                  exactly against the body's triangles (not the collision
//                  grid), m;
//   intersections  cloth triangle pairs that pass through each other;
//   seams          pairs closed, and the gap of each seam's open pairs, m;
//   strain         per piece, percentiles over its triangles of the
//                  engineering strain along the warp and the weft and of the
//                  shear angle (degrees), from each triangle's deformation
//                  gradient against its flat pattern shape;
//   contact        particles touching the body, their area and the pressure
//                  the cloth puts on it (normal force / particle area, Pa);
//   energy         the mean kinetic energy per particle at every frame, J.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/scene/build.hpp"

namespace vgd::dress {

using Vec3 = Eigen::Vector3d;

struct Percentiles {
  double p5 = 0, p50 = 0, p95 = 0, max = 0, min = 0;
};

struct PieceStrain {
  std::string piece;
  std::string fabric;      // the name of the MATERIAL the piece was draped in ("" in older certificates)
  Percentiles warp, weft;  // engineering strain, dimensionless (0.01 = 1 %)
  Percentiles shear_deg;   // change of the warp–weft angle, degrees
  // The fabric's own lock (MATERIAL strain_limit): its p95 along the warp or
  // the weft beyond it is over-stretched; 0 = the fabric states none and
  // Certificate::strain_limit applies.
  double fabric_limit = 0.0;
};

struct SeamState {
  std::string name;
  int pairs = 0, closed = 0;  // closed: merged, or within the merge distance
  double max_gap = 0, mean_gap = 0;  // m over all pairs
  Vec3 widest_at = Vec3::Zero();     // m: midpoint of the pair with the largest gap (where to look)
  // The body lies between the two sides of its widest open pair (a point of
  // the straight line between them more than 2 mm inside it): the sides are
  // held apart by the body, not by the cloth.
  bool body_between = false;
};

struct ContactState {
  int particles = 0;          // within the contact distance of the body
  double area = 0;            // m²: their lumped cloth area
  double force = 0;           // N: total normal force on the body
  Percentiles pressure;       // Pa over the contact particles
  // Pa per particle of the model (0 where the cloth does not touch the body):
  // the contact-pressure map (vgd drape writes it as contact-pressure.json,
  // vgd render --map pressure draws it). Not in the certificate's JSON.
  std::vector<double> particle_pressure;
};

// Where a piece ended against where it was placed: its centre (the mean of
// its particles) then and now.
struct PieceWhere {
  std::string piece;
  std::string segment;            // the body segment it was placed on
  Vec3 moved = Vec3::Zero();      // m: final centre − placed centre
  double raised = 0.0;            // m: placed this much higher than arranged (its garment reached the soles)
};

// A reason a drape is not passed: a class from a short fixed list and the
// figures behind it (the piece or seam named).
struct Failure {
  std::string kind;    // error, no rest, seams open, open side, penetration, self-intersection, over-stretched, displaced
  std::string detail;  // e.g. "LEFT_SLEEVE_38: weft strain p95 121 % (limit 50 %)"
};

// A side of the trunk the garment leaves open where its front and back
// should meet: slices of the cloth round the body with no cloth over a wide
// arc centred on the body's left or right.
struct OpenSide {
  std::string side;            // "left" or "right" (the wearer's)
  double top = 0, bottom = 0;  // m: heights of the highest and lowest open slice
  double widest_deg = 0;       // deg: the widest arc without cloth
};

// Where a drape that did not come to rest still moves: over the run's last
// second of simulated time, the particle that moved furthest (the sum of its
// moves from frame to frame: a particle jumping back and forth moves far and
// ends where it was), where it is at the end, the pieces holding particles
// that moved at least half as far, and the body segments beside it (one, or
// two at a crease: an armpit is the torso and an arm).
inline constexpr double kNearCrease = 0.02;  // m
struct StillMoving {
  double window_s = 0;     // s: the span measured (the last second, or the whole run when shorter)
  double path = 0;         // m: the furthest a particle moved over it
  Vec3 at = Vec3::Zero();  // m: that particle at the end
  std::vector<std::pair<std::string, int>> pieces;  // (piece, particles moving at least path / 2), most first
  std::vector<std::string> near;  // body segments whose surface is within kNearCrease of the nearest's
};

struct StageTime {
  std::string name;         // placing, sewing, settling
  double wall_s = 0;        // wall-clock seconds
  double simulated_s = 0;   // simulated seconds (0 for placing)
};

struct Certificate {
  // What was run.
  std::string version;                      // vgd's version
  std::vector<std::pair<std::string, std::string>> inputs;    // (what, file or value)
  std::vector<std::pair<std::string, std::string>> settings;  // (name, value with unit)
  // Why it stopped: "rest", "time limit", "error".
  std::string stop_reason;
  std::string stop_message;
  std::optional<StillMoving> still_moving;  // stopped at the time limit: where the cloth still moves
  double simulated_s = 0, wall_s = 0;
  int frames = 0;
  int frames_on_fewer_threads = 0;  // frames run on fewer threads than asked, cores being busy (sim/threads.hpp)
  std::vector<StageTime> stages;
  // Where the time went: seconds per effect (System::profile, all verbs) and
  // the integrator's counts.
  std::vector<std::pair<std::string, double>> effect_seconds;
  long steps = 0, force_evaluations = 0, linear_iterations = 0;
  // Self-collision's work over the run (absent: -1): detection passes, pairs
  // found, particles its fail-safe put back to their step's start.
  long self_detections = -1, self_pairs = 0, self_reverted = 0, self_untangled = 0;
  // Offset contact's work (absent: -1): detections, particle moves cut to
  // their bound, particles short of their step's end after the last round,
  // seam merges held back.
  long contact_detections = -1, contact_cut = 0, contact_unfinished = 0, contact_merges_held = 0;
  // The state reached.
  int particles = 0, triangles = 0;
  double max_penetration = 0;   // m, exact
  int particles_inside = 0;     // deeper than 0
  Vec3 deepest_at = Vec3::Zero();  // m: the deepest particle (where to look)
  double penetration_limit = 0.001;  // m: what the drape promises
  int triangle_intersections = -1;   // -1 when not measured
  // Cloth triangles the body passes through: their centre or an edge's
  // midpoint inside the body deeper than penetration_limit (exact depths; -1
  // when not measured) — a body ridge poking between particles that are all
  // outside it, which the particles' depth does not see. Per piece.
  int body_through_cloth = -1;
  double max_body_through = 0;  // m, the deepest such point
  std::map<std::string, int> body_through_by_piece;
  // Where the deepest of them is (m; deeper than the penetration limit) and
  // the body segments beside it, as StillMoving::near (an armpit: an arm and
  // the torso); empty when none is.
  std::optional<Vec3> body_through_at;
  std::vector<std::string> body_through_near;
  // Of those, triangles with the body deeper inside them than a quarter of
  // their longest rest edge: no ridge between particles reaches that far into
  // an intact cloth (the sag of the chord over the body's curvature); the
  // body is through an opening of it (a gaping slit, a strap beside the
  // shoulder instead of on it, a crotch between seam ends). A failure
  // ("penetration").
  int body_through_opening = -1;
  std::map<std::string, int> body_through_opening_by_piece;
  std::map<std::string, int> crossings_by_pieces;  // "A / B" (A ≤ B by name) → crossing pairs between them
  std::vector<SeamState> seams;
  std::vector<PieceStrain> strain;
  std::vector<PieceWhere> placement;
  // Trunk garments (pieces on the torso or hips): the sides left open
  // between the bust (or 30 % below the cloth's top, or 2 cm below the lowest
  // point of the seams joining sleeves to it: the armholes) and 8 cm above its
  // hem, sliced every 2 cm. An arc wider than open_limit_deg centred within 60° of
  // the body's left or right fails the drape ("open side"): a front and a back that
  // hang apart instead of being sewn (an open front or back is a style, an
  // open side is not). Sewn sides leave arcs of 7–9° (the mesh's spacing
  // seen from the body's axis: the shipped T-shirt and skirt, a Gerber tank);
  // the same tank with its side seams left out, 46–51°.
  std::vector<OpenSide> open_sides;
  double open_limit_deg = 25;
  ContactState contact;
  std::vector<double> times;            // s, per frame
  std::vector<double> kinetic_energy;   // J per particle, per frame
  // Limits of the checks. The p95 of a piece's warp or weft strain: 5 % of
  // a piece at twice its length is no drape but a garment pulled off its
  // body or sewn to the wrong piece (the project's T-shirt reaches 34–51 %
  // in its sleeve caps, where the cap's ease is sewn into the armhole;
  // docs/drape.md). How far a piece's centre may end from where it was
  // placed (m; the shipped garments' pieces move 1–7 cm): a waistband that
  // rides up to the armpits, a sleeve slipped off its arm.
  double strain_limit = 1.0;
  double displacement_limit = 0.12;
  // m: how far the body may show through the cloth between its particles
  // (body_through_cloth) before the drape fails as penetration. Cloth
  // triangles are flat: over a body part of 2 cm radius a 1.5 cm edge's
  // chord stands 1.4 mm off the surface, and the drapes that pass reach
  // 2.9 mm at most (the men's tee at size 54); a tight T-shirt on a larger
  // body shows it 42 mm through, a crumpled trouser hem on a foot 21 mm.
  double body_through_limit = 0.005;
  // Every check that fails, in a fixed order: error (the engine stopped the
  // run), no rest, seams open, open side (open_sides), penetration (particles inside
  // the body, the body through an opening of the cloth: body_through_opening,
  // or through the cloth between its particles by more than
  // body_through_limit), self-intersection, over-stretched, displaced.
  std::vector<Failure> failures() const;
  // What is measured and shown but does not fail the drape: "body through
  // cloth" within body_through_limit (the shipped T-shirt's sleeve hems show
  // it on the mannequin by 1.9 mm, docs/drape.md).
  std::vector<Failure> warnings() const;
  // No failure.
  bool passed() const;
  // "the body passes through N cloth triangles, up to X mm inside it between
  // their particles (PIECE n, ...)".
  std::string body_through_text() const;
  // Seam pairs closed and in all, over every seam.
  struct SeamTotals {
    int closed = 0, pairs = 0;
  };
  SeamTotals seam_totals() const;
};

// Measures the scene's state at full positions x (3N of the original
// particles, as frames give them). `merge_distance` (m) counts a seam pair as
// closed; particles nearer the body than `contact_distance` (m: the collision
// clearance plus a tolerance) touch it. Measuring intersections costs ~0.1 s
// on 20 000 triangles; off when `intersections` is false.
void measure_state(const scene::Scene& scene, const sim::VecX& x, double merge_distance, double contact_distance,
                   bool intersections, Certificate& out);

// A drape that failed only where the cloth is caught in the crease between an
// arm and the torso: no rest with the cloth still moving there, or the body
// through the cloth between its particles there (every particle outside it,
// no opening), and nothing else failing. The corrections after each step
// leave a sleeve's junction there sinking into the crease at every step,
// which holding the touching cloth on the body inside the step once sewn
// (sim::IntegratorSettings::hold_contacts_once_sewn) stops
// (docs/collisions.md, "Holding touching cloth once sewn"). Returns where, as
// "the right-arm and the torso, at (x, y, z) m"; nullopt otherwise.
std::optional<std::string> caught_at_armpit(const Certificate& c);

// The certificate as pretty-printed JSON.
std::string to_json(const Certificate& c);
// Reads what to_json wrote (a certificate.json from vgd dress, a catalogue
// item or the server), so that to_json(certificate_from_json(t)) == t for any
// t that to_json wrote. `source` names the text in errors. Throws vgd::Error
// naming the source and the field for text that is not such a certificate.
Certificate certificate_from_json(std::string_view text, const std::string& source);

// The contact-pressure map beside a drape's certificate (contact-pressure.json):
// {"unit": "Pa", "values": [...]}, one value per particle of the model (per
// vertex of garment.obj), 0 where the cloth does not touch the body.
std::string contact_pressure_json(const Certificate& c);
// Reads it back (Pa per vertex). Throws vgd::Error naming `source` and the
// field for text that is not such a map (a value negative or not finite).
std::vector<double> contact_pressure_from_json(std::string_view text, const std::string& source);

}  // namespace vgd::dress
