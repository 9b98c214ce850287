#pragma once
// The orthotropic fabric of the strain-rosette membrane and the bending model
// (seed 002 §3.1; docs/fabric-model.md). Sheet quantities: moduli are forces
// per unit width (N/m), bending rigidities moments per unit width per unit
// curvature (N·m). x is the warp (Model::uv's u), y the weft (v).
//
// The plane-stress law (Timoshenko & Goodier, Theory of Elasticity, §§ on
// orthotropic plates; seed 002 §3.1, with σ = Q (ε − ε₀)):
//
//   σ_xx = (E_x ε_xx + ν_yx E_x ε_yy) / (1 − ν_xy ν_yx)
//   σ_yy = (ν_xy E_y ε_xx + E_y ε_yy) / (1 − ν_xy ν_yx)
//   τ_xy = G_xy γ_xy
//
// with reciprocity E_y ν_xy = E_x ν_yx (the compliance matrix is symmetric).
//
// Default values: the worked example of ../shared/reference/mechanics.md §3
// (orthotropic_constants.csv), a plausible shirting-weight woven, not one
// measured fabric. Typical ranges quoted below are the usual FAST / Kawabata
// orders of magnitude for apparel wovens, for orientation only.
#include <limits>
#include <string>
#include <vector>

#include "vgd/sim/model.hpp"

namespace vgd::sim {

// A measured uniaxial tensile curve along one yarn direction (a Kawabata
// KES-FB1 or FAST-3 extension test): piecewise linear, extrapolated beyond its
// end points with the end segments' slopes.
struct StressStrainCurve {
  std::vector<double> strain;  // engineering strain (–), strictly increasing, e.g. {0, 0.01, 0.03, 0.06}
  std::vector<double> stress;  // sheet stress (N/m of width) at each strain, strictly increasing, e.g. {0, 10, 60, 240}
  bool empty() const { return strain.empty() && stress.empty(); }
};

inline constexpr double kDerived = std::numeric_limits<double>::quiet_NaN();

struct OrthotropicMaterial {
  // ---- membrane: plane stress, sheet moduli ----
  double E_warp = 5000.0;  // N/m, E_x: sheet Young's modulus along the warp; typical 1e3–2e4 (FAST-3 E100 of 0.5–10 %)
  double E_weft = 3000.0;  // N/m, E_y: along the weft; typical 1e3–2e4
  double G = 400.0;        // N/m, G_xy: in-plane sheet shear modulus; typical 20–500 (FAST G, Kawabata G ≈ 0.5–3 gf/cm/deg)
  double nu_warp_weft = 0.3;  // ν_xy = −ε_yy/ε_xx under stress along the warp (–); typical 0.1–0.5
  // ν_yx = −ε_xx/ε_yy under stress along the weft (–). kDerived (the default):
  // taken from reciprocity, ν_yx = ν_xy E_y / E_x (0.18 here). Given: checked
  // against reciprocity within kReciprocityTolerance (relative); the law then
  // still uses the reciprocal value, so that the stiffness is symmetric.
  double nu_weft_warp = kDerived;
  // Residual strains (–): the strain at which the fabric is free of stress, as
  // cut (seed 002's ε₀ₓₓ, ε₀ᵧᵧ). Negative = the fabric wants to shrink (a
  // relaxation shrinkage of 1–3 % is common). Typical 0.
  double residual_warp = 0.0;
  double residual_weft = 0.0;
  // Optional measured curves (strain → sheet stress). Empty = linear with
  // E_warp / E_weft. A curve must pass through (residual, 0): its stress-free
  // strain is the residual strain of its direction. A tensile test along that
  // yarn then follows the curve exactly, with the lateral contraction −ν ε
  // (strain_rosette.hpp). E_warp and E_weft still give ν_yx by reciprocity:
  // set them to the curves' small-strain slopes.
  StressStrainCurve curve_warp;
  StressStrainCurve curve_weft;

