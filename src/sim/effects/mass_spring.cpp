// The mass-spring cloth (seed 000 §4.1): topology, force kernel, Jacobian,
// stiffness bounds and Provot's strain limiter. The header explains the
// topology decisions.
//
// Index
//   [SECTION] Materials: validation
//   [SECTION] Topology: the seed's lattice (Figure 1)
//   [SECTION] Topology: unstructured meshes
//   [SECTION] Kernels
//   [SECTION] The effect
#include "vgd/sim/effects/mass_spring.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

#include "vgd/core/strings.hpp"
#include "vgd/sim/system.hpp"  // BlockJacobianEffect

namespace vgd::sim {

const char* to_string(SpringKind k) {
  switch (k) {
    case SpringKind::warp: return "warp";
    case SpringKind::weft: return "weft";
    case SpringKind::shear: return "shear";
    case SpringKind::bend_warp: return "bend-warp";
    case SpringKind::bend_weft: return "bend-weft";
  }
  return "?";
}

int SpringTopology::count(SpringKind kd) const {
  return static_cast<int>(std::count(kind.begin(), kind.end(), kd));
}

namespace {

// =============================================================================
// [SECTION] Materials: validation
// =============================================================================

std::string piece_label(const Model& m, int p) {
  std::string s = "piece " + std::to_string(p);
  if (p >= 0 && p < static_cast<int>(m.pieces.size())) s += " ('" + m.pieces[p] + "')";
  return s;
}

void check_materials(const Model& m, const std::vector<MassSpringMaterial>& per_piece) {
  if (per_piece.empty())
    throw SimulationError("mass-spring: no material given (one per piece, or one for all pieces)");
  if (per_piece.size() > 1 && !m.pieces.empty() && per_piece.size() != m.pieces.size())
    throw SimulationError("mass-spring: " + std::to_string(per_piece.size()) + " materials for " +
                          std::to_string(m.pieces.size()) + " pieces (give one per piece, or one for all)");
  for (std::size_t p = 0; p < per_piece.size(); ++p) {
    const MassSpringMaterial& mat = per_piece[p];
    const std::string who = per_piece.size() == 1 ? std::string("the material") : "the material of " + piece_label(m, static_cast<int>(p));
    auto check = [&](const char* field, double value, const char* unit) {
      if (!std::isfinite(value) || value < 0.0)
        throw SimulationError("mass-spring: " + who + " has " + field + " = " + format_significant(value, 6) +
                              unit + "; it must be a finite number ≥ 0");
    };
    check("warp", mat.warp, " N/m");
    check("weft", mat.weft, " N/m");
    check("shear", mat.shear, " N/m");
    check("bend_warp", mat.bend_warp, " N/m");
    check("bend_weft", mat.bend_weft, " N/m");
    check("damping", mat.damping, " N·s/m");
    check("max_strain", mat.max_strain, "");
  }
}

// The piece of triangle t, checked against the materials.
int piece_of(const Model& m, std::size_t t, std::size_t materials) {
  const int p = m.triangle_piece.empty() ? 0 : m.triangle_piece[t];
  const bool out = p < 0 || (materials > 1 && p >= static_cast<int>(materials)) ||
                   (!m.pieces.empty() && p >= static_cast<int>(m.pieces.size()));
  if (out)
    throw SimulationError("mass-spring: triangle " + std::to_string(t) + " belongs to piece " + std::to_string(p) +
                          ", which is out of range (" + std::to_string(materials) + " material(s), " +
                          std::to_string(m.pieces.size()) + " piece(s))");
  return p;
}

const MassSpringMaterial& material(const std::vector<MassSpringMaterial>& per_piece, int piece) {
  return per_piece.size() == 1 ? per_piece[0] : per_piece[piece];
}

// Collects springs before sorting; rest lengths and limits are filled at the end.
struct Builder {
  const Model& m;
  std::vector<std::tuple<int, int, SpringKind, double, double, double>> springs;  // a, b, kind, k, k_d, max_strain

