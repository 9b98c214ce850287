#pragma once
// Yarn strain limiting on triangles: after each step no triangle of a limited
// piece is stretched along the warp or the weft beyond (1 + limit) times its
// rest length there (within `tolerance`), whatever the mesh.
//
// A woven's yarns barely stretch: its tensile curve is soft for the first
// percent (crimp straightening) and then locks. A linear cloth model (springs
// or a membrane) has no lock, so a sleeve pushed by an arm or a cap pulled
// into an armhole stretches 30-50 % where the real fabric would move instead.
// Provot's limit (MassSpringMaterial::max_strain) acts on springs along the
// warp and the weft; on an unstructured mesh few edges lie along the yarns, a
// triangle stretched along the weft by shearing its edges keeps every edge
// within the limit, and the limit does not bound the strain the certificate
// measures.
//
// Here each triangle's deformation gradient F = [F_u F_v] (3 × 2, against its
// flat pattern: u warp, v weft, Model::uv) is the measure, as in the
// certificate: warp strain |F_u| − 1, weft strain |F_v| − 1 (continuum strain
// limiting, Thomaszewski, Pabst and Straßer 2009, restricted to the yarn
// directions; the bias, a woven's soft direction, stays free). A triangle over
// the limit gets the gradient F' with the offending column scaled back to
// 1 + limit, and its corners move to c + F'(X_i − X_c), c and X_c the
// mass-weighted centroids now and at rest: momentum is kept, the triangle
// keeps its orientation and shear. The stretching part of its velocity along
// that yarn is removed the same way (the rate u_yarnᵀ L e_yarn of the velocity
// gradient L, when positive). Gauss–Seidel passes over the limited triangles
// repeat until one corrects nothing or `passes` is reached; the stats say when
// they did not converge. Pinned particles do not move: a triangle with pinned
// corners moves its free ones only (by the same shape, shifted so the pinned
// corners stay).
//
// Order in the step: after the cloth model's own hooks and before seams'
// merges and the contacts, which have the last word (a particle the body
// pushes out stays out, and the certificate says if that stretched the cloth).
//
// Units: limits dimensionless (0.05 = 5 %); positions m; velocities m/s.
#include <memory>
#include <vector>

#include "vgd/sim/effect.hpp"

namespace vgd::sim {

struct StrainLimitDef {
  // Per piece (Model::pieces order): the largest warp and weft strain, 0 = no
  // limit on that piece. At least one must be > 0.
  std::vector<double> limit;
  std::vector<int> fixed;     // particles the limiter must not move (pins)
  int passes = 30;            // most Gauss–Seidel passes per step
  double tolerance = 1e-3;    // relative overshoot of 1 + limit left alone
};

struct StrainLimitStats {
  int triangles = 0;          // limited triangles
  long corrections = 0;       // triangle corrections, all steps
  long limited_steps = 0;     // steps in which anything was corrected
  long unresolved_steps = 0;  // steps whose passes ran out with a triangle over the limit
  int last_passes = 0;        // passes of the last step
  int last_unresolved = 0;    // triangles over the limit after the last step
};

std::unique_ptr<Effect> make_strain_limit(const Model& model, const StrainLimitDef& def);
// The stats of an effect made by make_strain_limit (nullptr for any other).
const StrainLimitStats* strain_limit_stats(const Effect& effect);

}  // namespace vgd::sim