  // ---- bending (plate rigidities per unit width) ----
  double B_warp = 1.0e-5;  // N·m, B_x = D₁₁: bending along the warp (curvature in the u direction); typical 2e-6–5e-5 (FAST-2)
  double B_weft = 6.0e-6;  // N·m, B_y = D₂₂: along the weft; typical 2e-6–5e-5
  // N·m, D₆₆: twisting rigidity per unit width. kDerived (the default): the
  // source paper's shear term with its units fixed, G_sheet h²/12 (= G₃D h³/12,
  // 8.33e-6 here; mechanics.md §3). Give a measured or smaller value for
  // limp fabrics: the continuum estimate makes B₄₅ 32 % above B_x here.
  double D_twist = kDerived;

  // ---- mass and geometry ----
  double density = 0.2;       // kg/m², areal density; typical 0.05 (voile) – 0.5 (denim)
  double thickness = 0.0005;  // m; typical 0.2–1.5 mm (KES-FB3 at 50 Pa); used for D_twist when derived
};

// Relative tolerance of the reciprocity check |E_y ν_xy − E_x ν_yx| ≤ tol·E_x ν_yx.
inline constexpr double kReciprocityTolerance = 1e-3;

// ν_yx as used by the law: ν_xy E_y / E_x (reciprocity).
double nu_weft_warp(const OrthotropicMaterial& m);
// D₆₆ (N·m) as used by the bending law: D_twist, or G h²/12 when derived.
double twist_rigidity(const OrthotropicMaterial& m);

// Everything wrong with a material, one sentence per problem, each naming the
// field ("E_warp", "curve_weft", ...); empty when the material is usable.
// Rejected: negative, zero or non-finite moduli, rigidities, density or
// thickness; ν that make the compliance not positive definite
// (1 − ν_xy ν_yx ≤ 0); a given ν_yx that violates reciprocity; curves with
// fewer than 2 points, mismatched lengths, non-finite values, a strain or
// stress that does not strictly increase, or that miss (residual, 0); bending
// rigidities that make the plate's D not positive definite.
std::vector<std::string> problems(const OrthotropicMaterial& m);
// Throws SimulationError("material <what>: <first problem>; <second> ...") if
// problems(m) is not empty.
void validate(const OrthotropicMaterial& m, const std::string& what = "");

// The material of each triangle: an index into per_piece by
// Model::triangle_piece, or 0 for all when per_piece has one entry. Validates
// every material a triangle uses; throws SimulationError naming the piece
// and the field, or a piece without a material.
std::vector<int> triangle_materials(const Model& m, const std::vector<OrthotropicMaterial>& per_piece);

// Off-axis Young's modulus (N/m) for uniaxial stress at angle theta (rad) from
// the warp (mechanics.md §3; Lekhnitskii / Jones, Mechanics of Composite
// Materials, eq. 2.97):
//   1/E_θ = c⁴/E_x + (1/G_xy − 2ν_xy/E_x) s²c² + s⁴/E_y,  c = cos θ, s = sin θ.
double off_axis_modulus(const OrthotropicMaterial& m, double theta_rad);

// Bending rigidity (N·m) of the plate for a cylindrical bend whose curvature
// lies at angle theta (rad) from the warp, the transverse curvature held at
// zero (the consistent form of mechanics.md §3):
//   B_θ = D₁₁ c⁴ + 2 (D₁₂ + 2 D₆₆) c² s² + D₂₂ s⁴,
//   D₁₁ = B_x, D₂₂ = B_y, D₁₂ = ν_yx B_x (= ν_xy B_y when B_y/B_x = E_y/E_x), D₆₆ = twist_rigidity.
double bending_rigidity(const OrthotropicMaterial& m, double theta_rad);

// The narrow-strip (compliance) value 1/(D⁻¹)′₁₁ (N·m): the transverse
// curvature free, as in a cantilever strip; B_x (1 − ν_yx² B_x/B_y) at θ = 0.
double bending_rigidity_strip(const OrthotropicMaterial& m, double theta_rad);

}  // namespace vgd::sim
