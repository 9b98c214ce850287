// Bending across interior edges (seed 002 §3.1); formulas in bending.hpp.
//
// [SECTION] hinge geometry: the dihedral angle, its gradient and Hessian
// [SECTION] curvature gauges and edge slopes (rest data)
// [SECTION] the effect: five-pass forces, Jacobian, bounds
// [SECTION] curvatures for tests and the lab
#include "vgd/sim/effects/bending.hpp"

#include "vgd/sim/system.hpp"  // BlockJacobianEffect

#include <omp.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <tuple>
#include <type_traits>

namespace vgd::sim {

namespace {

// =============================================================================
// [SECTION] hinge geometry
// =============================================================================
//
// A hinge is the edge P→Q with the triangle T = (Q, P, r) on its right and
// T′ = (P, Q, r′) on its left in the pattern; both orders are counter-clockwise
// in uv, so N = (P − Q)×(r − Q) and N′ = (Q − P)×(r′ − P) are the normals the
// flat pattern has on the same side. The signed dihedral angle (rad) is
//
//   θ = atan2((N × N′)·ê, N·N′),   ê = (Q − P)/L,  L = |Q − P|,
//
// positive when the hinge folds towards the normals' side (a valley). Its
// gradient (Bridson, Marino & Fedkiw 2003; Grinspun et al. 2003, "Discrete
// shells"): with h = |N|/L the height of r over the edge and α = (r − P)·ê/L
// where r projects on the edge,
//
//   ∇_r θ = N/(h|N|) = L N/|N|²,   ∇_r′ θ = L N′/|N′|²,
//   ∇_P θ = −(1 − α) ∇_r θ − (1 − α′) ∇_r′ θ,   ∇_Q θ = −α ∇_r θ − α′ ∇_r′ θ.
//
// These are seed 002's forces: M/h at the tip of a cantilever of length h
// along the normal, and at the edge the reactions that cancel force and torque.

// A dual number with 12 derivative components: the Hessian of θ is the
// derivative of its gradient, taken exactly in one forward pass.
struct Dual {
  double v = 0.0;
  Eigen::Matrix<double, 12, 1> d = Eigen::Matrix<double, 12, 1>::Zero();
};
inline Dual operator+(const Dual& a, const Dual& b) { return {a.v + b.v, a.d + b.d}; }
inline Dual operator-(const Dual& a, const Dual& b) { return {a.v - b.v, a.d - b.d}; }
inline Dual operator-(const Dual& a) { return {-a.v, -a.d}; }
inline Dual operator*(const Dual& a, const Dual& b) { return {a.v * b.v, a.v * b.d + b.v * a.d}; }
inline Dual operator*(double s, const Dual& a) { return {s * a.v, s * a.d}; }
inline Dual operator/(const Dual& a, const Dual& b) {
  return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)};
}
inline Dual operator-(double s, const Dual& a) { return {s - a.v, -a.d}; }
inline Dual sqrt(const Dual& a) {
  const double r = std::sqrt(a.v);
  return {r, a.d / (2.0 * r)};
}
using std::sqrt;