  void add(int i, int j, SpringKind kind, double k, const MassSpringMaterial& mat) {
    springs.emplace_back(std::min(i, j), std::max(i, j), kind, k, mat.damping, mat.max_strain);
  }
};

// =============================================================================
// [SECTION] Topology: the seed's lattice (Figure 1)
// =============================================================================

// Sorted distinct values of xs, merging values closer than tol.
std::vector<double> distinct(std::vector<double> xs, double tol) {
  std::sort(xs.begin(), xs.end());
  std::vector<double> out;
  for (double x : xs)
    if (out.empty() || x - out.back() > tol) out.push_back(x);
  return out;
}

// If the piece's particles form a complete nu × nv lattice in uv, aligned with
// warp and weft and cut into two triangles per cell (make_grid), returns the
// particle at each lattice point (index j * nu + i) and sets nu, nv.
// Otherwise returns an empty vector.
std::vector<int> find_lattice(const Model& m, const std::vector<int>& tris, int& nu, int& nv) {
  std::vector<int> verts;
  for (int t : tris) verts.insert(verts.end(), m.triangles[t].begin(), m.triangles[t].end());
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  std::vector<double> us, vs;
  for (int p : verts) us.push_back(m.uv[p].x()), vs.push_back(m.uv[p].y());
  const double extent = std::max(*std::max_element(us.begin(), us.end()) - *std::min_element(us.begin(), us.end()),
                                 *std::max_element(vs.begin(), vs.end()) - *std::min_element(vs.begin(), vs.end()));
  const double merge = 1e-9 * extent;
  const std::vector<double> u = distinct(us, merge), v = distinct(vs, merge);
  nu = static_cast<int>(u.size());
  nv = static_cast<int>(v.size());
  if (nu < 2 || nv < 2 || static_cast<std::size_t>(nu) * nv != verts.size()) return {};
  if (tris.size() != 2 * static_cast<std::size_t>(nu - 1) * (nv - 1)) return {};
  // Evenly spaced rows and columns.
  const double du = (u.back() - u.front()) / (nu - 1), dv = (v.back() - v.front()) / (nv - 1);
  const double tol = 1e-6 * std::min(du, dv);
  for (int i = 0; i < nu; ++i)
    if (std::abs(u[i] - (u.front() + i * du)) > tol) return {};
  for (int j = 0; j < nv; ++j)
    if (std::abs(v[j] - (v.front() + j * dv)) > tol) return {};
  // Every lattice point holds exactly one particle.
  std::vector<int> at_point(static_cast<std::size_t>(nu) * nv, -1);
  std::vector<std::array<int, 2>> ij(m.num_particles(), {-1, -1});
  for (int p : verts) {
    const double fi = (m.uv[p].x() - u.front()) / du, fj = (m.uv[p].y() - v.front()) / dv;
    const int i = static_cast<int>(std::lround(fi)), j = static_cast<int>(std::lround(fj));
    if (std::abs(fi - i) * du > tol || std::abs(fj - j) * dv > tol) return {};
    int& slot = at_point[static_cast<std::size_t>(j) * nu + i];
    if (slot != -1) return {};
    slot = p;
    ij[p] = {i, j};
  }
  // Every triangle lies inside one cell.
  for (int t : tris) {
    int i0 = nu, i1 = -1, j0 = nv, j1 = -1;
    for (int p : m.triangles[t]) {
      i0 = std::min(i0, ij[p][0]), i1 = std::max(i1, ij[p][0]);
      j0 = std::min(j0, ij[p][1]), j1 = std::max(j1, ij[p][1]);
    }
    if (i1 - i0 != 1 || j1 - j0 != 1) return {};
  }
  return at_point;
}

// Figure 1: structural (a, b), shear (c) and bending (d) springs of a lattice.
void add_lattice(Builder& B, const std::vector<int>& g, int nu, int nv, const MassSpringMaterial& mat) {
  auto p = [&](int i, int j) { return g[static_cast<std::size_t>(j) * nu + i]; };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      if (i + 1 < nu) B.add(p(i, j), p(i + 1, j), SpringKind::warp, mat.warp, mat);
      if (j + 1 < nv) B.add(p(i, j), p(i, j + 1), SpringKind::weft, mat.weft, mat);
      if (i + 1 < nu && j + 1 < nv) {
        B.add(p(i, j), p(i + 1, j + 1), SpringKind::shear, mat.shear, mat);
        B.add(p(i + 1, j), p(i, j + 1), SpringKind::shear, mat.shear, mat);
      }
      if (i + 2 < nu) B.add(p(i, j), p(i + 2, j), SpringKind::bend_warp, mat.bend_warp, mat);
      if (j + 2 < nv) B.add(p(i, j), p(i, j + 2), SpringKind::bend_weft, mat.bend_weft, mat);
    }
}

// =============================================================================
// [SECTION] Topology: unstructured meshes
// =============================================================================

// cos 2φ of a material-space direction d, φ its angle to the warp:
// +1 along the warp, 0 on the bias, −1 along the weft.
double cos_2phi(const Vec2& d) { return (d.x() * d.x() - d.y() * d.y()) / d.squaredNorm(); }

// k = c² k_yarn + (1 − c²) k_bias, k_yarn = warp-ish or weft-ish by the sign of c.
double blend(double c, double along_warp, double along_weft, double bias) {
  return c * c * (c >= 0.0 ? along_warp : along_weft) + (1.0 - c * c) * bias;
}

// Nearest direction class: within 22.5° of a yarn (|cos 2φ| ≥ cos 45°) or the bias.
SpringKind nearest(double c, SpringKind warp_kind, SpringKind weft_kind) {
  constexpr double kCos45 = 0.70710678118654752;
  return c >= kCos45 ? warp_kind : c <= -kCos45 ? weft_kind : SpringKind::shear;
}

// A stretch spring on every edge, an opposite-vertex spring across every
// interior (two-triangle) edge; duplicates are dropped, edges win.
void add_mesh(Builder& B, const std::vector<int>& tris, const std::vector<int>& tri_piece,
              const std::vector<MassSpringMaterial>& per_piece) {
  const Model& m = B.m;
  struct Side {
    int a, b, opposite, tri;
  };
  std::vector<Side> sides;
  sides.reserve(3 * tris.size());
  for (int t : tris) {
    const auto& T = m.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int i = T[k], j = T[(k + 1) % 3];
      sides.push_back({std::min(i, j), std::max(i, j), T[(k + 2) % 3], t});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return std::tie(x.a, x.b, x.tri) < std::tie(y.a, y.b, y.tri);
  });
  std::vector<std::array<int, 2>> edges;
  std::vector<std::tuple<int, int, int>> across;  // c, d (c < d), triangle giving the material
  for (std::size_t s = 0; s < sides.size();) {
    std::size_t e = s;
    while (e < sides.size() && sides[e].a == sides[s].a && sides[e].b == sides[s].b) ++e;
    const Side& first = sides[s];
    edges.push_back({first.a, first.b});
    const MassSpringMaterial& mat = material(per_piece, tri_piece[first.tri]);
    const double c = cos_2phi(m.uv[first.a] - m.uv[first.b]);
    B.add(first.a, first.b, nearest(c, SpringKind::warp, SpringKind::weft), blend(c, mat.warp, mat.weft, mat.shear), mat);
    // Interior edge (exactly two triangles; non-manifold edges get none).
    if (e - s == 2 && sides[s].opposite != sides[s + 1].opposite)
      across.emplace_back(std::min(sides[s].opposite, sides[s + 1].opposite),
                          std::max(sides[s].opposite, sides[s + 1].opposite), first.tri);
    s = e;
  }
  std::sort(across.begin(), across.end());
  for (std::size_t q = 0; q < across.size(); ++q) {
    const auto [c_, d_, tri] = across[q];
    if (q > 0 && std::get<0>(across[q - 1]) == c_ && std::get<1>(across[q - 1]) == d_) continue;
    if (std::binary_search(edges.begin(), edges.end(), std::array<int, 2>{c_, d_})) continue;
    const MassSpringMaterial& mat = material(per_piece, tri_piece[tri]);
    const double c = cos_2phi(m.uv[c_] - m.uv[d_]);
    B.add(c_, d_, nearest(c, SpringKind::bend_warp, SpringKind::bend_weft),
          blend(c, mat.bend_warp, mat.bend_weft, mat.shear), mat);
  }
}

}  // namespace

