#pragma once
// The strain-rosette membrane (seed 002 §3.1) as one Effect ("strain-rosette").
//
// Each triangle is a rosette of three strain gauges, its edges (seed 002,
// Figure 9). Gauge k of rest vector D_k = (Δu, Δv) (m, in Model::uv, u = warp)
// and current 3-D length l_k reads the Green strain e_k = (l_k²/|D_k|² − 1)/2,
// and the rosette relation
//
//   l_k² = Δu² C_xx + Δv² C_yy + 2 Δu Δv C_xy          (k = 1, 2, 3)
//
// is solved for the metric C = FᵀF (right Cauchy–Green tensor) in the
// warp/weft frame with a 3×3 inverse precomputed per triangle. The relation is
// exact at any deformation (it is the definition of the metric), depends only
// on edge lengths, so rigid motions in 3-D give no strain. From C the yarn
// strains, which are what a tensile tester or a shear tester reads:
//
//   ε_xx = √C_xx − 1            engineering strain of the warp yarns
//   ε_yy = √C_yy − 1            engineering strain of the weft yarns
//   γ_xy = C_xy / √(C_xx C_yy)  sine of the shear angle between the yarns
//
// (= the small-strain ε_xx, ε_yy, γ_xy to first order). Stresses (N/m) follow
// the plane-stress orthotropic law of material.hpp, or the measured curves.
// The energy is U = Σ A_t W(ε_t) (A_t rest area, m²; W in J/m²), and the forces
// −∂U/∂x are central edge forces: the tension in edge k is
//
//   T_k = −2 l_k ∂U/∂(l_k²)   (N),  ∂U/∂(l²) = A T⁻ᵀ ∂W/∂C,
//
// the seed's "stress along each edge times its length". They are the
// consistent nodal forces of the membrane energy (tests prove it against
// −A P ∇N_i), and they conserve linear and angular momentum exactly.
//
// Measured curves: with u = ε − ε₀, the equivalent uniaxial strains
//   a_x = (u_x + ν_yx u_y)/(1 − ν_xy ν_yx),  a_y = (ν_xy u_x + u_y)/(1 − ν_xy ν_yx)
// turn the linear law into σ_x = E_x a_x, σ_y = E_y a_y; a curve replaces E a by
// S(ε₀ + a). A tensile test along a yarn (free sides) follows its curve
// exactly, with the given Poisson ratio at every strain; each direction's
// tangent S′ multiplies its direct and its coupled term. Such a law has no
// potential unless S_x′/S_y′ stays E_x/E_y: with curves the Jacobian is exact
// but not symmetric, and energy() is the work along the straight loading path
// from ε₀ (docs/fabric-model.md). The linear law is hyperelastic.
//
// Jacobian: exact (add_jacobian returns true). Stiffness bound: Gershgorin row
// sums of the rest stiffness, with each curve's steepest slope.
#include <memory>
#include <vector>

#include "vgd/sim/effect.hpp"
#include "vgd/sim/material.hpp"

namespace vgd::sim {

struct RosetteOptions {
  // Forces are computed by OpenMP threads when omp_get_max_threads() > 1 and
  // the model has at least this many triangles; below, threads cost more than
  // they save. The result is identical to the serial one, bit for bit
  // (per-element buffers gathered per particle). A run uses fewer threads
  // while other processes keep cores busy (sim/threads.hpp).
  int parallel_min_triangles = 1000;
  // The Jacobian implicit steps get: exact (false), or made definite (true;
  // scenes with a body: scene/build.cpp). Compressed, a triangle's exact
  // Hessian is indefinite (a gauge in compression has negative stiffness
  // across it, and the strain measures' curvature weighs by stress of either
  // sign), and M − h²K stopped being positive definite at 30 ms of a skirt's
  // drape. Definite: per triangle the Hessian in its three gauges symmetrised
  // with its negative eigenvalues set to 0, and each gauge's stress term
  // taken only in tension (as the mass-spring clamps a compressed spring's
  // transverse stiffness, Choi & Ko 2002). The forces are exact either way;
  // only the step's linearisation differs (docs/fabric-model.md, 4a).
  bool definite_jacobian = false;
};

// The effect for a model: one material per piece (by Model::triangle_piece), or
// one for all pieces. Throws SimulationError naming the piece and field of an
// invalid material, or a triangle of zero rest area.
std::unique_ptr<Effect> make_strain_rosette(const Model& m, const std::vector<OrthotropicMaterial>& per_piece,
                                            const RosetteOptions& options = {});

// ---- kernels, for tests and the material lab ----

// Yarn strains (ε_xx, ε_yy, γ_xy) (–) of triangle `t` of m at positions x (3N, m).
Vec3 rosette_strain(const Model& m, int t, const VecX& x);
// Sheet stresses (σ_xx, σ_yy, τ_xy) (N/m) of a (valid) material at yarn strains.
Vec3 rosette_stress(const OrthotropicMaterial& mat, const Vec3& strain);
// Energy per rest area W (J/m²) at yarn strains; W = 0 at the residual strains
// (for measured curves, the work along the straight path from them).
double rosette_energy_density(const OrthotropicMaterial& mat, const Vec3& strain);

}  // namespace vgd::sim
