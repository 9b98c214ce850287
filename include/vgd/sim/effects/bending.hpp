#pragma once
// Bending across the interior edges (seed 002 §3.1, "a cantilever beam bending
// across a given edge of the mesh") as one Effect ("bending").
//
// Hinges. Every interior edge of a piece is a hinge between its two triangles;
// θ_e (rad) is the signed dihedral angle between their normals, 0 when flat
// (the rest shape is the flat pattern, Model::uv). θ is invariant under rigid
// motion, so the model holds for large deflections with small angles per hinge.
//
// Curvature per triangle (a rotation-free Morley triangle). By Green's theorem
// over a triangle T of area A, the mean of the surface's Hessian is
//
//   κ_T = (1/A) Σ_{e∈T} L_e β_e (n_e⊗n_e),   κ = (κ_xx, κ_yy, 2κ_xy) (1/m, warp/weft frame)
//
// with β_e the normal slope at the edge's midpoint relative to T's plane. A
// hinge angle is the sum of its two sides' β (β_T + β_T′ = θ_e); the split is
// θ/2 each plus a correction from the local curvature (the "curvature gauges":
// for z = ½ xᵀKx each hinge reads θ_e = w_e·κ exactly, so a triangle's three
// hinges determine κ, the bending twin of the strain rosette). The result is
// exact for quadratic surfaces on any mesh, and Σ_T A_T κ_T = Σ_e L_e θ_e n⊗n
// depends on the boundary only, so a uniform moment leaves inner particles
// without force (the plate patch test). At a free edge no moment crosses:
// its slope is chosen so that M_nn = (n⊗n)·Dκ = 0 (Morley's natural condition).
//
// Energy, the plate's (mechanics.md §3, consistent form):
//
//   U = Σ_T ½ A_T κ_Tᵀ D κ_T,   D = [[B_x, ν_yx B_x, 0], [ν_yx B_x, B_y, 0], [0, 0, D₆₆]]   (N·m)
//
// so a sheet bent into a cylinder along θ carries the moment B_θ κ of
// material.hpp's bending_rigidity (plate) away from its free edges, and a
// narrow free strip the strip value (bending_rigidity_strip).
//
// Forces −∂U/∂x = −Σ_e M_e ∇θ_e, M_e = ∂U/∂θ_e (N·m): at each hinge's two
// opposite vertices a force M_e/h along that triangle's normal (seed 002's
// F_θ = M_θ/L₁ at the tip of the cantilever of length L₁ = h across the edge),
// and at the edge vertices the two forces that cancel their sum and moment (the
// seed's restoring forces that keep linear momentum; angular momentum is kept
// too).
//
// Scaling: κ_T ∝ θ/h, so U converges to ∫ ½ κᵀDκ dA as the mesh is refined
// (tests: a cantilever's tip deflection to O(h²), a cylinder's moment to O(h)
// with free edges); the stiffness per particle ∝ B/h², explicit steps ∝ h².
// A clamp made by holding two rows of particles acts at the middle of the
// held row of cells.
//
// Jacobian: exact, including the dihedral angle's second derivatives
// (add_jacobian returns true).
#include <memory>
#include <vector>

#include "vgd/sim/effect.hpp"
#include "vgd/sim/material.hpp"

namespace vgd::sim {

struct BendingOptions {
  // Forces are computed by OpenMP threads when omp_get_max_threads() > 1 and
  // the model has at least this many hinges; identical to serial, bit for bit.
  // A run uses fewer threads while other processes keep cores busy (sim/threads.hpp).
  int parallel_min_hinges = 1000;
  // The Jacobian implicit steps get: exact (false), or made definite (true;
  // scenes with a body: scene/build.cpp). The exact Hessian is
  // Σ_T A (C_T ∇θ)ᵀ D (C_T ∇θ) + Σ_h M_h ∇²θ_h; the second sum, the moments
  // times the angles' curvature, is indefinite (a strain-rosette T-shirt's
  // drape was refused at 4.6 s for it). Definite: the first sum alone
  // (Gauss–Newton), positive semi-definite. The forces are exact either way;
  // only the step's linearisation differs.
  bool definite_jacobian = false;
};

// The effect for a model: one material per piece (by Model::triangle_piece) or
// one for all. Throws SimulationError for an invalid material, an edge shared
// by more than two triangles of a piece, or two triangles that lie on the same
// side of their shared edge in the pattern (overlapping). Hinges join only
// triangles of the same piece; either orientation of a piece's triangles is
// accepted (each hinge takes its normals from the pattern's orientation).
std::unique_ptr<Effect> make_bending(const Model& m, const std::vector<OrthotropicMaterial>& per_piece,
                                     const BendingOptions& options = {});

// The curvature a bending effect sees in one triangle.
struct TriangleCurvature {
  Vec3 kappa = Vec3::Zero();  // (κ_xx, κ_yy, 2κ_xy), 1/m, warp/weft frame
  int hinges = 0;             // interior edges of the triangle (3 = fully measured)
};
// Per triangle, at positions x (3N, m). Empty if `bending` is not a bending effect.
std::vector<TriangleCurvature> bending_curvatures(const Effect& bending, const VecX& x);

}  // namespace vgd::sim