SpringTopology mass_spring_topology(const Model& m, const std::vector<MassSpringMaterial>& per_piece) {
  check_materials(m, per_piece);
  // Triangles by piece.
  std::vector<int> tri_piece(m.triangles.size());
  int pieces = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    tri_piece[t] = piece_of(m, t, per_piece.size());
    pieces = std::max(pieces, tri_piece[t] + 1);
  }
  std::vector<std::vector<int>> by_piece(pieces);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) by_piece[tri_piece[t]].push_back(static_cast<int>(t));

  // The seed's lattice where a piece is one, the mesh rules elsewhere.
  SpringTopology top;
  Builder B{m, {}};
  std::vector<int> unstructured;
  for (int p = 0; p < pieces; ++p) {
    if (by_piece[p].empty()) continue;
    int nu = 0, nv = 0;
    const std::vector<int> lattice = find_lattice(m, by_piece[p], nu, nv);
    if (lattice.empty()) {
      unstructured.insert(unstructured.end(), by_piece[p].begin(), by_piece[p].end());
      continue;
    }
    add_lattice(B, lattice, nu, nv, material(per_piece, p));
    top.lattice_pieces.push_back(p);
  }
  add_mesh(B, unstructured, tri_piece, per_piece);

  // Sorted by (a, b): neighbouring springs touch neighbouring memory.
  std::sort(B.springs.begin(), B.springs.end(), [](const auto& x, const auto& y) {
    return std::tie(std::get<0>(x), std::get<1>(x)) < std::tie(std::get<0>(y), std::get<1>(y));
  });
  const std::size_t n = B.springs.size();
  top.a.resize(n), top.b.resize(n), top.kind.resize(n), top.k.resize(n);
  top.damping.resize(n), top.rest.resize(n), top.max_length.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    const auto& [a, b, kind, k, kd, max_strain] = B.springs[s];
    const double r = (m.uv[a] - m.uv[b]).norm();
    if (!(r > 0.0))
      throw SimulationError("mass-spring: the spring between particles " + std::to_string(a) + " and " +
                            std::to_string(b) + " has zero rest length (same material coordinates)");
    const bool yarn = kind == SpringKind::warp || kind == SpringKind::weft;
    top.a[s] = a, top.b[s] = b, top.kind[s] = kind, top.k[s] = k, top.damping[s] = kd, top.rest[s] = r;
    top.max_length[s] = yarn && max_strain > 0.0 ? (1.0 + max_strain) * r : 0.0;
  }
  return top;
}

