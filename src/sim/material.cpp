// The orthotropic fabric: derived constants, validation, off-axis moduli and
// bending rigidities (mechanics.md §3).
#include "vgd/sim/material.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "vgd/sim/types.hpp"

namespace vgd::sim {

namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// A modulus-like field must be finite and > 0.
void positive(std::vector<std::string>& out, const char* field, double v, const char* unit) {
  if (!std::isfinite(v) || !(v > 0.0))
    out.push_back(std::string(field) + " is " + num(v) + " " + unit + "; it must be a finite number > 0");
}

// Linear interpolation / end-segment extrapolation of a valid curve at strain e.
double curve_at(const StressStrainCurve& c, double e) {
  const auto& x = c.strain;
  std::size_t k = 0;
  while (k + 2 < x.size() && e > x[k + 1]) ++k;
  return c.stress[k] + (c.stress[k + 1] - c.stress[k]) / (x[k + 1] - x[k]) * (e - x[k]);
}

// Checks one curve.
void check_curve(std::vector<std::string>& out, const char* field, const StressStrainCurve& c, double residual,
                 const char* residual_field) {
  if (c.empty()) return;
  const std::string f = field;
  if (c.strain.size() != c.stress.size()) {
    out.push_back(f + " has " + std::to_string(c.strain.size()) + " strains but " + std::to_string(c.stress.size()) +
                  " stresses; give one stress (N/m) per strain");
    return;
  }
  if (c.strain.size() < 2) {
    out.push_back(f + " has " + std::to_string(c.strain.size()) + " point(s); a curve needs at least 2");
    return;
  }
  for (std::size_t k = 0; k < c.strain.size(); ++k)
    if (!std::isfinite(c.strain[k]) || !std::isfinite(c.stress[k])) {
      out.push_back(f + " point " + std::to_string(k) + " is not finite");
      return;
    }
  for (std::size_t k = 0; k + 1 < c.strain.size(); ++k) {
    if (!(c.strain[k + 1] > c.strain[k])) {
      out.push_back(f + " strain does not increase between points " + std::to_string(k) + " and " +
                    std::to_string(k + 1) + " (" + num(c.strain[k]) + ", " + num(c.strain[k + 1]) + ")");
      return;
    }
    if (!(c.stress[k + 1] > c.stress[k])) {
      out.push_back(f + " is not monotone increasing: stress " + num(c.stress[k]) + " N/m at point " +
                    std::to_string(k) + ", " + num(c.stress[k + 1]) + " N/m at point " + std::to_string(k + 1) +
                    " (a fabric's tensile curve must rise; a flat or falling segment is not elastic)");
      return;
    }
  }
  double scale = 0.0;
  for (double s : c.stress) scale = std::max(scale, std::abs(s));
  const double at_residual = curve_at(c, residual);
  if (std::abs(at_residual) > 1e-9 * scale) {
    out.push_back(f + " does not pass through (" + std::string(residual_field) + ", 0) = (" + num(residual) +
                  ", 0): its stress there is " + num(at_residual) +
                  " N/m; start the curve at zero stress at the residual strain (0 unless a residual is given)");
    return;
  }
}

}  // namespace

double nu_weft_warp(const OrthotropicMaterial& m) { return m.nu_warp_weft * m.E_weft / m.E_warp; }

double twist_rigidity(const OrthotropicMaterial& m) {
  // G₃D h³/12 with G₃D = G_sheet/h: G_sheet h²/12 (N/m · m² = N·m).
  return std::isnan(m.D_twist) ? m.G * m.thickness * m.thickness / 12.0 : m.D_twist;
}

std::vector<std::string> problems(const OrthotropicMaterial& m) {
  std::vector<std::string> out;
  positive(out, "E_warp", m.E_warp, "N/m");
  positive(out, "E_weft", m.E_weft, "N/m");
  positive(out, "G", m.G, "N/m");
  positive(out, "B_warp", m.B_warp, "N·m");
  positive(out, "B_weft", m.B_weft, "N·m");
  positive(out, "density", m.density, "kg/m²");
  positive(out, "thickness", m.thickness, "m");
  if (!std::isnan(m.D_twist) && (!std::isfinite(m.D_twist) || m.D_twist < 0.0))
    out.push_back("D_twist is " + num(m.D_twist) + " N·m; it must be finite and ≥ 0 (or left derived)");
  if (!std::isfinite(m.residual_warp)) out.push_back("residual_warp is not finite");
  if (!std::isfinite(m.residual_weft)) out.push_back("residual_weft is not finite");
  const bool moduli_ok = out.empty() || (std::isfinite(m.E_warp) && m.E_warp > 0 && std::isfinite(m.E_weft) &&
                                         m.E_weft > 0 && std::isfinite(m.B_warp) && m.B_warp > 0 &&
                                         std::isfinite(m.B_weft) && m.B_weft > 0);

  // Poisson ratios: positive definite compliance, reciprocity.
  if (!std::isfinite(m.nu_warp_weft)) {
    out.push_back("nu_warp_weft is not finite");
  } else if (moduli_ok) {
    const double nyx = nu_weft_warp(m);
    const double det = 1.0 - m.nu_warp_weft * nyx;
    if (!(det > 0.0))
      out.push_back("nu_warp_weft = " + num(m.nu_warp_weft) + " with nu_weft_warp = " + num(nyx) +
                    " gives 1 − ν_xy ν_yx = " + num(det) +
                    " ≤ 0: the compliance is not positive definite (need ν_xy² < E_warp/E_weft = " +
                    num(m.E_warp / m.E_weft) + ")");
    if (!std::isnan(m.nu_weft_warp)) {
      if (!std::isfinite(m.nu_weft_warp))
        out.push_back("nu_weft_warp is not finite (leave it kDerived to take it from reciprocity)");
      else if (std::abs(m.E_weft * m.nu_warp_weft - m.E_warp * m.nu_weft_warp) >
               kReciprocityTolerance * std::max(std::abs(m.E_weft * m.nu_warp_weft), 1e-300))
        out.push_back("nu_weft_warp = " + num(m.nu_weft_warp) +
                      " violates reciprocity E_weft·nu_warp_weft = E_warp·nu_weft_warp (expected " + num(nyx) +
                      " within " + num(kReciprocityTolerance * 100) + " %)");
    }
    // Bending: D = [[B_x, ν_yx B_x], [ν_yx B_x, B_y]] must be positive definite.
    if (det > 0.0 && !(nyx * nyx * m.B_warp < m.B_weft))
      out.push_back("B_weft = " + num(m.B_weft) + " N·m is too small for the bending Poisson coupling D₁₂ = ν_yx B_warp = " +
                    num(nyx * m.B_warp) + " N·m (need ν_yx² B_warp < B_weft)");
  }

  // Curves.
  check_curve(out, "curve_warp", m.curve_warp, m.residual_warp, "residual_warp");
  check_curve(out, "curve_weft", m.curve_weft, m.residual_weft, "residual_weft");
  return out;
}

