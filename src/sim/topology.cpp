// The restructured mesh after seam merges; see the header.
#include "vgd/sim/topology.hpp"

#include <algorithm>
#include <numeric>

#include "vgd/core/diagnostics.hpp"

namespace vgd::sim {

std::vector<int> identity_representative(int particles) {
  std::vector<int> r(static_cast<std::size_t>(particles));
  std::iota(r.begin(), r.end(), 0);
  return r;
}

void average_merged_copies(const std::vector<int>& representative, const VecX& mass, VecX& x) {
  const int n = static_cast<int>(representative.size());
  if (x.size() != 3 * static_cast<Eigen::Index>(n) || mass.size() != n) return;
  std::vector<Vec3> sum(n, Vec3::Zero());
  std::vector<double> total(n, 0.0);
  for (int i = 0; i < n; ++i) {
    sum[representative[i]] += mass[i] * at(x, i);
    total[representative[i]] += mass[i];
  }
  for (int i = 0; i < n; ++i) at(x, i) = sum[representative[i]] / total[representative[i]];
}

namespace {
std::vector<std::array<int, 2>> sorted_edges(const std::vector<std::array<int, 3>>& triangles) {
  std::vector<std::array<int, 2>> e;
  e.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) e.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  std::sort(e.begin(), e.end());
  return e;
}
}  // namespace

MergedMesh merged_topology(const Model& m, const std::vector<int>& representative) {
  VGD_ASSERT(static_cast<int>(representative.size()) == m.num_particles(),
             "merged_topology: one representative per particle");
  MergedMesh out;
  out.particles = representative.empty() ? 0 : *std::max_element(representative.begin(), representative.end()) + 1;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& T = m.triangles[t];
    const std::array<int, 3> r{representative[T[0]], representative[T[1]], representative[T[2]]};
    if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2]) {
      ++out.collapsed_triangles;
      continue;
    }
    out.triangles.push_back(r);
    out.source_triangle.push_back(static_cast<int>(t));
  }
  out.edges = sorted_edges(out.triangles);
  out.edges.erase(std::unique(out.edges.begin(), out.edges.end()), out.edges.end());
  auto original = sorted_edges(m.triangles);
  original.erase(std::unique(original.begin(), original.end()), original.end());
  out.merged_edges = static_cast<int>(original.size()) - static_cast<int>(out.edges.size());
  return out;
}

MeshCheck check_mesh(const std::vector<std::array<int, 3>>& triangles) {
  MeshCheck c;
  c.triangles = static_cast<int>(triangles.size());
  std::vector<std::array<int, 3>> keys;
  keys.reserve(triangles.size());
  for (const auto& t : triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) ++c.degenerate_triangles;
    auto k = t;
    std::sort(k.begin(), k.end());
    keys.push_back(k);
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i] == keys[i - 1]) ++c.duplicate_triangles;
  const auto e = sorted_edges(triangles);
  for (std::size_t s = 0; s < e.size();) {
    std::size_t x = s;
    while (x < e.size() && e[x] == e[s]) ++x;
    if (e[s][0] != e[s][1]) {  // a degenerate triangle's zero-length side is not an edge
      ++c.edges;
      const std::size_t n = x - s;
      if (n == 1) ++c.boundary_edges;
      else if (n == 2) ++c.interior_edges;
      else {
        ++c.non_manifold_edges;
        c.non_manifold.push_back(e[s]);
      }
    }
    s = x;
  }
  return c;
}

}  // namespace vgd::sim
