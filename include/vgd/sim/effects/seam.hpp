#pragma once
// Seams that sew (seed 002 §3.3, seed 000 §4.2): a seam pairs two hems as a
// list of particle pairs; a force pulls each pair together and, once a pair is
// closer than merge_distance, the two particles merge into one at the next
// frame boundary (System::apply_merges restructures the topology). docs/seams.md.
//
// Force on a pair (a, b), l = x_a − x_b, d = |l|, u = l/d:
//   f_a = −φ(d) u − c (v_a − v_b),   f_b = −f_a,
//   linear:      φ(d) = k d                        (a zero-rest-length spring)
//   saturating:  φ(d) = F tanh(k d / F)            (F = max_force)
// The seed says only "non-linear elastic forces"; vgd's non-linear law is the
// saturating one: it is the linear spring k near closing (so the last
// millimetres close as fast as with the spring) but pulls a far pair with at
// most F, so pieces placed far apart (a sleeve 20 cm from its armhole) are not
// shot together with a force growing with the gap; its stiffness is bounded by
// k everywhere (φ′ ≤ k, φ/d ≤ k), so the explicit stability bound is the
// linear spring's, and its Jacobian is negative semi-definite (implicit steps
// stay definite). A stiffening law (k d (1 + (d/d0)²)) has neither property.
// The damping is isotropic on the pair's relative velocity (it also damps
// sliding along the gap, harmless for a pair that is about to become one).
//
// Jacobian (a-a block; a-b = b-a = −it, b-b = it):
//   ∂f_a/∂x_a = −[φ′(d) u uᵀ + (φ(d)/d)(I − u uᵀ)]   (−k I for the linear law)
//   ∂f_a/∂v_a = −c I
// Stiffness bound per pair end: 2k (∂f/∂x rows) and 2c (∂f/∂v rows); the
// explicit limit for a particle of mass m on one pair is ω² ≤ 2k/m (plus its
// other effects): e.g. symplectic Euler h < 2/ω = √(2m/k).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "vgd/sim/effect.hpp"

namespace vgd::sim {

// One seam: pairs of particles (global indices of the Model) to be joined.
struct SeamPairs {
  std::string name;                         // for progress and messages ("side seam left")
  std::vector<std::array<int, 2>> pairs;    // (particle on one hem, particle on the other)
  // Seams (indices into SeamDef::seams) that must have closed, every pair
  // merged, before this one pulls: a sleeve's cap waits for its underarm seam,
  // so the sleeve is a tube round its arm before it is pulled to the armhole
  // (an open sleeve pulled along an arm swung forward slid off it through its
  // opening, and the underarm seam closed with the arm outside). Until then
  // its pairs exert no force; they still merge when they meet. A seam may
  // wait for seams that wait in turn, never for itself through them.
  std::vector<int> after;
};

enum class SeamLaw {
  linear,      // φ = k d
  saturating,  // φ = F tanh(k d / F): vgd's non-linear law (see above)
};

// Defaults: a gentle sewing force for garment-sized particles (grams); not
// measured, the scene tunes them to the fabric and the distances.
struct SeamDef {
  std::vector<SeamPairs> seams;
  SeamLaw law = SeamLaw::saturating;
  double stiffness = 1.0;         // N/m per pair: k, the force per metre of gap near closing
  double max_force = 0.05;        // N per pair: F of the saturating law (the pull of a far pair)
  double damping = 0.01;          // N·s/m per pair: c, on the pair's relative velocity
  double merge_distance = 0.002;  // m: a pair closer than this merges (seed 002: "below a given threshold")
  // m: a pair next to an already merged pair of its seam (its neighbour along
  // the hems) that has stopped closing (its gap shrank by less than 2 % since
  // the last frame) merges once closer than this, so a seam closes like a
  // zipper from its sewn end instead of stalling a few millimetres open where
  // the cloth is tight (a sleeve cap's ease, an armpit). 0 = off.
  double zip_distance = 0.0;
  // m: the last open pair of a seam, stalled (as above) for last_stitch_frames
  // frames in a row, merges once closer than this: where four pieces meet (an
  // armpit) the last corner pair could hang 3–5 cm apart for good, each
  // particle held on its own side of the crease, and the drape never came to
  // rest. 0 = off.
  double last_stitch_distance = 0.0;
  int last_stitch_frames = 10;
  bool merge = true;              // false: pairs are pulled together but never merged
  // s: a seam waiting for others (SeamPairs::after) pulls from this time on
  // whether they have closed or not (checked at frame boundaries), so a seam
  // that stalls open does not hold the garment apart. 0 = wait until they close.
  double wait_limit = 0.0;
};

// Validates the definition against the model (particles exist, a pair joins two
// different particles, finite non-negative constants, max_force > 0 for the
// saturating law); throws SimulationError naming the seam and pair.
std::unique_ptr<Effect> make_seam(const Model& model, const SeamDef& def);

// The magnitude φ(d) (N) of the seam force at gap d (m).
double seam_force(const SeamDef& def, double d);

// How far the sewing is. A pair is closed when its particles have merged.
struct SeamProgress {
  std::string name;      // the seam's name ("" for the total)
  int closed = 0;        // pairs merged
  int total = 0;         // pairs
  double max_gap = 0.0;  // m, largest distance of an open pair (0 when all closed)
  double mean_gap = 0.0; // m, mean distance of the open pairs (0 when all closed)
  bool waiting = false;  // not pulling yet: the seams it waits for are open (SeamPairs::after)
};
struct SeamReport {
  std::vector<SeamProgress> seams;  // one per SeamDef::seams entry
  SeamProgress total;
};

// The progress of a seam effect at the last frame boundary (gaps are measured
// when the System gathers merge requests, sim::run: every frame); nullptr for
// any other effect.
const SeamReport* seam_report(const Effect& e);

}  // namespace vgd::sim
