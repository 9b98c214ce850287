// The strain-rosette membrane (seed 002 §3.1); formulas in strain_rosette.hpp.
//
// [SECTION] the constitutive law (linear and measured curves)
// [SECTION] the rosette kernel of one triangle (gauges, forces, Hessian)
// [SECTION] the effect: precomputed rest data, three-pass forces, Jacobian, bounds
// [SECTION] public kernels
#include "vgd/sim/effects/strain_rosette.hpp"

#include "vgd/sim/system.hpp"

#include <omp.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace vgd::sim {

namespace {

// =============================================================================
// [SECTION] the constitutive law
// =============================================================================

// A strictly increasing piecewise-linear map ε (–) → σ (N/m), extrapolated with
// its end slopes; validated by material.cpp before it gets here.
class Curve {
 public:
  Curve() = default;
  // Knots (strain, stress); `rest` is the strain where the stress is 0.
  Curve(std::vector<double> e, std::vector<double> s, double rest) : e_(std::move(e)), s_(std::move(s)) {
    const std::size_t n = e_.size();
    m_.resize(n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k) m_[k] = (s_[k + 1] - s_[k]) / (e_[k + 1] - e_[k]);
    // p_k = ∫_{ε_0}^{ε_k} σ dε (trapezoids: exact for a piecewise-linear σ).
    p_.assign(n, 0.0);
    for (std::size_t k = 0; k + 1 < n; ++k) p_[k + 1] = p_[k] + 0.5 * (e_[k + 1] - e_[k]) * (s_[k] + s_[k + 1]);
    rest_ = rest;
    rest_segment_ = segment(rest);
    area_rest_ = integral(rest);
  }
  // A straight line of slope E (N/m) through (rest, 0).
  static Curve linear(double E, double rest) { return Curve({rest - 1.0, rest + 1.0}, {-E, E}, rest); }

  // Segment of a strain (0 .. n−2; the end segments extend outwards).
  int segment(double e) const {
    const auto it = std::upper_bound(e_.begin() + 1, e_.end() - 1, e);
    return static_cast<int>(it - e_.begin()) - 1;
  }
  double slope(int k) const { return m_[k]; }  // N/m
  double stress(double e, int k) const { return s_[k] + m_[k] * (e - e_[k]); }
  // (1/a) ∫_rest^{rest+a} σ dε (N/m): the mean stress along a loading from rest.
  double mean_stress(double a) const {
    const double e = rest_ + a;
    const int k = segment(e);
    if (k == rest_segment_) return 0.5 * stress(e, k);  // on the rest segment, exactly (and safe at a = 0)
    return (integral(e) - area_rest_) / a;
  }
  double max_slope() const { return *std::max_element(m_.begin(), m_.end()); }