template <class S>
struct V3 {
  S x, y, z;
};
template <class S>
V3<S> operator-(const V3<S>& a, const V3<S>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class S>
V3<S> cross(const V3<S>& a, const V3<S>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class S>
S dot(const V3<S>& a, const V3<S>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// ∇θ (12 values: P, Q, r, r′) from the four positions, for any scalar type.
template <class S>
void dihedral_gradient(const V3<S>& P, const V3<S>& Q, const V3<S>& r, const V3<S>& rp, S g[12]) {
  const V3<S> N = cross(P - Q, r - Q), Np = cross(Q - P, rp - P), e = Q - P;
  const S L2 = dot(e, e), L = sqrt(L2);
  const S cr = L / dot(N, N), crp = L / dot(Np, Np);  // 1/(h|N|)
  const S a = dot(r - P, e) / L2, ap = dot(rp - P, e) / L2;
  const S n[3] = {N.x, N.y, N.z}, np[3] = {Np.x, Np.y, Np.z};
  for (int c = 0; c < 3; ++c) {
    const S gr = cr * n[c], grp = crp * np[c];
    g[c] = -((1.0 - a) * gr) - (1.0 - ap) * grp;
    g[3 + c] = -(a * gr) - ap * grp;
    g[6 + c] = gr;
    g[9 + c] = grp;
  }
}

inline V3<double> v3(const double* p) { return {p[0], p[1], p[2]}; }

// The dihedral angle (rad) from the two normals and the edge.
inline double dihedral_angle(const Vec3& N, const Vec3& Np, const Vec3& e) {
  return std::atan2(N.cross(Np).dot(e) / e.norm(), N.dot(Np));
}

// =============================================================================
// [SECTION] curvature gauges and edge slopes (rest data)
// =============================================================================

// w_e (m): θ_e = w_e·κ for z = ½ xᵀKx, κ = (K_xx, K_yy, 2K_xy), from the
// pattern: the edge P→Q and the opposite vertices r (right) and r′ (left).
// Derivation: the linear interpolants' slopes on both sides agree along the
// edge; their jump across it, (g′ − g)·n, is
//   K_nn (h + h′)/2 + K_tn (b − a) + K_tt [a(a − L)/h + b(b − L)/h′]/2.
Vec3 curvature_gauge(const Vec2& P, const Vec2& Q, const Vec2& r, const Vec2& rp) {
  const double L = (Q - P).norm();
  const Vec2 t = (Q - P) / L, n(-t.y(), t.x());
  const double a = (r - P).dot(t), h = -(r - P).dot(n);
  const double b = (rp - P).dot(t), hp = (rp - P).dot(n);
  const double alpha = 0.5 * (a * (a - L) / h + b * (b - L) / hp), beta = 0.5 * (h + hp), gamma = b - a;
  const Vec3 tt(t.x() * t.x(), t.y() * t.y(), t.x() * t.y());
  const Vec3 nn(n.x() * n.x(), n.y() * n.y(), n.x() * n.y());
  const Vec3 tn(t.x() * n.x(), t.y() * n.y(), 0.5 * (t.x() * n.y() + t.y() * n.x()));
  return alpha * tt + beta * nn + gamma * tn;
}

// u (m): the share of a hinge angle on one side of the edge, for z = ½ xᵀKx.
// Triangle T with edge P–Q and opposite vertex r; n the edge's outward unit
// normal (away from r), t = (Q − P)/L, r at (a, −h) in the edge frame. The
// exact slope across the edge midpoint, ψ = ∇z(mid)·n, less the slope of T's
// linear interpolant, g_T·n, is
//   β_T = ψ − g_T·n = K_tt a(a − L)/(2h) + K_nn h/2 + K_tn (L/2 − a) = u·κ,
// and the two sides add up to the hinge angle: β_T + β_T′ = θ = w·κ.
Vec3 slope_gauge(const Vec2& P, const Vec2& Q, const Vec2& r) {
  const double L = (Q - P).norm();
  const Vec2 t = (Q - P) / L;
  Vec2 n(-t.y(), t.x());
  if ((r - P).dot(n) > 0.0) n = -n;
  const double a = (r - P).dot(t), h = -(r - P).dot(n);
  const Vec3 tt(t.x() * t.x(), t.y() * t.y(), t.x() * t.y());
  const Vec3 nn(n.x() * n.x(), n.y() * n.y(), n.x() * n.y());
  const Vec3 tn(t.x() * n.x(), t.y() * n.y(), 0.5 * (t.x() * n.y() + t.y() * n.x()));
  return a * (a - L) / (2.0 * h) * tt + 0.5 * h * nn + (0.5 * L - a) * tn;
}

// (n_x², n_y², 2 n_x n_y): n⊗n in the (κ_xx, κ_yy, 2κ_xy) basis.
Vec3 normal_square(const Vec2& P, const Vec2& Q) {
  const Vec2 t = (Q - P).normalized();
  return Vec3(t.y() * t.y(), t.x() * t.x(), -2.0 * t.x() * t.y());
}

// The plate rigidities D (N·m) in (κ_xx, κ_yy, 2κ_xy), mechanics.md §3:
// D₁₁ = B_x, D₂₂ = B_y, D₁₂ = ν_yx B_x, D₆₆ = twist_rigidity (floored at
// 1e-9 min(B_x, B_y) so that D stays invertible).
Mat3 plate_rigidity(const OrthotropicMaterial& m) {
  const double D12 = nu_weft_warp(m) * m.B_warp;
  const double D66 = std::max(twist_rigidity(m), 1e-9 * std::min(m.B_warp, m.B_weft));
  Mat3 D;
  D << m.B_warp, D12, 0, D12, m.B_weft, 0, 0, 0, D66;
  return D;
}

// =============================================================================
// [SECTION] the effect
// =============================================================================

class Bending final : public Effect, public BlockJacobianEffect {
 public:
  Bending(const Model& m, const std::vector<OrthotropicMaterial>& per_piece, const BendingOptions& o)
      : n_(m.num_particles()), options_(o) {
    validate(m);
    const std::vector<int> mat = triangle_materials(m, per_piece);
    for (const auto& p : per_piece) D_.push_back(plate_rigidity(p));
    const int nt = static_cast<int>(m.triangles.size());
    tv_.resize(3 * nt);
    sign_.resize(nt);
    area_.resize(nt);
    mat_ = mat;
    for (int t = 0; t < nt; ++t) {
      const auto& tri = m.triangles[t];
      for (int k = 0; k < 3; ++k) tv_[3 * t + k] = tri[k];
      const Vec2 ab = m.uv[tri[1]] - m.uv[tri[0]], ac = m.uv[tri[2]] - m.uv[tri[0]];
      const double cross = ab.x() * ac.y() - ab.y() * ac.x();
      sign_[t] = cross >= 0.0 ? 1.0 : -1.0;
      area_[t] = 0.5 * std::abs(cross);
    }
    build_hinges(m);
    build_stencils(m);
    build_gather();
    normal_.assign(3 * nt, 0.0);
    theta_.assign(hinges(), 0.0);
    mu_.assign(3 * nt, 0.0);
    hf_.assign(12 * hinges(), 0.0);
    rest_bound(m);
  }

  const char* name() const override { return "bending"; }

  // Five passes over independent outputs (parallel, bit-identical to serial):
  // triangle normals; hinge angles θ; per triangle the curvature κ_T = Σ c θ
  // and its moment A D κ_T; per hinge M = ∂U/∂θ = Σ_T cᵀ A D κ_T and the
  // forces −M ∇θ; per particle the sum over the hinges it belongs to.
  void add_forces(const Eval& e, VecX& f) override {
    const double* x = e.x.data();
    const int nt = static_cast<int>(sign_.size()), nh = hinges();
    const bool par = omp_get_max_threads() > 1 && nh >= options_.parallel_min_hinges;
#pragma omp parallel if (par)
    {
#pragma omp for schedule(static)
      for (int t = 0; t < nt; ++t) {
        if (!has_hinge_[t]) continue;
        const double* p0 = x + 3 * tv_[3 * t];
        const double* p1 = x + 3 * tv_[3 * t + 1];
        const double* p2 = x + 3 * tv_[3 * t + 2];
        const double ax = p1[0] - p0[0], ay = p1[1] - p0[1], az = p1[2] - p0[2];
        const double bx = p2[0] - p0[0], by = p2[1] - p0[1], bz = p2[2] - p0[2];
        const double sg = sign_[t];
        double* N = &normal_[3 * t];
        N[0] = sg * (ay * bz - az * by);
        N[1] = sg * (az * bx - ax * bz);
        N[2] = sg * (ax * by - ay * bx);
      }
#pragma omp for schedule(static)
      for (int h = 0; h < nh; ++h) {
        const int* v = &hv_[4 * h];
        const double* N = &normal_[3 * ht_[2 * h]];
        const double* M = &normal_[3 * ht_[2 * h + 1]];
        const double ex = x[3 * v[1]] - x[3 * v[0]], ey = x[3 * v[1] + 1] - x[3 * v[0] + 1],
                     ez = x[3 * v[1] + 2] - x[3 * v[0] + 2];
        // θ = atan2((N × N′)·ê, N·N′)
        const double cx = N[1] * M[2] - N[2] * M[1], cy = N[2] * M[0] - N[0] * M[2], cz = N[0] * M[1] - N[1] * M[0];
        const double sine = (cx * ex + cy * ey + cz * ez) / std::sqrt(ex * ex + ey * ey + ez * ez);
        theta_[h] = std::atan2(sine, N[0] * M[0] + N[1] * M[1] + N[2] * M[2]);
      }
#pragma omp for schedule(static)
      for (int t = 0; t < nt; ++t) {
        double k0 = 0, k1 = 0, k2 = 0;
        for (int s = st_off_[t]; s < st_off_[t + 1]; ++s) {
          const double th = theta_[st_hinge_[s]];
          const double* c = &st_coef_[3 * s];
          k0 += c[0] * th, k1 += c[1] * th, k2 += c[2] * th;
        }
        const Mat3& D = D_[mat_[t]];
        const double A = area_[t];
        double* mu = &mu_[3 * t];
        mu[0] = A * (D(0, 0) * k0 + D(0, 1) * k1 + D(0, 2) * k2);
        mu[1] = A * (D(1, 0) * k0 + D(1, 1) * k1 + D(1, 2) * k2);
        mu[2] = A * (D(2, 0) * k0 + D(2, 1) * k1 + D(2, 2) * k2);
      }
#pragma omp for schedule(static)
      for (int h = 0; h < nh; ++h) {
        double Mh = 0.0;
        for (int s = tr_off_[h]; s < tr_off_[h + 1]; ++s) {
          const double* c = &st_coef_[3 * tr_slot_[s]];
          const double* mu = &mu_[3 * tr_tri_[s]];
          Mh += c[0] * mu[0] + c[1] * mu[1] + c[2] * mu[2];
        }
        const int* v = &hv_[4 * h];
        const double* P = x + 3 * v[0];
        const double* Q = x + 3 * v[1];
        const double* r = x + 3 * v[2];
        const double* rp = x + 3 * v[3];
        const double* N = &normal_[3 * ht_[2 * h]];
        const double* Np = &normal_[3 * ht_[2 * h + 1]];
        const double ex = Q[0] - P[0], ey = Q[1] - P[1], ez = Q[2] - P[2];
        const double L2 = ex * ex + ey * ey + ez * ez, L = std::sqrt(L2);
        // ∇_r θ = L N/|N|², ∇_r′ θ = L N′/|N′|²; the edge takes the rest by lever arms.
        const double cr = Mh * L / (N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
        const double crp = Mh * L / (Np[0] * Np[0] + Np[1] * Np[1] + Np[2] * Np[2]);
        const double a = ((r[0] - P[0]) * ex + (r[1] - P[1]) * ey + (r[2] - P[2]) * ez) / L2;
        const double ap = ((rp[0] - P[0]) * ex + (rp[1] - P[1]) * ey + (rp[2] - P[2]) * ez) / L2;
        double* F = &hf_[12 * h];
        for (int c = 0; c < 3; ++c) {
          const double gr = cr * N[c], grp = crp * Np[c];
          F[c] = (1.0 - a) * gr + (1.0 - ap) * grp;
          F[3 + c] = a * gr + ap * grp;
          F[6 + c] = -gr;
          F[9 + c] = -grp;
        }
      }
#pragma omp for schedule(static)
      for (int i = 0; i < n_; ++i) {
        double fx = 0, fy = 0, fz = 0;
        for (int k = inc_off_[i]; k < inc_off_[i + 1]; ++k) {
          const double* F = &hf_[inc_[k]];
          fx += F[0], fy += F[1], fz += F[2];
        }
        f[3 * i] += fx, f[3 * i + 1] += fy, f[3 * i + 2] += fz;
      }
    }
  }

  // −[Σ_T A (C_T ∇θ)ᵀ D (C_T ∇θ) + Σ_h M_h ∇²θ_h], exact, or the first sum
  // alone (BendingOptions::definite_jacobian).
  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets&) override {
    assemble_hessian(
        e.x.data(), -1.0, [&](int i, int j, const Mat3& b) { add_block(dfdx, i, j, b); }, !options_.definite_jacobian);
    return true;
  }

  // The same blocks, in the same order, straight into the System's block
  // pattern. The blocks come in an order fixed by the mesh (a hinge without
  // moment still takes its 16 places), so their slots are looked up once per
  // pattern version and then read in turn.
  bool add_jacobian_blocks(const Eval& e, JacobianAssembler& out) override {
    const bool record = blocks_version_ != out.version();
    if (record) blocks_.clear();
    std::size_t k = 0;
    assemble_hessian(e.x.data(), -1.0, [&](int i, int j, const Mat3* b) {
      int q;
      if (record)
        blocks_.push_back(q = out.slot(i, j));
      else
        q = blocks_[k++];
      if (q < 0 || b == nullptr) return;  // prescribed, or a place kept
      double* d = out.dfdx(q);  // row-major
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) d[3 * r + c] += (*b)(r, c);
    }, !options_.definite_jacobian);
    if (record) blocks_version_ = out.version();
    return true;
  }

  double energy(const Eval& e) const override {
    const std::vector<double> th = angles(e.x.data());
    double u = 0.0;
    for (std::size_t t = 0; t < sign_.size(); ++t) {
      const Vec3 k = curvature(static_cast<int>(t), th);
      u += 0.5 * area_[t] * k.dot(D_[mat_[t]] * k);
    }
    return u;
  }

  void add_stiffness_bound(const Model&, VecX& k_rows, VecX&) const override { k_rows += k_bound_; }

  std::vector<TriangleCurvature> curvatures(const VecX& x) const {
    const std::vector<double> th = angles(x.data());
    std::vector<TriangleCurvature> out(sign_.size());
    for (std::size_t t = 0; t < sign_.size(); ++t) {
      out[t].kappa = curvature(static_cast<int>(t), th);
      for (int k = 0; k < 3; ++k) out[t].hinges += th_[3 * t + k] >= 0;
    }
    return out;
  }

 private:
  int hinges() const { return static_cast<int>(hv_.size() / 4); }

  Vec3 curvature(int t, const std::vector<double>& th) const {
    Vec3 k = Vec3::Zero();
    for (int s = st_off_[t]; s < st_off_[t + 1]; ++s) k += Eigen::Map<const Vec3>(&st_coef_[3 * s]) * th[st_hinge_[s]];
    return k;
  }

  // Interior edges of each piece, as hinges (P, Q, r, r′) with T on the right
  // of P→Q in the pattern and T′ on its left.
  void build_hinges(const Model& m) {
    struct Item {
      int a, b, t, k;
    };
    const int nt = static_cast<int>(m.triangles.size());
    std::vector<Item> items;
    items.reserve(3 * nt);
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) {
        const int p = tv_[3 * t + k], q = tv_[3 * t + (k + 1) % 3];
        items.push_back({std::min(p, q), std::max(p, q), t, k});
      }
    std::sort(items.begin(), items.end(),
              [](const Item& l, const Item& r) { return std::tie(l.a, l.b, l.t) < std::tie(r.a, r.b, r.t); });
    auto piece = [&](int t) { return m.triangle_piece.empty() ? 0 : m.triangle_piece[t]; };
    th_.assign(3 * nt, -1);
    for (std::size_t s = 0; s < items.size();) {
      std::size_t e = s;
      while (e < items.size() && items[e].a == items[s].a && items[e].b == items[s].b) ++e;
      for (std::size_t i = s; i < e; ++i)
        for (std::size_t j = i + 1; j < e; ++j) {
          if (piece(items[i].t) != piece(items[j].t)) continue;
          int same_piece = 0;
          for (std::size_t k = s; k < e; ++k) same_piece += piece(items[k].t) == piece(items[i].t);
          if (same_piece > 2)
            throw SimulationError("bending: the edge between particles " + std::to_string(items[s].a) + " and " +
                                  std::to_string(items[s].b) + " is shared by " + std::to_string(same_piece) +
                                  " triangles of piece " + std::to_string(piece(items[i].t)) +
                                  "; a cloth surface has at most two per edge (remesh the piece)");
          add_hinge(m, items[i], items[j]);
        }
      s = e;
    }
  }

  template <class Item>
  void add_hinge(const Model& m, const Item& A, const Item& B) {
    const int a = A.a, b = A.b;
    const int ra = tv_[3 * A.t + (A.k + 2) % 3], rb = tv_[3 * B.t + (B.k + 2) % 3];
    // Orient P→Q so that ra lies on its right in the pattern.
    const Vec2 d = m.uv[b] - m.uv[a];
    const double side_a = d.x() * (m.uv[ra] - m.uv[a]).y() - d.y() * (m.uv[ra] - m.uv[a]).x();
    const double side_b = d.x() * (m.uv[rb] - m.uv[a]).y() - d.y() * (m.uv[rb] - m.uv[a]).x();
    if (!(side_a * side_b < 0.0))
      throw SimulationError("bending: triangles " + std::to_string(A.t) + " and " + std::to_string(B.t) +
                            " lie on the same side of their shared edge (particles " + std::to_string(a) + ", " +
                            std::to_string(b) + ") in the pattern: they overlap; remesh the piece");
    int P = a, Q = b;
    if (side_a > 0.0) std::swap(P, Q);  // ra on the left of a→b: reverse the edge
    const int h = hinges();
    hv_.insert(hv_.end(), {P, Q, ra, rb});
    ht_.insert(ht_.end(), {A.t, B.t});
    th_[3 * A.t + A.k] = h;  // the hinge on edge k (vertex k → k+1) of each triangle
    th_[3 * B.t + B.k] = h;
  }

  // The curvature of each triangle as a combination of hinge angles,
  //   κ_T = Σ_h c_{T,h} θ_h   (1/m per rad, stencil: T's hinges and its neighbours'),
  // a rotation-free Morley triangle (Morley 1968; Oñate & Zárate 2000 for the
  // rotation-free idea): by Green's theorem over T, with β_e = ψ_e − g_T·n_e the
  // edge's normal slope at its midpoint relative to T's plane,
  //   κ_T = (1/A_T) Σ_e L_e β_e (n_e⊗n_e),
  // exact for quadratic surfaces when β_e is. Each hinge angle is split between
  // its sides, β_T + β_T′ = θ_e, so Σ_T A_T κ_T = Σ_e L_e θ_e n⊗n, the integral of
  // the surface's Hessian: uniform curvature leaves inner particles without
  // force (the patch test). The split, β_T = θ/2 + ½(u_T − u_T′)·K̂_e, uses the
  // curvature K̂_e = ½(K̂_T + K̂_T′) of the triangles' rosettes (K̂_T = Z_T⁻¹ θ_T:
  // one curvature gauge θ = w·κ per hinge, M_nn = 0 per free edge), so that it
  // is exact for quadratic surfaces. A free edge's slope is chosen so that no
  // moment crosses it (Morley's natural condition, solved per triangle).
  void build_stencils(const Model& m) {
    const int nt = static_cast<int>(sign_.size());
    has_hinge_.assign(nt, 0);
    // The rosettes K̂_T = R_T θ_T (3 × 3, columns by edge slot k, zero for free edges).
    std::vector<Mat3> R(nt, Mat3::Zero());
    for (int t = 0; t < nt; ++t) {
      const Mat3& D = D_[mat_[t]];
      Mat3 Z;
      bool any = false;
      for (int k = 0; k < 3; ++k) {
        const int h = th_[3 * t + k];
        if (h >= 0) {
          const int* v = &hv_[4 * h];
          Z.row(k) = curvature_gauge(m.uv[v[0]], m.uv[v[1]], m.uv[v[2]], m.uv[v[3]]).transpose();
          any = true;
        } else {
          Z.row(k) = normal_square(m.uv[tv_[3 * t + k]], m.uv[tv_[3 * t + (k + 1) % 3]]).transpose() * D;
        }
      }
      if (!any) continue;
      has_hinge_[t] = 1;
      const Eigen::FullPivLU<Mat3> lu(Z);
      if (!lu.isInvertible())
        throw SimulationError("bending: triangle " + std::to_string(t) +
                              " has curvature gauges that do not determine its curvature (a degenerate or "
                              "sliver triangle in the pattern). What would work: remesh the piece with quality "
                              "triangles (mesh.min_angle 20-30 degrees, the mesher's default 25), or run the "
                              "strain-rosette membrane without bending (cloth \"bending\": false)");
      R[t] = lu.inverse();
      for (int k = 0; k < 3; ++k)
        if (th_[3 * t + k] < 0) R[t].col(k).setZero();
    }
    // Per triangle, the stencil before and after the free-edge condition.
    st_off_.assign(nt + 1, 0);
    for (int t = 0; t < nt; ++t) {
      std::vector<std::pair<int, Vec3>> c;  // (hinge, coefficient), in first-seen order
      auto add = [&](int h, const Vec3& v) {
        for (auto& [hh, vv] : c)
          if (hh == h) {
            vv += v;
            return;
          }
        c.emplace_back(h, v);
      };
      if (has_hinge_[t]) {
        const double A = area_[t];
        for (int k = 0; k < 3; ++k) {
          const int h = th_[3 * t + k];
          if (h < 0) continue;
          const int* v = &hv_[4 * h];
          const int other = ht_[2 * h] == t ? ht_[2 * h + 1] : ht_[2 * h];
          const int r_own = ht_[2 * h] == t ? v[2] : v[3], r_other = ht_[2 * h] == t ? v[3] : v[2];
          const Vec2 P = m.uv[v[0]], Q = m.uv[v[1]];
          const double L = (Q - P).norm();
          const Vec3 nn = normal_square(P, Q) * (L / A);
          const Vec3 d = slope_gauge(P, Q, m.uv[r_own]) - slope_gauge(P, Q, m.uv[r_other]);
          add(h, 0.5 * nn);
          for (int j = 0; j < 3; ++j) {
            if (th_[3 * t + j] >= 0) add(th_[3 * t + j], 0.25 * d.dot(R[t].col(j)) * nn);
            if (th_[3 * other + j] >= 0) add(th_[3 * other + j], 0.25 * d.dot(R[other].col(j)) * nn);
          }
        }
        // Free edges: slopes β_f with (n_f⊗n_f)·D κ_T = 0, κ_T = κ⁰ + Σ_f (L_f/A) β_f n_f⊗n_f,
        // hence κ_T = P_T κ⁰, P_T = I − F (Nᵀ D F)⁻¹ Nᵀ D.
        const Mat3& D = D_[mat_[t]];
        Eigen::Matrix<double, 3, Eigen::Dynamic> F(3, 0), N(3, 0);
        for (int k = 0; k < 3; ++k) {
          if (th_[3 * t + k] >= 0) continue;
          const Vec2 P = m.uv[tv_[3 * t + k]], Q = m.uv[tv_[3 * t + (k + 1) % 3]];
          const Vec3 nn = normal_square(P, Q);
          F.conservativeResize(3, F.cols() + 1);
          N.conservativeResize(3, N.cols() + 1);
          F.col(F.cols() - 1) = (P - Q).norm() / A * nn;
          N.col(N.cols() - 1) = nn;
        }
        if (F.cols() > 0) {
          const Eigen::MatrixXd S = N.transpose() * D * F;
          const Mat3 PT = Mat3::Identity() - F * S.inverse() * N.transpose() * D;
          for (auto& [hh, vv] : c) vv = PT * vv;
        }
      }
      for (const auto& [hh, vv] : c) {
        st_hinge_.push_back(hh);
        st_coef_.insert(st_coef_.end(), {vv.x(), vv.y(), vv.z()});
      }
      st_off_[t + 1] = static_cast<int>(st_hinge_.size());
      max_stencil_nodes_ = std::max(max_stencil_nodes_, 4 * (st_off_[t + 1] - st_off_[t]));
    }
    // The transpose: per hinge, the (triangle, stencil slot) pairs that use it, by triangle.
    std::vector<int> count(hinges() + 1, 0);
    for (int h : st_hinge_) ++count[h + 1];
    tr_off_.assign(hinges() + 1, 0);
    for (int h = 0; h < hinges(); ++h) tr_off_[h + 1] = tr_off_[h] + count[h + 1];
    tr_tri_.resize(st_hinge_.size());
    tr_slot_.resize(st_hinge_.size());
    std::vector<int> fill(tr_off_.begin(), tr_off_.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int s = st_off_[t]; s < st_off_[t + 1]; ++s) {
        const int k = fill[st_hinge_[s]]++;
        tr_tri_[k] = t;
        tr_slot_[k] = s;
      }
  }

  // Per particle, the offsets into hf_ of its hinge forces (fixed order).
  void build_gather() {
    std::vector<int> count(n_ + 1, 0);
    for (int v : hv_) ++count[v + 1];
    inc_off_.assign(n_ + 1, 0);
    for (int i = 0; i < n_; ++i) inc_off_[i + 1] = inc_off_[i] + count[i + 1];
    inc_.resize(inc_off_[n_]);
    std::vector<int> fill(inc_off_.begin(), inc_off_.end() - 1);
    for (int h = 0; h < hinges(); ++h)
      for (int role = 0; role < 4; ++role) inc_[fill[hv_[4 * h + role]]++] = 12 * h + 3 * role;
  }

  // Hinge angles at positions x, computed from scratch (const verbs).
  std::vector<double> angles(const double* x) const {
    std::vector<double> th(hinges());
    for (int h = 0; h < hinges(); ++h) {
      const int* v = &hv_[4 * h];
      const Vec3 P = Eigen::Map<const Vec3>(x + 3 * v[0]), Q = Eigen::Map<const Vec3>(x + 3 * v[1]);
      const Vec3 r = Eigen::Map<const Vec3>(x + 3 * v[2]), rp = Eigen::Map<const Vec3>(x + 3 * v[3]);
      th[h] = dihedral_angle((P - Q).cross(r - Q), (Q - P).cross(rp - P), Q - P);
    }
    return th;
  }

  // scale × Hessian of U, block by block: sink(i, j, block) with a Mat3, or
  // (for a sink taking a pointer) also sink(i, j, nullptr) for each block of
  // a hinge without moment, so that the sequence of (i, j) is the mesh's.
  template <class Sink>
  void assemble_hessian(const double* x, double scale, Sink&& sink, bool exact = true) const {
    constexpr bool by_pointer = std::is_invocable_v<Sink, int, int, const Mat3*>;
    auto put = [&](int i, int j, const Mat3& b) {
      if constexpr (by_pointer)
        sink(i, j, &b);
      else
        sink(i, j, b);
    };
    const int nh = hinges(), nt = static_cast<int>(sign_.size());
    const std::vector<double> th = angles(x);
    std::vector<double> grad(12 * nh), M(nh, 0.0);
    for (int h = 0; h < nh; ++h) {
      const int* v = &hv_[4 * h];
      dihedral_gradient(v3(x + 3 * v[0]), v3(x + 3 * v[1]), v3(x + 3 * v[2]), v3(x + 3 * v[3]), &grad[12 * h]);
    }
    // A (C_T ∇θ)ᵀ D (C_T ∇θ) on each triangle's stencil, and the moments M_h:
    // G = C_T ∇θ in 3 × 3 blocks, one per node of the stencil (its hinges'
    // corners, at most 4 per hinge), K_ij = A G_iᵀ D G_j.
    std::vector<int> nodes(max_stencil_nodes_);
    std::vector<Mat3> G(max_stencil_nodes_), DG(max_stencil_nodes_);
    for (int t = 0; t < nt; ++t) {
      if (st_off_[t] == st_off_[t + 1]) continue;
      const Mat3& D = D_[mat_[t]];
      const Vec3 mu = area_[t] * (D * curvature(t, th));
      int ns = 0;
      auto node = [&](int p) {
        for (int k = 0; k < ns; ++k)
          if (nodes[k] == p) return k;
        nodes[ns] = p;
        G[ns].setZero();
        return ns++;
      };
      for (int s = st_off_[t]; s < st_off_[t + 1]; ++s) {
        const int h = st_hinge_[s];
        const Vec3 c = Eigen::Map<const Vec3>(&st_coef_[3 * s]);
        M[h] += c.dot(mu);
        for (int role = 0; role < 4; ++role)
          G[node(hv_[4 * h + role])] += c * Eigen::Map<const Vec3>(&grad[12 * h + 3 * role]).transpose();
      }
      for (int j = 0; j < ns; ++j) DG[j] = (scale * area_[t]) * (D * G[j]);
      for (int i = 0; i < ns; ++i)
        for (int j = 0; j < ns; ++j) put(nodes[i], nodes[j], G[i].transpose() * DG[j]);
    }
    // Σ_h M_h ∇²θ_h: the derivative of the gradient, by dual numbers (the
    // exact Hessian only: BendingOptions::definite_jacobian).
    for (int h = 0; h < nh && exact; ++h) {
      const int* v = &hv_[4 * h];
      if (M[h] == 0.0) {
        if constexpr (by_pointer)
          for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) sink(v[i], v[j], nullptr);
        continue;
      }
      V3<Dual> p[4];
      for (int role = 0; role < 4; ++role) {
        const double* q = x + 3 * v[role];
        Dual c[3];
        for (int k = 0; k < 3; ++k) {
          c[k].v = q[k];
          c[k].d[3 * role + k] = 1.0;
        }
        p[role] = {c[0], c[1], c[2]};
      }
      Dual g[12];
      dihedral_gradient(p[0], p[1], p[2], p[3], g);
      Eigen::Matrix<double, 12, 12> Hh;
      for (int r = 0; r < 12; ++r) Hh.row(r) = g[r].d.transpose();
      Hh = 0.5 * (Hh + Hh.transpose()).eval();
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) put(v[i], v[j], scale * M[h] * Hh.block<3, 3>(3 * i, 3 * j));
    }
  }

  // Gershgorin row sums of the Hessian at the flat pattern (x = (u, v, 0)):
  // there θ = 0 and it is Σ A (C∇θ)ᵀ D (C∇θ), all along the normal. The bounded
  // eigenvalue does not change under rigid motion.
  void rest_bound(const Model& m) {
    VecX xr(3 * n_);
    for (int i = 0; i < n_; ++i) at(xr, i) = Vec3(m.uv[i].x(), m.uv[i].y(), 0.0);
    Triplets trip;
    assemble_hessian(xr.data(), 1.0, [&](int i, int j, const Mat3& b) { add_block(trip, i, j, b); });
    k_bound_ = particle_row_sums(trip, n_);
  }

  int n_;
  BendingOptions options_;
  std::vector<Mat3> D_;  // plate rigidities per material (N·m)
  // per triangle (SoA)
  std::vector<int> tv_;         // 3 vertices
  std::vector<double> sign_;    // +1 counter-clockwise in uv, −1 clockwise
  std::vector<double> area_;    // rest area (m²)
  std::vector<int> mat_;        // material
  std::vector<int> th_;         // per edge slot k (vertex k → k+1): its hinge, −1 for a free edge
  std::vector<char> has_hinge_;
  // per triangle stencil (CSR): hinges and coefficients c (1/m, 3 each)
  std::vector<int> st_off_, st_hinge_;
  std::vector<double> st_coef_;
  // its transpose: per hinge, the triangles and stencil slots that use it
  std::vector<int> tr_off_, tr_tri_, tr_slot_;
  // per hinge (SoA)
  std::vector<int> hv_;  // P, Q, r, r′
  std::vector<int> ht_;  // T, T′
  // gather: per particle, offsets into hf_
  std::vector<int> inc_off_, inc_;
  // the step's scratch
  std::vector<double> normal_, theta_, mu_, hf_;
  VecX k_bound_;
  int max_stencil_nodes_ = 0;  // at most 4 per hinge of the largest stencil (assemble_hessian's scratch)
  std::vector<int> blocks_;  // the Hessian's block slots in assembly order (add_jacobian_blocks)
  long blocks_version_ = -1;
};

}  // namespace

std::unique_ptr<Effect> make_bending(const Model& m, const std::vector<OrthotropicMaterial>& per_piece,
                                     const BendingOptions& options) {
  return std::make_unique<Bending>(m, per_piece, options);
}

// =============================================================================
// [SECTION] curvatures
// =============================================================================

std::vector<TriangleCurvature> bending_curvatures(const Effect& bending, const VecX& x) {
  const auto* b = dynamic_cast<const Bending*>(&bending);
  return b ? b->curvatures(x) : std::vector<TriangleCurvature>{};
}

}  // namespace vgd::sim
