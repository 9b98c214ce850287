// Material damping: a dashpot along every mesh edge (damps stretching only).
// f_i = -c ((v_i - v_j)·d) d, f_j = -f_i, d = (x_i - x_j)/|x_i - x_j|.
#include <algorithm>
#include <cmath>

#include "vgd/sim/effects/basic.hpp"

namespace vgd::sim {

std::vector<std::array<int, 2>> mesh_edges(const std::vector<std::array<int, 3>>& triangles) {
  std::vector<std::array<int, 2>> e;
  e.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) e.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  return e;
}

namespace {

class Damping final : public Effect {
 public:
  Damping(const Model& m, const DampingDef& d) : c_(d.c), edges_(mesh_edges(m.triangles)) {}
  const char* name() const override { return "damping"; }
  void add_forces(const Eval& e, VecX& f) override {
    for (const auto& [i, j] : edges_) {
      const Vec3 d = at(e.x, i) - at(e.x, j);
      const double len2 = d.squaredNorm();
      if (len2 == 0.0) continue;
      const Vec3 fi = -c_ * (at(e.v, i) - at(e.v, j)).dot(d) / len2 * d;
      at(f, i) += fi;
      at(f, j) -= fi;
    }
  }
  // Exact in v; the dependence of d on x is left out (it vanishes at rest).
  bool add_jacobian(const Eval& e, Triplets&, Triplets& dfdv) override {
    for (const auto& [i, j] : edges_) {
      const Vec3 d = at(e.x, i) - at(e.x, j);
      const double len2 = d.squaredNorm();
      if (len2 == 0.0) continue;
      const Mat3 b = -c_ * d * d.transpose() / len2;
      add_block(dfdv, i, i, b);
      add_block(dfdv, j, j, b);
      add_block(dfdv, i, j, -b);
      add_block(dfdv, j, i, -b);
    }
    return false;
  }
  // Seam merges: the merged mesh's edges (merged_topology): dashpots whose
  // ends became one particle go, and of two on one particle pair the first is
  // kept (one dashpot per edge, as mass-spring keeps one spring per edge).
  void particles_merged(const Model&, const std::vector<int>& rep) override {
    std::vector<std::pair<std::array<int, 2>, std::size_t>> keyed;
    for (std::size_t q = 0; q < edges_.size(); ++q) {
      const int ra = rep[edges_[q][0]], rb = rep[edges_[q][1]];
      if (ra != rb) keyed.push_back({{std::min(ra, rb), std::max(ra, rb)}, q});
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::size_t> keep;
    for (std::size_t q = 0; q < keyed.size(); ++q)
      if (q == 0 || keyed[q].first != keyed[q - 1].first) keep.push_back(keyed[q].second);
    std::sort(keep.begin(), keep.end());
    std::vector<std::array<int, 2>> kept;
    kept.reserve(keep.size());
    for (std::size_t q : keep) kept.push_back(edges_[q]);
    edges_ = std::move(kept);
  }
  void add_stiffness_bound(const Model&, VecX&, VecX& c) const override {
    for (const auto& [i, j] : edges_) {
      c[i] += 2 * c_;
      c[j] += 2 * c_;
    }
  }

 private:
  double c_;
  std::vector<std::array<int, 2>> edges_;
};

}  // namespace

std::unique_ptr<Effect> make_damping(const Model& model, const DampingDef& def) {
  return std::make_unique<Damping>(model, def);
}

}  // namespace vgd::sim