 private:
  double integral(double e) const {
    const int k = segment(e);
    return p_[k] + 0.5 * (e - e_[k]) * (s_[k] + stress(e, k));
  }
  std::vector<double> e_, s_, m_, p_;
  double rest_ = 0.0, area_rest_ = 0.0;
  int rest_segment_ = 0;
};

// One material, compiled for the kernel.
struct Law {
  double Q11 = 0, Q12 = 0, Q22 = 0, G = 0;  // N/m, plane-stress stiffness
  double e0x = 0, e0y = 0;                  // residual strains (–)
  double nxy = 0, nyx = 0, det = 1;         // ν_xy, ν_yx, 1 − ν_xy ν_yx
  bool curves = false;                      // measured curves (else the linear fast path)
  Curve cx, cy;                             // ε → σ per yarn direction (lines when not measured)
  double stiff_x = 0, stiff_y = 0;          // N/m, steepest slopes (stiffness bound)
};

Law compile(const OrthotropicMaterial& m) {
  Law L;
  L.nxy = m.nu_warp_weft;
  L.nyx = nu_weft_warp(m);
  L.det = 1.0 - L.nxy * L.nyx;
  // Plane stress (seed 002 §3.1; Timoshenko & Goodier): σ = Q (ε − ε₀).
  L.Q11 = m.E_warp / L.det;
  L.Q22 = m.E_weft / L.det;
  L.Q12 = L.nyx * m.E_warp / L.det;  // = ν_xy E_y / det
  L.G = m.G;
  L.e0x = m.residual_warp;
  L.e0y = m.residual_weft;
  L.curves = !m.curve_warp.empty() || !m.curve_weft.empty();
  L.cx = m.curve_warp.empty() ? Curve::linear(m.E_warp, m.residual_warp)
                              : Curve(m.curve_warp.strain, m.curve_warp.stress, m.residual_warp);
  L.cy = m.curve_weft.empty() ? Curve::linear(m.E_weft, m.residual_weft)
                              : Curve(m.curve_weft.strain, m.curve_weft.stress, m.residual_weft);
  L.stiff_x = L.cx.max_slope();
  L.stiff_y = L.cy.max_slope();
  return L;
}

// The law in "equivalent uniaxial strains": with u = ε − ε₀,
//   a_x = (u_x + ν_yx u_y)/(1 − ν_xy ν_yx),   a_y = (ν_xy u_x + u_y)/(1 − ν_xy ν_yx)
// is the warp (weft) strain of the uniaxial test that gives the same warp
// (weft) stress, and the linear law reads σ_x = E_x a_x, σ_y = E_y a_y. With a
// measured curve, E a becomes S(ε₀ + a): a tensile test along a yarn (a_y = 0,
// lateral strain −ν_xy u_x) reproduces the curve exactly, and the Poisson
// ratios stay the given ones at every strain. The tangent of a direction
// multiplies its direct and its coupled term alike:
//   ∂σ_x/∂ε = S_x′ (1, ν_yx)/(1 − ν_xy ν_yx),   ∂σ_y/∂ε = S_y′ (ν_xy, 1)/(1 − ν_xy ν_yx),
// which is symmetric only while S_x′/S_y′ = E_x/E_y: a law with independent
// curves and fixed Poisson ratios has no potential (docs/fabric-model.md).
inline void equivalent_strains(const Law& L, const Vec3& eps, double& ux, double& uy, double& ax, double& ay) {
  ux = eps[0] - L.e0x;
  uy = eps[1] - L.e0y;
  ax = (ux + L.nyx * uy) / L.det;
  ay = (L.nxy * ux + uy) / L.det;
}

// σ (N/m) and, if wanted, the tangent dσ/dε at yarn strains eps = (ε_x, ε_y, γ).
void law_stress(const Law& L, const Vec3& eps, Vec3& sigma, Mat3* D) {
  sigma[2] = L.G * eps[2];
  if (!L.curves) {
    const double ux = eps[0] - L.e0x, uy = eps[1] - L.e0y;
    sigma[0] = L.Q11 * ux + L.Q12 * uy;
    sigma[1] = L.Q12 * ux + L.Q22 * uy;
    if (D) *D << L.Q11, L.Q12, 0, L.Q12, L.Q22, 0, 0, 0, L.G;
    return;
  }
  double ux, uy, ax, ay;
  equivalent_strains(L, eps, ux, uy, ax, ay);
  const int kx = L.cx.segment(L.e0x + ax), ky = L.cy.segment(L.e0y + ay);
  sigma[0] = L.cx.stress(L.e0x + ax, kx);
  sigma[1] = L.cy.stress(L.e0y + ay, ky);
  if (D) {
    const double tx = L.cx.slope(kx) / L.det, ty = L.cy.slope(ky) / L.det;
    *D << tx, tx * L.nyx, 0, ty * L.nxy, ty, 0, 0, 0, L.G;
  }
}

// W (J/m²): ½(ε−ε₀)ᵀQ(ε−ε₀) + ½Gγ² for the linear law. With curves, the work
// done along the straight loading path from ε₀ to ε,
//   W = u_x (1/a_x)∫₀^{a_x} S_x + u_y (1/a_y)∫₀^{a_y} S_y + ½Gγ²,
// the stored energy for the linear law and along either yarn, a diagnostic
// (not a potential of the forces) elsewhere.
double law_energy(const Law& L, const Vec3& eps) {
  const double shear = 0.5 * L.G * eps[2] * eps[2];
  if (!L.curves) {
    const double ux = eps[0] - L.e0x, uy = eps[1] - L.e0y;
    return 0.5 * (L.Q11 * ux * ux + 2.0 * L.Q12 * ux * uy + L.Q22 * uy * uy) + shear;
  }
  double ux, uy, ax, ay;
  equivalent_strains(L, eps, ux, uy, ax, ay);
  return ux * L.cx.mean_stress(ax) + uy * L.cy.mean_stress(ay) + shear;
}

// =============================================================================
// [SECTION] the rosette kernel of one triangle
// =============================================================================

// Smallest C_xx, C_yy admitted (a triangle crushed flat along a yarn).
constexpr double kMinMetric = 1e-12;

// The rosette inverse of a triangle: C = Tinv q, where row k of T is
// (Δu², Δv², 2ΔuΔv) of edge k (vertex k → k+1) and q_k its squared length.
Mat3 rosette_inverse(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 d[3] = {b - a, c - b, a - c};
  Mat3 T;
  for (int k = 0; k < 3; ++k) T.row(k) << d[k].x() * d[k].x(), d[k].y() * d[k].y(), 2.0 * d[k].x() * d[k].y();
  return T.inverse();
}

// The gauges of a triangle at positions x: edge vectors, the metric, yarn strains.
struct Gauges {
  Vec3 d[3];       // current edge vectors x_{k+1} − x_k (m)
  double C11, C22, C12;  // metric in the warp/weft frame (–)
  double sx, sy;   // √C11, √C22: yarn stretches
  Vec3 eps;        // ε_x, ε_y, γ
};

inline void read_gauges(const double* Ti, const double* x, const int* v, Gauges& g) {
  const double* p0 = x + 3 * v[0];
  const double* p1 = x + 3 * v[1];
  const double* p2 = x + 3 * v[2];
  g.d[0] = Vec3(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]);
  g.d[1] = Vec3(p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]);
  g.d[2] = Vec3(p0[0] - p2[0], p0[1] - p2[1], p0[2] - p2[2]);
  const double q0 = g.d[0].squaredNorm(), q1 = g.d[1].squaredNorm(), q2 = g.d[2].squaredNorm();
  // The rosette relation solved for the metric (seed 002: "solving a linear system of three equations").
  g.C11 = std::max(Ti[0] * q0 + Ti[1] * q1 + Ti[2] * q2, kMinMetric);
  g.C22 = std::max(Ti[3] * q0 + Ti[4] * q1 + Ti[5] * q2, kMinMetric);
  g.C12 = Ti[6] * q0 + Ti[7] * q1 + Ti[8] * q2;
  g.sx = std::sqrt(g.C11);
  g.sy = std::sqrt(g.C22);
  g.eps = Vec3(g.sx - 1.0, g.sy - 1.0, g.C12 / (g.sx * g.sy));
}