namespace {

// =============================================================================
// [SECTION] Kernels
// =============================================================================

// Seed 000 §4.1.2, per spring s joining particles a and b:
//   f_a = −[k (|l| − r) + k_d (l′·l)/|l|] l/|l|,   f_b = −f_a,
//   l = x_a − x_b (m), l′ = v_a − v_b (m/s), r rest length (m),
//   k (N/m), k_d (N·s/m).
// Written as f_a = −σ l with σ = k (1 − r/|l|) + k_d (l′·l)/|l|² (N/m): one
// square root and one division per spring. Springs of zero length (coincident
// particles) have no direction and are skipped. ia, ib are 3 × particle index.
void accumulate_springs(int begin, int end, const int* __restrict ia, const int* __restrict ib,
                        const double* __restrict k, const double* __restrict kd, const double* __restrict r,
                        const double* __restrict x, const double* __restrict v, double* __restrict f) {
  for (int s = begin; s < end; ++s) {
    const int a = ia[s], b = ib[s];
    const double lx = x[a] - x[b], ly = x[a + 1] - x[b + 1], lz = x[a + 2] - x[b + 2];
    const double wx = v[a] - v[b], wy = v[a + 1] - v[b + 1], wz = v[a + 2] - v[b + 2];
    const double l2 = lx * lx + ly * ly + lz * lz;
    if (l2 == 0.0) continue;
    const double inv = 1.0 / std::sqrt(l2);
    const double sigma = k[s] * (1.0 - r[s] * inv) + kd[s] * (lx * wx + ly * wy + lz * wz) * (inv * inv);
    const double fx = sigma * lx, fy = sigma * ly, fz = sigma * lz;
    f[a] -= fx, f[a + 1] -= fy, f[a + 2] -= fz;
    f[b] += fx, f[b + 1] += fy, f[b + 2] += fz;
  }
}

// The spring's Jacobian blocks (the analytic derivative of the force above):
// with L = |l|, u = l/L, P = I − u uᵀ (the projection across the spring),
//   ∂f_a/∂x_a = −k [u uᵀ + (1 − r/L) P] − (k_d/L) [u (P l′)ᵀ + (l′·u) P]
//   ∂f_a/∂v_a = −k_d u uᵀ
// and ∂f_a/∂x_b = ∂f_b/∂x_a = −∂f_a/∂x_a, ∂f_b/∂x_b = ∂f_a/∂x_a (same for v).
// The second bracket is the damping term's dependence on the direction u; it
// makes ∂f/∂x unsymmetric when the spring stretches or turns.
void spring_blocks(const Vec3& l, const Vec3& w, double k, double kd, double r, Mat3& dx, Mat3& dv) {
  const double L = l.norm();
  const Vec3 u = l / L;
  const Mat3 uu = u * u.transpose();
  const Mat3 P = Mat3::Identity() - uu;
  // A compressed spring's transverse stiffness k (1 − r/L) is negative: it
  // makes M − h²K indefinite once h²k/m is large (cloth placed curved round a
  // body starts with many). Implicit steps use it clamped at 0 (Choi & Ko
  // 2002): the step stays definite; the forces themselves are exact.
  dx = -k * (uu + std::max(0.0, 1.0 - r / L) * P) - (kd / L) * (u * (P * w).transpose() + u.dot(w) * P);
  dv = -kd * uu;
}

// =============================================================================
// [SECTION] The effect
// =============================================================================

class MassSpring final : public Effect, public BlockJacobianEffect {
 public:
  MassSpring(const Model& m, const SpringTopology& top, const MassSpringOptions& o) : opt_(o) {
    const int n = top.size();
    ia_.resize(n), ib_.resize(n);
    for (int s = 0; s < n; ++s) ia_[s] = 3 * top.a[s], ib_[s] = 3 * top.b[s];
    k_ = top.k, kd_ = top.damping, r_ = top.rest;
    stats_.springs = n;

    // The limiter's springs and how each end shares a correction (∝ 1/mass, 0 if fixed).
    std::vector<bool> fixed(m.num_particles(), false);
    for (int p : o.fixed) {
      if (p < 0 || p >= m.num_particles())
        throw SimulationError("mass-spring: options.fixed names particle " + std::to_string(p) +
                              ", but the model has " + std::to_string(m.num_particles()));
      fixed[p] = true;
    }
    if (o.limit_passes < 1)
      throw SimulationError("mass-spring: options.limit_passes = " + std::to_string(o.limit_passes) + "; must be ≥ 1");
    if (!std::isfinite(o.limit_tolerance) || o.limit_tolerance < 0.0)
      throw SimulationError("mass-spring: options.limit_tolerance = " +
                            format_significant(o.limit_tolerance, 6) + "; must be ≥ 0");
    for (int s = 0; s < n; ++s) {
      if (top.max_length[s] <= 0.0) continue;
      const double wa = fixed[top.a[s]] ? 0.0 : 1.0 / m.mass[top.a[s]];
      const double wb = fixed[top.b[s]] ? 0.0 : 1.0 / m.mass[top.b[s]];
      if (wa + wb == 0.0) continue;  // both ends pinned: nothing can move
      lim_spring_.push_back(s);
      lim_length_.push_back(top.max_length[s]);
      lim_share_a_.push_back(wa / (wa + wb));
      lim_share_b_.push_back(wb / (wa + wb));
    }
    stats_.limited_springs = static_cast<int>(lim_spring_.size());
  }

