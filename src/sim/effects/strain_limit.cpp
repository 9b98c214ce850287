// Yarn strain limiting on triangles (include/vgd/sim/effects/strain_limit.hpp).
#include "vgd/sim/effects/strain_limit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace vgd::sim {
namespace {

using Mat32 = Eigen::Matrix<double, 3, 2>;

class StrainLimit final : public Effect {
 public:
  StrainLimit(const Model& m, const StrainLimitDef& d) : passes_(d.passes), tolerance_(d.tolerance) {
    if (d.passes < 1) throw SimulationError("strain limit: passes must be at least 1");
    if (!(d.tolerance >= 0.0) || !std::isfinite(d.tolerance))
      throw SimulationError("strain limit: tolerance must be a finite number >= 0");
    const int pieces = std::max<int>(1, static_cast<int>(m.pieces.size()));
    if (static_cast<int>(d.limit.size()) != pieces)
      throw SimulationError("strain limit: " + std::to_string(d.limit.size()) + " limits given for " +
                            std::to_string(pieces) + " pieces");
    for (std::size_t p = 0; p < d.limit.size(); ++p)
      if (!(d.limit[p] >= 0.0) || !std::isfinite(d.limit[p]))
        throw SimulationError("strain limit: the limit of piece " + std::to_string(p) +
                              " must be a finite strain >= 0 (0 = none)");
    fixed_.assign(m.num_particles(), 0);
    for (int i : d.fixed)
      if (i >= 0 && i < m.num_particles()) fixed_[i] = 1;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const int piece = m.triangle_piece.empty() ? 0 : m.triangle_piece[t];
      const double limit = piece < static_cast<int>(d.limit.size()) ? d.limit[piece] : 0.0;
      if (!(limit > 0.0)) continue;
      const auto& T = m.triangles[t];
      Eigen::Matrix2d D;
      D.col(0) = m.uv[T[1]] - m.uv[T[0]];
      D.col(1) = m.uv[T[2]] - m.uv[T[0]];
      // A rest triangle of (nearly) no area has no deformation gradient.
      if (!(std::abs(D.determinant()) >= 1e-14)) continue;
      Tri tri;
      tri.v = T;
      tri.d_inv = D.inverse();
      tri.stretch_max = 1.0 + limit;
      double mass = 0.0;
      Vec2 centre = Vec2::Zero();
      for (int k = 0; k < 3; ++k) mass += m.mass[T[k]], centre += m.mass[T[k]] * m.uv[T[k]];
      if (!(mass > 0.0)) continue;
      centre /= mass;
      for (int k = 0; k < 3; ++k) {
        tri.w[k] = m.mass[T[k]] / mass;
        tri.r[k] = m.uv[T[k]] - centre;
      }
      tris_.push_back(tri);
    }
    if (tris_.empty()) throw SimulationError("strain limit: no piece has a limit > 0");
    stats_.triangles = static_cast<int>(tris_.size());
  }

  const char* name() const override { return "strain-limit"; }
  void add_forces(const Eval&, VecX&) override {}
  bool add_jacobian(const Eval&, Triplets&, Triplets&) override { return true; }
  // Cloth moving centimetres between frames is stretched unseen in between.
  bool needs_every_step() const override { return true; }

  void after_step(const Model&, State& s) override {
    int passes = 0;
    long corrected = 0;
    bool clean = false;
    while (!clean && passes < passes_) {
      ++passes;
      clean = true;
      for (const Tri& t : tris_)
        if (limit(t, s)) clean = false, ++corrected;
    }
    int unresolved = 0;
    if (!clean)
      for (const Tri& t : tris_) unresolved += over(t, s) ? 1 : 0;
    stats_.corrections += corrected;
    if (corrected > 0) ++stats_.limited_steps;
    if (unresolved > 0) ++stats_.unresolved_steps;
    stats_.last_passes = passes;
    stats_.last_unresolved = unresolved;
  }

  const StrainLimitStats& stats() const { return stats_; }