void validate(const OrthotropicMaterial& m, const std::string& what) {
  const auto p = problems(m);
  if (p.empty()) return;
  std::string msg = "material" + (what.empty() ? std::string() : " " + what) + ": ";
  for (std::size_t k = 0; k < p.size(); ++k) msg += (k ? "; " : "") + p[k];
  throw SimulationError(msg);
}

std::vector<int> triangle_materials(const Model& m, const std::vector<OrthotropicMaterial>& per_piece) {
  if (per_piece.empty()) throw SimulationError("no material given: give one per piece, or one for all pieces");
  const std::size_t nt = m.triangles.size();
  std::vector<int> idx(nt, 0);
  std::vector<bool> used(per_piece.size(), false);
  for (std::size_t t = 0; t < nt; ++t) {
    const int piece = m.triangle_piece.empty() ? 0 : m.triangle_piece[t];
    if (per_piece.size() > 1) {
      if (piece < 0 || piece >= static_cast<int>(per_piece.size()))
        throw SimulationError("triangle " + std::to_string(t) + " belongs to piece " + std::to_string(piece) +
                              ", which has no material (" + std::to_string(per_piece.size()) + " given)");
      idx[t] = piece;
    }
    used[idx[t]] = true;
  }
  for (std::size_t k = 0; k < per_piece.size(); ++k) {
    if (!used[k]) continue;
    std::string what;
    if (per_piece.size() == 1)
      what = "(all pieces)";
    else
      what = "of piece " + std::to_string(k) + (k < m.pieces.size() ? " '" + m.pieces[k] + "'" : std::string());
    validate(per_piece[k], what);
  }
  return idx;
}

double off_axis_modulus(const OrthotropicMaterial& m, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double c2 = c * c, s2 = s * s;
  const double inv = c2 * c2 / m.E_warp + (1.0 / m.G - 2.0 * m.nu_warp_weft / m.E_warp) * s2 * c2 + s2 * s2 / m.E_weft;
  return 1.0 / inv;
}

double bending_rigidity(const OrthotropicMaterial& m, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double c2 = c * c, s2 = s * s;
  const double D12 = nu_weft_warp(m) * m.B_warp, D66 = twist_rigidity(m);
  return m.B_warp * c2 * c2 + 2.0 * (D12 + 2.0 * D66) * c2 * s2 + m.B_weft * s2 * s2;
}

double bending_rigidity_strip(const OrthotropicMaterial& m, double theta) {
  // Bending compliance d = D⁻¹ maps moments (M_xx, M_yy, M_xy) to curvatures
  // (κ_xx, κ_yy, 2κ_xy). A moment M about the strip's transverse axis alone is
  // M (c², s², cs); the curvature along n = (c, s) is (c², s², cs)·κ, so
  // κ_θ = M vᵀ d v with v = (c², s², cs), and B_strip = 1 / vᵀ d v.
  const double c = std::cos(theta), s = std::sin(theta);
  const double D11 = m.B_warp, D22 = m.B_weft, D12 = nu_weft_warp(m) * m.B_warp, D66 = twist_rigidity(m);
  const double det = D11 * D22 - D12 * D12;
  const double d11 = D22 / det, d22 = D11 / det, d12 = -D12 / det;
  const double c2 = c * c, s2 = s * s;
  double compliance = d11 * c2 * c2 + 2.0 * d12 * c2 * s2 + d22 * s2 * s2;
  if (c2 * s2 > 0.0) {
    if (!(D66 > 0.0)) return 0.0;  // no twisting rigidity: an off-axis strip twists freely
    compliance += c2 * s2 / D66;
  }
  return 1.0 / compliance;
}

}  // namespace vgd::sim