// ∂U/∂q_k (N/m, U = A W) from the stress: the chain W → (ε, γ) → C → q,
//   ∂W/∂C = σ_x ∂ε_x/∂C + σ_y ∂ε_y/∂C + τ ∂γ/∂C,  ∂U/∂q = A Tinvᵀ ∂W/∂C.
inline void gauge_gradient(const Gauges& g, const Vec3& s, const double* Ti, double A, double gq[3]) {
  const double gam = g.eps[2];
  const double w11 = 0.5 * s[0] / g.sx - 0.5 * s[2] * gam / g.C11;
  const double w22 = 0.5 * s[1] / g.sy - 0.5 * s[2] * gam / g.C22;
  const double w12 = s[2] / (g.sx * g.sy);
  for (int k = 0; k < 3; ++k) gq[k] = A * (Ti[k] * w11 + Ti[3 + k] * w22 + Ti[6 + k] * w12);
}

// The Hessian of U = A W(ε(C(q))) in x, as 3×3 particle blocks K[i][j]:
//   K = Σ_kl H_kl ∇q_k ∇q_lᵀ + Σ_k g_k ∇²q_k,
//   H = A Tinvᵀ (Jᵀ D J + Σ_m σ_m ∇²_C ε_m) Tinv,   J = ∂(ε_x, ε_y, γ)/∂(C11, C22, C12),
//   ∇_{k+1} q_k = 2 d_k = −∇_k q_k,   ∇²q_k = 2 [I −I; −I I] on its two vertices.
void hessian_blocks(const Gauges& g, const Vec3& s, const Mat3& D, const double* Ti, double A, Mat3 K[3][3],
                    bool definite = false) {
  const double gam = g.eps[2], sxy = g.sx * g.sy;
  Mat3 J;
  J << 0.5 / g.sx, 0, 0,                                   //
      0, 0.5 / g.sy, 0,                                    //
      -0.5 * gam / g.C11, -0.5 * gam / g.C22, 1.0 / sxy;  //
  Mat3 HC = J.transpose() * D * J;
  // Curvature of the strain measures (second derivatives in C).
  HC(0, 0) += s[0] * (-0.25 / (g.C11 * g.sx)) + s[2] * (0.75 * gam / (g.C11 * g.C11));
  HC(1, 1) += s[1] * (-0.25 / (g.C22 * g.sy)) + s[2] * (0.75 * gam / (g.C22 * g.C22));
  const double h01 = s[2] * 0.25 * gam / (g.C11 * g.C22);
  const double h02 = s[2] * (-0.5 / (g.C11 * sxy));
  const double h12 = s[2] * (-0.5 / (g.C22 * sxy));
  HC(0, 1) += h01, HC(1, 0) += h01;
  HC(0, 2) += h02, HC(2, 0) += h02;
  HC(1, 2) += h12, HC(2, 1) += h12;
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> T(Ti);
  Mat3 H = A * T.transpose() * HC * T;
  double gq[3];
  gauge_gradient(g, s, Ti, A, gq);
  if (definite) {
    // Symmetrised, its negative eigenvalues to 0; the gauges' stress terms in
    // tension only (RosetteOptions::definite_jacobian). Then K = Σ H_kl ∇q_k
    // ∇q_lᵀ + Σ g_k ∇²q_k is a sum of positive semi-definite terms.
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(0.5 * (H + H.transpose()));
    H = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
    for (double& v : gq) v = std::max(v, 0.0);
  }
  // a[i][k] = ∇_i q_k.
  Vec3 a[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) a[i][k].setZero();
  for (int k = 0; k < 3; ++k) {
    a[(k + 1) % 3][k] = 2.0 * g.d[k];
    a[k][k] = -2.0 * g.d[k];
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Mat3 b = Mat3::Zero();
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          if (H(k, l) != 0.0) b += H(k, l) * a[i][k] * a[j][l].transpose();
      K[i][j] = b;
    }
  for (int k = 0; k < 3; ++k) {
    const int i = k, j = (k + 1) % 3;
    const Mat3 gI = 2.0 * gq[k] * Mat3::Identity();
    K[i][i] += gI, K[j][j] += gI, K[i][j] -= gI, K[j][i] -= gI;
  }
}