 private:
  struct Tri {
    std::array<int, 3> v{};
    Eigen::Matrix2d d_inv;     // 1/m: inverse of the rest edge matrix [u1−u0, u2−u0]
    std::array<Vec2, 3> r;     // m: rest corners from the mass-weighted rest centroid
    std::array<double, 3> w{};  // mass shares (sum 1)
    double stretch_max = 1.0;  // 1 + limit
  };

  Mat32 gradient(const Tri& t, const VecX& x) const {
    Mat32 e;
    e.col(0) = at(x, t.v[1]) - at(x, t.v[0]);
    e.col(1) = at(x, t.v[2]) - at(x, t.v[0]);
    return e * t.d_inv;
  }

  bool over(const Tri& t, const State& s) const {
    const Mat32 F = gradient(t, s.x);
    const double bound = t.stretch_max * (1.0 + tolerance_);
    return F.col(0).norm() > bound || F.col(1).norm() > bound;
  }

  // Brings one triangle back within its limit; false when it was within it.
  bool limit(const Tri& t, State& s) {
    const Mat32 F = gradient(t, s.x);
    const double bound = t.stretch_max * (1.0 + tolerance_);
    const std::array<double, 2> len{F.col(0).norm(), F.col(1).norm()};
    if (!(len[0] > bound) && !(len[1] > bound)) return false;
    int nfixed = 0;
    for (int k = 0; k < 3; ++k) nfixed += fixed_[t.v[k]];
    if (nfixed == 3) return false;
    Mat32 G = F;
    std::array<bool, 2> clamped{false, false};
    for (int c = 0; c < 2; ++c)
      if (len[c] > bound) G.col(c) *= t.stretch_max / len[c], clamped[c] = true;
    // Positions: the limited shape about the current centroid, shifted to
    // keep pinned corners where they are.
    Vec3 centre = Vec3::Zero();
    for (int k = 0; k < 3; ++k) centre += t.w[k] * at(s.x, t.v[k]);
    std::array<Vec3, 3> target;
    for (int k = 0; k < 3; ++k) target[k] = centre + G * t.r[k];
    if (nfixed > 0) {
      Vec3 shift = Vec3::Zero();
      for (int k = 0; k < 3; ++k)
        if (fixed_[t.v[k]]) shift += at(s.x, t.v[k]) - target[k];
      shift /= nfixed;
      for (int k = 0; k < 3; ++k) target[k] += shift;
    }
    // Velocities: the yarn's stretching rate removed.
    Mat32 L;
    L.col(0) = at(s.v, t.v[1]) - at(s.v, t.v[0]);
    L.col(1) = at(s.v, t.v[2]) - at(s.v, t.v[0]);
    L = L * t.d_inv;
    Mat32 dL = Mat32::Zero();
    for (int c = 0; c < 2; ++c) {
      if (!clamped[c]) continue;
      const Vec3 dir = G.col(c) / t.stretch_max;
      const double rate = dir.dot(L.col(c));
      if (rate > 0.0) dL.col(c) = -rate * dir;
    }
    // The same gradient change, shifted so that pinned corners keep theirs.
    Vec3 dv_shift = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      if (fixed_[t.v[k]]) dv_shift -= dL * t.r[k] / nfixed;
    for (int k = 0; k < 3; ++k) {
      if (fixed_[t.v[k]]) continue;
      at(s.x, t.v[k]) = target[k];
      at(s.v, t.v[k]) += dL * t.r[k] + dv_shift;
    }
    return true;
  }

  int passes_;
  double tolerance_;
  std::vector<char> fixed_;
  std::vector<Tri> tris_;
  StrainLimitStats stats_;
};

}  // namespace

std::unique_ptr<Effect> make_strain_limit(const Model& model, const StrainLimitDef& def) {
  return std::make_unique<StrainLimit>(model, def);
}

const StrainLimitStats* strain_limit_stats(const Effect& effect) {
  const auto* e = dynamic_cast<const StrainLimit*>(&effect);
  return e ? &e->stats() : nullptr;
}

}  // namespace vgd::sim