  const char* name() const override { return "mass-spring"; }
  const MassSpringStats& stats() const { return stats_; }

  // Small systems: one pass in spring order. From options.parallel_min_springs
  // on, the springs are cut into kChunks contiguous chunks, whatever the
  // thread count: chunk 0 adds into f, chunk c > 0 into its own buffer over the
  // particles it touches, and the buffers are added in chunk order. Threads
  // only share out the chunks, so the sum is bit-for-bit the same with 1, 2 or
  // 8 threads (the two-garment drape, whose contacts amplify any rounding
  // difference, came to rest with one thread and not with two before).
  void add_forces(const Eval& e, VecX& f) override {
    const int n = static_cast<int>(k_.size());
    if (n < opt_.parallel_min_springs) {
      accumulate_springs(0, n, ia_.data(), ib_.data(), k_.data(), kd_.data(), r_.data(), e.x.data(), e.v.data(),
                         f.data());
      return;
    }
    partition(static_cast<int>(f.size()));
    double* out = f.data();
#pragma omp parallel if (omp_get_max_threads() > 1)
    {
      const int team = omp_get_num_threads();
      for (int c = omp_get_thread_num(); c < kChunks; c += team) {
        double* dst = out;
        if (c > 0) {
          dst = buffers_[c].data();
          std::fill(dst + chunks_[c].lo, dst + chunks_[c].hi, 0.0);
        }
        accumulate_springs(chunks_[c].begin, chunks_[c].end, ia_.data(), ib_.data(), k_.data(), kd_.data(),
                           r_.data(), e.x.data(), e.v.data(), dst);
      }
#pragma omp barrier
#pragma omp for schedule(static)
      for (int d = reduce_lo_; d < reduce_hi_; ++d)
        for (int c = 1; c < kChunks; ++c)
          if (d >= chunks_[c].lo && d < chunks_[c].hi) out[d] += buffers_[c][d];
    }
  }

  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets& dfdv) override {
    const int n = static_cast<int>(k_.size());
    Mat3 kx, kv;
    for (int s = 0; s < n; ++s) {
      const int a = ia_[s] / 3, b = ib_[s] / 3;
      const Vec3 l = at(e.x, a) - at(e.x, b);
      if (l.squaredNorm() == 0.0) continue;
      spring_blocks(l, at(e.v, a) - at(e.v, b), k_[s], kd_[s], r_[s], kx, kv);
      add_block(dfdx, a, a, kx), add_block(dfdx, b, b, kx);
      add_block(dfdx, a, b, -kx), add_block(dfdx, b, a, -kx);
      add_block(dfdv, a, a, kv), add_block(dfdv, b, b, kv);
      add_block(dfdv, a, b, -kv), add_block(dfdv, b, a, -kv);
    }
    return true;
  }