// =============================================================================
// [SECTION] the effect
// =============================================================================

class StrainRosette final : public Effect, public BlockJacobianEffect {
 public:
  StrainRosette(const Model& m, const std::vector<OrthotropicMaterial>& per_piece, const RosetteOptions& o)
      : n_(m.num_particles()), options_(o) {
    validate(m);
    const std::vector<int> mat = triangle_materials(m, per_piece);
    for (const auto& p : per_piece) laws_.push_back(compile(p));
    const int nt = static_cast<int>(m.triangles.size());
    tv_.resize(3 * nt);
    ti_.resize(9 * nt);
    area_.resize(nt);
    law_.resize(nt);
    for (int t = 0; t < nt; ++t) {
      const auto& tri = m.triangles[t];
      const Vec2 a = m.uv[tri[0]], b = m.uv[tri[1]], c = m.uv[tri[2]];
      const Vec2 ab = b - a, ac = c - a;
      const double area = 0.5 * std::abs(ab.x() * ac.y() - ab.y() * ac.x());
      const double scale = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
      if (!(area > 1e-12 * scale) || !std::isfinite(area))
        throw SimulationError("strain-rosette: triangle " + std::to_string(t) + " (particles " +
                              std::to_string(tri[0]) + ", " + std::to_string(tri[1]) + ", " + std::to_string(tri[2]) +
                              ") has no area in the pattern (uv); remesh the piece");
      const Mat3 Ti = rosette_inverse(a, b, c);
      for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) ti_[9 * t + 3 * r + col] = Ti(r, col);
      for (int k = 0; k < 3; ++k) tv_[3 * t + k] = tri[k];
      area_[t] = area;
      law_[t] = mat[t];
    }
    gq_.assign(3 * nt, 0.0);
    build_edges(nt);
    rest_bound(m);
  }

  const char* name() const override { return "strain-rosette"; }

  // Two passes, each over independent outputs (hence parallel and
  // bit-identical to serial): triangles → ∂U/∂q per gauge; particles → Σ over
  // its edges of the central forces 2 w_e (x_j − x_i), w_e the sum of the
  // edge's gauges' ∂U/∂q in a fixed order.
  void add_forces(const Eval& e, VecX& f) override {
    const double* x = e.x.data();
    const int nt = static_cast<int>(area_.size());
    const bool par = omp_get_max_threads() > 1 && nt >= options_.parallel_min_triangles;
#pragma omp parallel if (par)
    {
#pragma omp for schedule(static)
      for (int t = 0; t < nt; ++t) gauge_forces(t, x);
#pragma omp for schedule(static)
      for (int i = 0; i < n_; ++i) {
        if (adj_off_[i] == adj_off_[i + 1]) continue;
        const double xi = x[3 * i], yi = x[3 * i + 1], zi = x[3 * i + 2];
        double fx = 0, fy = 0, fz = 0;
        for (int a = adj_off_[i]; a < adj_off_[i + 1]; ++a) {
          // The edge's coefficient: its gauges' ∂U/∂q, in a fixed order.
          const int ed = adj_edge_[a];
          double w = 0.0;
          for (int k = slot_off_[ed]; k < slot_off_[ed + 1]; ++k) w += gq_[slots_[k]];
          const double w2 = 2.0 * w;
          const int j = adj_other_[a];
          fx += w2 * (x[3 * j] - xi);
          fy += w2 * (x[3 * j + 1] - yi);
          fz += w2 * (x[3 * j + 2] - zi);
        }
        f[3 * i] += fx;
        f[3 * i + 1] += fy;
        f[3 * i + 2] += fz;
      }
    }
  }

  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets&) override {
    element_hessians(e.x.data(), [&](int t, const Mat3 (&K)[3][3]) {
      const int* v = &tv_[3 * t];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) add_block(dfdx, v[i], v[j], -K[i][j]);
    });
    return true;
  }

  // The same blocks as add_jacobian, in the same order, straight into the
  // System's block pattern: each triangle's nine slots looked up once per
  // pattern version (through triplets, assembly took 45 % of a drape).
  bool add_jacobian_blocks(const Eval& e, JacobianAssembler& out) override {
    const int nt = static_cast<int>(area_.size());
    if (blocks_version_ != out.version()) {
      blocks_.resize(9 * static_cast<std::size_t>(nt));
      for (int t = 0; t < nt; ++t)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) blocks_[9 * t + 3 * i + j] = out.slot(tv_[3 * t + i], tv_[3 * t + j]);
      blocks_version_ = out.version();
    }
    element_hessians(e.x.data(), [&](int t, const Mat3 (&K)[3][3]) {
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const int q = blocks_[9 * t + 3 * i + j];
          if (q < 0) continue;  // a prescribed particle
          double* b = out.dfdx(q);  // row-major
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) b[3 * r + c] -= K[i][j](r, c);
        }
    });
    return true;
  }

  // Each triangle's Hessian blocks K[i][j] of U at x (made definite if the
  // options say so), in triangle order: sink(t, K).
  template <class Sink>
  void element_hessians(const double* x, Sink&& sink) const {
    Mat3 K[3][3];
    for (int t = 0; t < static_cast<int>(area_.size()); ++t) {
      Gauges g;
      const double* Ti = &ti_[9 * t];
      read_gauges(Ti, x, &tv_[3 * t], g);
      Vec3 s;
      Mat3 D;
      law_stress(laws_[law_[t]], g.eps, s, &D);
      hessian_blocks(g, s, D, Ti, area_[t], K, options_.definite_jacobian);
      sink(t, K);
    }
  }

  double energy(const Eval& e) const override {
    const double* x = e.x.data();
    double u = 0.0;
    for (std::size_t t = 0; t < area_.size(); ++t) {
      Gauges g;
      read_gauges(&ti_[9 * t], x, &tv_[3 * t], g);
      u += area_[t] * law_energy(laws_[law_[t]], g.eps);
    }
    return u;
  }

  void add_stiffness_bound(const Model&, VecX& k_rows, VecX&) const override { k_rows += k_bound_; }

 private:
  // ∂U/∂q_k of triangle t into gq_ (the hot loop: scalars only, no temporaries
  // that the compiler would spill and reload through the stack).
  void gauge_forces(int t, const double* x) {
    const int* v = &tv_[3 * t];
    const double* p0 = x + 3 * v[0];
    const double* p1 = x + 3 * v[1];
    const double* p2 = x + 3 * v[2];
    const double ax = p1[0] - p0[0], ay = p1[1] - p0[1], az = p1[2] - p0[2];
    const double bx = p2[0] - p1[0], by = p2[1] - p1[1], bz = p2[2] - p1[2];
    const double cx = p0[0] - p2[0], cy = p0[1] - p2[1], cz = p0[2] - p2[2];
    const double q0 = ax * ax + ay * ay + az * az, q1 = bx * bx + by * by + bz * bz, q2 = cx * cx + cy * cy + cz * cz;
    const double* Ti = &ti_[9 * t];
    const double C11 = std::max(Ti[0] * q0 + Ti[1] * q1 + Ti[2] * q2, kMinMetric);
    const double C22 = std::max(Ti[3] * q0 + Ti[4] * q1 + Ti[5] * q2, kMinMetric);
    const double C12 = Ti[6] * q0 + Ti[7] * q1 + Ti[8] * q2;
    const double sx = std::sqrt(C11), sy = std::sqrt(C22), isxy = 1.0 / (sx * sy);
    const double gam = C12 * isxy;
    const Law& L = laws_[law_[t]];
    double s0, s1, s2;
    if (!L.curves) {
      const double ux = sx - 1.0 - L.e0x, uy = sy - 1.0 - L.e0y;
      s0 = L.Q11 * ux + L.Q12 * uy;
      s1 = L.Q12 * ux + L.Q22 * uy;
      s2 = L.G * gam;
    } else {
      Vec3 sg;
      law_stress(L, Vec3(sx - 1.0, sy - 1.0, gam), sg, nullptr);
      s0 = sg[0], s1 = sg[1], s2 = sg[2];
    }
    // ∂W/∂C, then ∂U/∂q = A Tinvᵀ ∂W/∂C (as gauge_gradient).
    const double w11 = 0.5 * (s0 / sx - s2 * gam / C11);
    const double w22 = 0.5 * (s1 / sy - s2 * gam / C22);
    const double w12 = s2 * isxy;
    const double A = area_[t];
    double* g = &gq_[3 * t];
    g[0] = A * (Ti[0] * w11 + Ti[3] * w22 + Ti[6] * w12);
    g[1] = A * (Ti[1] * w11 + Ti[4] * w22 + Ti[7] * w12);
    g[2] = A * (Ti[2] * w11 + Ti[5] * w22 + Ti[8] * w12);
  }

  // Edges (each once) with the gauge slots (3t + k) that measure them, and per
  // particle its edges and neighbours, in a fixed order.
  void build_edges(int nt) {
    struct Item {
      int a, b, slot;
    };
    std::vector<Item> items;
    items.reserve(3 * nt);
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) {
        const int p = tv_[3 * t + k], q = tv_[3 * t + (k + 1) % 3];
        items.push_back({std::min(p, q), std::max(p, q), 3 * t + k});
      }
    std::sort(items.begin(), items.end(),
              [](const Item& l, const Item& r) { return std::tie(l.a, l.b, l.slot) < std::tie(r.a, r.b, r.slot); });
    std::vector<int> ea, eb;
    slot_off_.push_back(0);
    for (std::size_t s = 0; s < items.size(); ++s) {
      if (s == 0 || items[s].a != items[s - 1].a || items[s].b != items[s - 1].b) {
        if (s > 0) slot_off_.push_back(static_cast<int>(slots_.size()));
        ea.push_back(items[s].a);
        eb.push_back(items[s].b);
      }
      slots_.push_back(items[s].slot);
    }
    if (!items.empty()) slot_off_.push_back(static_cast<int>(slots_.size()));
    const int ne = static_cast<int>(ea.size());
    std::vector<int> count(n_ + 1, 0);
    for (int ed = 0; ed < ne; ++ed) ++count[ea[ed] + 1], ++count[eb[ed] + 1];
    adj_off_.assign(n_ + 1, 0);
    for (int i = 0; i < n_; ++i) adj_off_[i + 1] = adj_off_[i] + count[i + 1];
    adj_edge_.resize(adj_off_[n_]);
    adj_other_.resize(adj_off_[n_]);
    std::vector<int> fill(adj_off_.begin(), adj_off_.end() - 1);
    for (int ed = 0; ed < ne; ++ed) {
      adj_edge_[fill[ea[ed]]] = ed, adj_other_[fill[ea[ed]]++] = eb[ed];
      adj_edge_[fill[eb[ed]]] = ed, adj_other_[fill[eb[ed]]++] = ea[ed];
    }
  }

  // Gershgorin row sums of the stiffness at the flat rest shape (x = (u, v, 0)),
  // with each curve's steepest slope and the residual prestress. Row sums are
  // taken in the pattern's own frame; the largest eigenvalue they bound does
  // not change when the cloth is moved rigidly.
  void rest_bound(const Model& m) {
    VecX xr(3 * n_);
    for (int i = 0; i < n_; ++i) at(xr, i) = Vec3(m.uv[i].x(), m.uv[i].y(), 0.0);
    Triplets trip;
    Mat3 K[3][3];
    for (std::size_t t = 0; t < area_.size(); ++t) {
      const Law& L = laws_[law_[t]];
      Gauges g;
      const double* Ti = &ti_[9 * t];
      const int* v = &tv_[3 * t];
      read_gauges(Ti, xr.data(), v, g);
      Vec3 s;
      law_stress(L, g.eps, s, nullptr);
      // The stiffest tangent the law can reach.
      const double tx = L.stiff_x / L.det, ty = L.stiff_y / L.det;
      Mat3 D;
      D << tx, tx * L.nyx, 0, ty * L.nxy, ty, 0, 0, 0, L.G;
      hessian_blocks(g, s, D, Ti, area_[t], K);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) add_block(trip, v[i], v[j], K[i][j]);
    }
    k_bound_ = particle_row_sums(trip, n_);
  }

  int n_;
  RosetteOptions options_;
  std::vector<Law> laws_;
  // per triangle (SoA): vertices, rosette inverse (row-major 3×3), rest area (m²), law
  std::vector<int> tv_;
  std::vector<double> ti_, area_;
  std::vector<int> law_;
  std::vector<double> gq_;  // 3 per triangle: ∂U/∂q_k (N/m), the step's scratch
  std::vector<int> blocks_;  // 9 per triangle: block slots (i, j) of its corners (add_jacobian_blocks)
  long blocks_version_ = -1;
  // per edge: its gauge slots (CSR)
  std::vector<int> slot_off_, slots_;
  // per particle (CSR): incident edges and the particle at their other end
  std::vector<int> adj_off_, adj_edge_, adj_other_;
  VecX k_bound_;  // N/m per particle
};

}  // namespace

std::unique_ptr<Effect> make_strain_rosette(const Model& m, const std::vector<OrthotropicMaterial>& per_piece,
                                            const RosetteOptions& options) {
  return std::make_unique<StrainRosette>(m, per_piece, options);
}

// =============================================================================
// [SECTION] public kernels
// =============================================================================

Vec3 rosette_strain(const Model& m, int t, const VecX& x) {
  const auto& tri = m.triangles.at(t);
  const Mat3 Ti = rosette_inverse(m.uv[tri[0]], m.uv[tri[1]], m.uv[tri[2]]);
  double ti[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) ti[3 * r + c] = Ti(r, c);
  Gauges g;
  read_gauges(ti, x.data(), tri.data(), g);
  return g.eps;
}

Vec3 rosette_stress(const OrthotropicMaterial& mat, const Vec3& strain) {
  Vec3 s;
  law_stress(compile(mat), strain, s, nullptr);
  return s;
}

double rosette_energy_density(const OrthotropicMaterial& mat, const Vec3& strain) {
  return law_energy(compile(mat), strain);
}

}  // namespace vgd::sim