  // The same blocks as add_jacobian, added in the same order straight into
  // the System's block pattern: each spring's four slots (aa, bb, ab, ba) are
  // looked up once per pattern version.
  bool add_jacobian_blocks(const Eval& e, JacobianAssembler& out) override {
    const int n = static_cast<int>(k_.size());
    if (slots_version_ != out.version()) {
      slots_.resize(4 * static_cast<std::size_t>(n));
      for (int s = 0; s < n; ++s) {
        const int a = ia_[s] / 3, b = ib_[s] / 3;
        slots_[4 * s] = out.slot(a, a), slots_[4 * s + 1] = out.slot(b, b);
        slots_[4 * s + 2] = out.slot(a, b), slots_[4 * s + 3] = out.slot(b, a);
      }
      slots_version_ = out.version();
    }
    // spring_blocks written out (same blocks to rounding): with u = l/L,
    // w = v_a − v_b, P = I − u uᵀ and c = max(0, 1 − r/L),
    //   ∂f/∂x = α u uᵀ + β I − γ u (P w)ᵀ,  α = −k (1 − c) + γ u·w,
    //   β = −k c − γ u·w,  γ = k_d / L;      ∂f/∂v = −k_d u uᵀ.
    const double* x = e.x.data();
    const double* v = e.v.data();
    double kx[9], kv[9];
    for (int s = 0; s < n; ++s) {
      const int a = ia_[s], b = ib_[s];
      const double l[3] = {x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]};
      const double L2 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
      if (L2 == 0.0) continue;
      const double L = std::sqrt(L2);
      const double u[3] = {l[0] / L, l[1] / L, l[2] / L};
      const double w[3] = {v[a] - v[b], v[a + 1] - v[b + 1], v[a + 2] - v[b + 2]};
      const double uw = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
      const double pw[3] = {w[0] - uw * u[0], w[1] - uw * u[1], w[2] - uw * u[2]};
      const double c = std::max(0.0, 1.0 - r_[s] / L), gamma = kd_[s] / L;
      const double alpha = -k_[s] * (1.0 - c) + gamma * uw, beta = -k_[s] * c - gamma * uw;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          kx[3 * i + j] = alpha * u[i] * u[j] - gamma * u[i] * pw[j] + (i == j ? beta : 0.0);
          kv[3 * i + j] = -kd_[s] * u[i] * u[j];
        }
      const int* q = &slots_[4 * static_cast<std::size_t>(s)];
      for (int t = 0; t < 4; ++t) {
        if (q[t] < 0) continue;  // a prescribed end
        double *dx = out.dfdx(q[t]), *dv = out.dfdv(q[t]);
        if (t < 2)
          for (int m = 0; m < 9; ++m) dx[m] += kx[m], dv[m] += kv[m];
        else
          for (int m = 0; m < 9; ++m) dx[m] -= kx[m], dv[m] -= kv[m];
      }
    }
    return true;
  }

  // ½ k (|l| − r)² per spring (J); the damping term stores no energy.
  double energy(const Eval& e) const override {
    double u = 0.0;
    for (std::size_t s = 0; s < k_.size(); ++s) {
      const double stretch = (at(e.x, ia_[s] / 3) - at(e.x, ib_[s] / 3)).norm() - r_[s];
      u += 0.5 * k_[s] * stretch * stretch;
    }
    return u;
  }

  // Block Gershgorin (Feingold & Varga 1962): every eigenvalue λ of M⁻¹ ∂f/∂x
  // satisfies |λ| ≤ max_a (1/m_a) Σ_b ‖K_ab‖₂ over the 3 × 3 blocks of row a.
  // A spring puts the block K = k [u uᵀ + (1 − r/L) P] (elastic part, symmetric)
  // on (a, a) and −K on (a, b), and ‖K‖₂ = k max(1, |1 − r/L|): k along the
  // spring, k |1 − r/L| across it (negative under compression). So each spring
  // adds 2 k max(1, |1 − r/L|) to the rows of both its ends, which is 2k for
  // every length L ≥ r/2 — any stretch, and compression to half the rest
  // length, far beyond what cloth sees — and is rotation-invariant, unlike the
  // entry-wise row sums (up to 1.37× larger for a spring off the axes). We
  // take the larger of 2k and its value at the initial placement x0, which may
  // be compressed further. The damping term's dependence on x, of norm
  // ≤ √2 k_d |l′|/L, is left out: it is 0 at rest and, for the seed's
  // k_d = 0.1 N·s/m, under 1 % of k even at strain rates of 100/s.
  // For ∂f/∂v: ‖k_d u uᵀ‖₂ = k_d, so 2 k_d per spring end.
  void add_stiffness_bound(const Model& m, VecX& k_rows, VecX& c_rows) const override {
    for (std::size_t s = 0; s < k_.size(); ++s) {
      const int a = ia_[s] / 3, b = ib_[s] / 3;
      const double L0 = (at(m.x0, a) - at(m.x0, b)).norm();
      const double across = L0 > 0.0 ? std::abs(1.0 - r_[s] / L0) : 1.0;
      const double ks = 2.0 * k_[s] * std::max(1.0, across);
      k_rows[a] += ks, k_rows[b] += ks;
      c_rows[a] += 2.0 * kd_[s], c_rows[b] += 2.0 * kd_[s];
    }
  }

  // Seam merges (seed 002 §3.3): the restructured mesh loses the springs
  // whose ends became one particle and keeps one spring per particle pair.
  // Where two springs now join the same pair (the two hems' edges along a
  // sewn seam) the first in spring order is kept — the spring of the lower
  // particle indices, as E-Fabric keeps the surviving vertex's edge. Keeping
  // the stiffer one was not chosen: it would make the result depend on which
  // material is stiffer along that direction (a warp hem sewn to a weft hem
  // would take the warp constant and rest length), and summing both would
  // double the stiffness of every seam line; one spring per edge is what
  // rebuilding the springs from the merged mesh gives. The limiter's springs
  // and the parallel partition are rebuilt.
  void particles_merged(const Model&, const std::vector<int>& rep) override {
    const int n = static_cast<int>(k_.size());
    std::vector<std::pair<std::array<int, 2>, int>> keyed;  // reduced pair, spring
    keyed.reserve(n);
    for (int s = 0; s < n; ++s) {
      const int ra = rep[ia_[s] / 3], rb = rep[ib_[s] / 3];
      if (ra != rb) keyed.push_back({{std::min(ra, rb), std::max(ra, rb)}, s});
    }
    std::sort(keyed.begin(), keyed.end());  // by pair, then by spring: the first of a pair is kept
    std::vector<int> keep;
    for (std::size_t q = 0; q < keyed.size(); ++q)
      if (q == 0 || keyed[q].first != keyed[q - 1].first) keep.push_back(keyed[q].second);
    if (static_cast<int>(keep.size()) == n) return;
    std::sort(keep.begin(), keep.end());  // original order: neighbouring springs, neighbouring memory
    std::vector<int> new_index(n, -1);
    auto pick = [&](auto& v) {
      std::remove_reference_t<decltype(v)> out;
      out.reserve(keep.size());
      for (int s : keep) out.push_back(v[s]);
      v = std::move(out);
    };
    for (std::size_t q = 0; q < keep.size(); ++q) new_index[keep[q]] = static_cast<int>(q);
    pick(ia_), pick(ib_), pick(k_), pick(kd_), pick(r_);
    slots_version_ = -1;  // other springs: block slots are looked up again
    std::size_t w = 0;
    for (std::size_t q = 0; q < lim_spring_.size(); ++q) {
      if (new_index[lim_spring_[q]] < 0) continue;
      lim_spring_[w] = new_index[lim_spring_[q]];
      lim_length_[w] = lim_length_[q], lim_share_a_[w] = lim_share_a_[q], lim_share_b_[w] = lim_share_b_[q];
      ++w;
    }
    lim_spring_.resize(w), lim_length_.resize(w), lim_share_a_.resize(w), lim_share_b_.resize(w);
    stats_.springs = static_cast<int>(k_.size());
    stats_.limited_springs = static_cast<int>(w);
    chunks_.clear();
    buffer_dofs_ = -1;
  }

  // Provot (1995), "Deformation constraints in a mass-spring model to describe
  // rigid cloth behavior": after the step, every limited spring longer than
  // L_max = (1 + max_strain) r is shortened to L_max by moving its ends along
  // it, shares ∝ 1/mass (equal halves for the seed's equal masses; particles in
  // options.fixed do not move), and the ends' separating velocity along the
  // spring is removed (an approaching velocity is kept). Momentum is conserved.
  // Gauss–Seidel passes in spring order repeat until a pass corrects nothing
  // or options.limit_passes is reached; springs within
  // L_max (1 + limit_tolerance) are left alone.
  // Why a cap and a tolerance: each correction of equal halves pulls the
  // neighbouring springs, so on long loaded chains the passes converge like a
  // diffusion, in O(chain length²) passes. Where springs carry a local excess
  // (Provot's use: the corners of a hanging cloth) a few passes suffice; where
  // the limit must carry most of the weight (the seed's 90 kg flag from two
  // corners) it does not converge within a step, and the stats say so
  // (unresolved_steps, last_unresolved) instead of spending unbounded time.
  void after_step(const Model&, State& st) override {
    if (lim_spring_.empty()) return;
    double* x = st.x.data();
    double* v = st.v.data();
    const double slack = 1.0 + opt_.limit_tolerance;
    int passes = 0;
    long corrected = 0;
    bool clean = false;
    while (!clean && passes < opt_.limit_passes) {
      ++passes;
      clean = true;
      for (std::size_t q = 0; q < lim_spring_.size(); ++q) {
        const int s = lim_spring_[q], a = ia_[s], b = ib_[s];
        const Vec3 l(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]);
        const double L = l.norm(), L_max = lim_length_[q];
        if (L <= L_max * slack) continue;
        clean = false;
        ++corrected;
        const Vec3 d = l / L;
        const double excess = L - L_max;
        const double sa = lim_share_a_[q], sb = lim_share_b_[q];
        for (int c = 0; c < 3; ++c) x[a + c] -= sa * excess * d[c], x[b + c] += sb * excess * d[c];
        const double separating = (v[a] - v[b]) * d[0] + (v[a + 1] - v[b + 1]) * d[1] + (v[a + 2] - v[b + 2]) * d[2];
        if (separating > 0.0)
          for (int c = 0; c < 3; ++c) v[a + c] -= sa * separating * d[c], v[b + c] += sb * separating * d[c];
      }
    }
    // What is left when the passes ran out.
    int unresolved = 0;
    if (!clean)
      for (std::size_t q = 0; q < lim_spring_.size(); ++q) {
        const int a = ia_[lim_spring_[q]], b = ib_[lim_spring_[q]];
        const Vec3 l(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]);
        if (l.norm() > lim_length_[q] * slack) ++unresolved;
      }
    stats_.corrections += corrected;
    if (corrected > 0) ++stats_.limited_steps;
    if (unresolved > 0) ++stats_.unresolved_steps;
    stats_.last_passes = passes;
    stats_.last_unresolved = unresolved;
  }

 private:
  struct Chunk {
    int begin = 0, end = 0;  // springs
    int lo = 0, hi = 0;      // dofs touched
  };

  // Chunks of the parallel sum: fixed, so the thread count cannot change the
  // result; 8 keeps up to 8 cores busy at little cost on fewer.
  static constexpr int kChunks = 8;

  // Cuts the springs into kChunks chunks and sizes the buffers; allocates
  // only when the number of dofs changes.
  void partition(int dofs) {
    if (static_cast<int>(chunks_.size()) == kChunks && buffer_dofs_ == dofs) return;
    const int n = static_cast<int>(k_.size());
    chunks_.assign(kChunks, {});
    buffers_.assign(kChunks, VecX());
    buffer_dofs_ = dofs;
    reduce_lo_ = dofs, reduce_hi_ = 0;
    for (int c = 0; c < kChunks; ++c) {
      Chunk& ch = chunks_[c];
      ch.begin = static_cast<int>(static_cast<long>(n) * c / kChunks);
      ch.end = static_cast<int>(static_cast<long>(n) * (c + 1) / kChunks);
      ch.lo = dofs, ch.hi = 0;
      for (int s = ch.begin; s < ch.end; ++s) {
        ch.lo = std::min({ch.lo, ia_[s], ib_[s]});
        ch.hi = std::max({ch.hi, ia_[s] + 3, ib_[s] + 3});
      }
      if (ch.begin == ch.end) ch.lo = ch.hi = 0;
      if (c > 0) {
        buffers_[c] = VecX::Zero(dofs);
        reduce_lo_ = std::min(reduce_lo_, ch.lo);
        reduce_hi_ = std::max(reduce_hi_, ch.hi);
      }
    }
  }

  MassSpringOptions opt_;
  // Springs, structure of arrays: 3 × end indices, k (N/m), k_d (N·s/m), rest length (m).
  std::vector<int> ia_, ib_;
  std::vector<double> k_, kd_, r_;
  std::vector<int> slots_;   // per spring, block slots aa, bb, ab, ba (add_jacobian_blocks)
  long slots_version_ = -1;  // the pattern version slots_ belong to
  // Limited springs: spring index, L_max (m), share of the correction each end takes.
  std::vector<int> lim_spring_;
  std::vector<double> lim_length_, lim_share_a_, lim_share_b_;
  // Parallel force sums.
  std::vector<Chunk> chunks_;
  std::vector<VecX> buffers_;
  int buffer_dofs_ = 0, reduce_lo_ = 0, reduce_hi_ = 0;
  MassSpringStats stats_;
};

}  // namespace

std::unique_ptr<Effect> make_mass_spring(const Model& m, const std::vector<MassSpringMaterial>& per_piece,
                                         const MassSpringOptions& options) {
  if (options.parallel_min_springs < 0)
    throw SimulationError("mass-spring: options.parallel_min_springs must be ≥ 0");
  return std::make_unique<MassSpring>(m, mass_spring_topology(m, per_piece), options);
}

const MassSpringStats* mass_spring_stats(const Effect& e) {
  const auto* ms = dynamic_cast<const MassSpring*>(&e);
  return ms ? &ms->stats() : nullptr;
}

}  // namespace vgd::sim
