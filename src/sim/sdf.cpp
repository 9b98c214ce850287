// Signed distance grid and triangle BVH of a closed mesh (include/vgd/sim/sdf.hpp).
#include "vgd/sim/sdf.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <utility>

namespace vgd::sim {

namespace {
// Below this many grid nodes the threads cost more than the band they share.
constexpr std::size_t kParallelMinNodes = 100000;
}  // namespace

// ---------------------------------------------------------------------------
// Pseudo-normals
// ---------------------------------------------------------------------------

MeshNormals::MeshNormals(const mesh::SurfaceMesh& m) {
  const int nt = m.num_triangles();
  face_.resize(nt);
  vertex_.assign(m.num_vertices(), Vec3::Zero());
  edge_.resize(nt);
  std::map<std::pair<int, int>, Vec3> edge_sum;  // undirected edge -> Σ adjacent face normals
  for (int t = 0; t < nt; ++t) {
    const auto& tr = m.triangles[t];
    const Vec3 &a = m.vertices[tr[0]], &b = m.vertices[tr[1]], &c = m.vertices[tr[2]];
    Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    face_[t] = len > 0 ? Vec3(n / len) : Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const int i = tr[k], j = tr[(k + 1) % 3], l = tr[(k + 2) % 3];
      // Angle at corner i, the weight of this face in i's pseudo-normal.
      const Vec3 e1 = (m.vertices[j] - m.vertices[i]).normalized(),
                 e2 = (m.vertices[l] - m.vertices[i]).normalized();
      const double angle = std::acos(std::clamp(e1.dot(e2), -1.0, 1.0));
      vertex_[i] += angle * face_[t];
      // Eigen leaves a default-constructed vector uninitialised: insert zero first.
      edge_sum.try_emplace({std::min(i, j), std::max(i, j)}, Vec3::Zero()).first->second += face_[t];
    }
  }
  for (auto& n : vertex_) n.normalize();
  for (int t = 0; t < nt; ++t) {
    const auto& tr = m.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int i = tr[k], j = tr[(k + 1) % 3];
      edge_[t][k] = edge_sum[{std::min(i, j), std::max(i, j)}].normalized();
    }
  }
  vtri_ = m.triangles;
}

Vec3 MeshNormals::pseudo_normal(int t, const Vec3& b) const {
  // Which barycentric coordinates vanish tells the feature: none → face,
  // one → the opposite edge, two → the remaining vertex.
  constexpr double eps = 1e-9;
  const bool z0 = b[0] <= eps, z1 = b[1] <= eps, z2 = b[2] <= eps;
  const int zeros = int(z0) + int(z1) + int(z2);
  if (zeros == 0) return face_[t];
  if (zeros == 1) return z2 ? edge_[t][0] : z0 ? edge_[t][1] : edge_[t][2];
  const auto& tr = vtri_[t];
  return !z0 ? vertex_[tr[0]] : !z1 ? vertex_[tr[1]] : vertex_[tr[2]];
}

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& bary) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) {
    bary = {1, 0, 0};
    return a;
  }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) {
    bary = {0, 1, 0};
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    bary = {1 - v, v, 0};
    return a + v * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) {
    bary = {0, 0, 1};
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    bary = {1 - w, 0, w};
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    bary = {0, 1 - w, w};
    return b + w * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  bary = {1 - v - w, v, w};
  return a + v * ab + w * ac;
}

// ---------------------------------------------------------------------------
// Signed distance grid
// ---------------------------------------------------------------------------

SignedDistanceGrid::SignedDistanceGrid(const mesh::SurfaceMesh& m, const SdfOptions& o)
    : h_(o.spacing), inv_h_(1.0 / o.spacing), band_(o.band) {
  if (!(o.spacing > 0) || !(o.band > 0) || m.triangles.empty())
    throw SimulationError("signed distance grid: spacing and band must be > 0 and the mesh non-empty");
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // One band plus two cells of margin: the box boundary lies outside the band,
  // so the flood fill below starts from far-field nodes.
  const double margin = band_ + 2 * h_;
  origin_ = lo - Vec3::Constant(margin);
  const Vec3 extent = hi - lo + Vec3::Constant(2 * margin);
  nx_ = static_cast<int>(std::ceil(extent.x() * inv_h_)) + 1;
  ny_ = static_cast<int>(std::ceil(extent.y() * inv_h_)) + 1;
  nz_ = static_cast<int>(std::ceil(extent.z() * inv_h_)) + 1;
  const std::size_t count = static_cast<std::size_t>(nx_) * ny_ * nz_;
  if (count > (std::size_t(1) << 31))
    throw SimulationError("signed distance grid: " + std::to_string(count) + " nodes; use a larger spacing");

  // Narrow band: every triangle visits the nodes of its box grown by the band.
  const MeshNormals normals(m);
  std::vector<float> dist(count, std::numeric_limits<float>::infinity());
  std::vector<signed char> sign(count, 0);
  const float bandf = static_cast<float>(band_);
  // Threads take slabs of z and every triangle's nodes in their slab: each
  // node still sees the triangles in order, so the grid does not depend on
  // the thread count.
#pragma omp parallel if (count >= kParallelMinNodes)
  {
    const int slabs = omp_get_num_threads(), slab = omp_get_thread_num();
    const int slab_lo = static_cast<int>(static_cast<long>(nz_) * slab / slabs);
    const int slab_hi = static_cast<int>(static_cast<long>(nz_) * (slab + 1) / slabs) - 1;
    for (int t = 0; t < m.num_triangles(); ++t) {
      const auto& tr = m.triangles[t];
      const Vec3 &a = m.vertices[tr[0]], &b = m.vertices[tr[1]], &c = m.vertices[tr[2]];
      const Vec3 tlo = a.cwiseMin(b).cwiseMin(c) - Vec3::Constant(band_) - origin_;
      const Vec3 thi = a.cwiseMax(b).cwiseMax(c) + Vec3::Constant(band_) - origin_;
      const int i0 = std::max(0, static_cast<int>(std::ceil(tlo.x() * inv_h_)));
      const int j0 = std::max(0, static_cast<int>(std::ceil(tlo.y() * inv_h_)));
      const int k0 = std::max(slab_lo, static_cast<int>(std::ceil(tlo.z() * inv_h_)));
      const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor(thi.x() * inv_h_)));
      const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor(thi.y() * inv_h_)));
      const int k1 = std::min(slab_hi, static_cast<int>(std::floor(thi.z() * inv_h_)));
      if (k0 > k1) continue;
      const Vec3& fn = normals.face_normal(t);
      // The triangle lies in the ball about its box's centre through the box's
      // corners: a node farther than that radius plus the band from the
      // centre is beyond the band (1 µm spared for rounding), so each row is
      // visited only where it crosses the grown ball. Only nodes the test
      // below would reject are skipped: the grid is the same, bit for bit.
      const Vec3 centre = 0.5 * (a.cwiseMin(b).cwiseMin(c) + a.cwiseMax(b).cwiseMax(c));
      const double reach = 0.5 * (a.cwiseMax(b).cwiseMax(c) - a.cwiseMin(b).cwiseMin(c)).norm() + band_ + 1e-6;
      const double reach2 = reach * reach;
      for (int k = k0; k <= k1; ++k)
        for (int j = j0; j <= j1; ++j) {
          const std::size_t row = (static_cast<std::size_t>(k) * ny_ + j) * nx_;
          // The row's nodes within the ball: |x − cx| ≤ sqrt(reach² − r⊥²).
          const double dy = origin_.y() + h_ * j - centre.y(), dz = origin_.z() + h_ * k - centre.z();
          const double across = reach2 - dy * dy - dz * dz;
          if (across <= 0.0) continue;
          const double half = std::sqrt(across);
          const int ia = std::max(i0, static_cast<int>(std::floor((centre.x() - half - origin_.x()) * inv_h_)));
          const int ib = std::min(i1, static_cast<int>(std::ceil((centre.x() + half - origin_.x()) * inv_h_)));
          for (int i = ia; i <= ib; ++i) {
            const Vec3 p = origin_ + h_ * Vec3(i, j, k);
            // The plane distance bounds the triangle distance from below: a cheap rejection.
            const double plane = std::abs((p - a).dot(fn));
            if (plane >= band_ || plane >= dist[row + i]) continue;
            Vec3 bary;
            const Vec3 q = closest_point_on_triangle(p, a, b, c, bary);
            const double d = (p - q).norm();
            if (d >= band_ || d >= dist[row + i]) continue;
            dist[row + i] = static_cast<float>(d);
            sign[row + i] = (p - q).dot(normals.pseudo_normal(t, bary)) < 0 ? -1 : 1;
          }
        }
    }
  }

  // Far field: nodes reachable from the box boundary without crossing the band
  // are outside; the rest are inside. 6-connected flood fill; the band is at
  // least one cell thick wherever the surface passes, so nothing leaks.
  phi_.assign(count, 0.0f);
  std::vector<signed char> far(count, 0);  // 0 unknown, 1 outside
  std::vector<std::uint32_t> stack;        // node indices (count < 2³¹)
  const std::uint32_t sx = 1, sy = static_cast<std::uint32_t>(nx_),
                      sz = static_cast<std::uint32_t>(nx_) * static_cast<std::uint32_t>(ny_);
  auto seed = [&](std::uint32_t n) {
    if (sign[n] == 0 && !far[n]) {
      far[n] = 1;
      stack.push_back(n);
    }
  };
  // The box's six faces (the reachable set does not depend on the order).
  for (int k = 0; k < nz_; ++k)
    for (int j = 0; j < ny_; ++j) {
      const bool face = k == 0 || j == 0 || k == nz_ - 1 || j == ny_ - 1;
      const std::uint32_t row = k * sz + j * sy;
      if (face)
        for (int i = 0; i < nx_; ++i) seed(row + i);
      else
        seed(row), seed(row + nx_ - 1);
    }
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    const std::uint32_t k = n / sz, rem = n - k * sz, j = rem / sy, i = rem - j * sy;
    if (i > 0) seed(n - sx);
    if (static_cast<int>(i) < nx_ - 1) seed(n + sx);
    if (j > 0) seed(n - sy);
    if (static_cast<int>(j) < ny_ - 1) seed(n + sy);
    if (k > 0) seed(n - sz);
    if (static_cast<int>(k) < nz_ - 1) seed(n + sz);
  }
  for (std::size_t n = 0; n < count; ++n) {
    if (sign[n] != 0) {
      phi_[n] = sign[n] * dist[n];
      ++band_nodes_;
    } else {
      phi_[n] = far[n] ? bandf : -bandf;
    }
  }
}

double SignedDistanceGrid::distance(const Vec3& p) const {
  Vec3 g;
  return sample(p, g);
}

double SignedDistanceGrid::sample(const Vec3& p, Vec3& gradient) const {
  const Vec3 u = (p - origin_) * inv_h_;
  const int i = static_cast<int>(std::floor(u.x())), j = static_cast<int>(std::floor(u.y())),
            k = static_cast<int>(std::floor(u.z()));
  if (i < 0 || j < 0 || k < 0 || i >= nx_ - 1 || j >= ny_ - 1 || k >= nz_ - 1) {
    gradient.setZero();
    return band_;
  }
  const double fx = u.x() - i, fy = u.y() - j, fz = u.z() - k;
  const std::size_t sx = 1, sy = nx_, sz = static_cast<std::size_t>(nx_) * ny_;
  const float* c = &phi_[k * sz + j * sy + i];
  const double c000 = c[0], c100 = c[sx], c010 = c[sy], c110 = c[sy + sx];
  const double c001 = c[sz], c101 = c[sz + sx], c011 = c[sz + sy], c111 = c[sz + sy + sx];
  // Interpolate along x, then y, then z; the gradient is the exact derivative
  // of the trilinear interpolant.
  const double c00 = c000 + fx * (c100 - c000), c10 = c010 + fx * (c110 - c010);
  const double c01 = c001 + fx * (c101 - c001), c11 = c011 + fx * (c111 - c011);
  const double c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
  const double d = c0 + fz * (c1 - c0);
  const double dx0 = (1 - fy) * (c100 - c000) + fy * (c110 - c010);
  const double dx1 = (1 - fy) * (c101 - c001) + fy * (c111 - c011);
  gradient.x() = ((1 - fz) * dx0 + fz * dx1) * inv_h_;
  gradient.y() = ((1 - fz) * (c10 - c00) + fz * (c11 - c01)) * inv_h_;
  gradient.z() = (c1 - c0) * inv_h_;
  return d;
}

// ---------------------------------------------------------------------------
// BVH
// ---------------------------------------------------------------------------

namespace {
constexpr int kLeafSize = 4;

double box_distance2(const std::array<float, 3>& lo, const std::array<float, 3>& hi, const Vec3& p) {
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double e = std::max({static_cast<double>(lo[a]) - p[a], 0.0, p[a] - static_cast<double>(hi[a])});
    d2 += e * e;
  }
  return d2;
}
}  // namespace

TriangleBvh::TriangleBvh(const mesh::SurfaceMesh& m) : v_(m.vertices), t_(m.triangles), normals_(m) {
  const int nt = static_cast<int>(t_.size());
  order_.resize(nt);
  std::vector<Vec3> centre(nt);
  for (int t = 0; t < nt; ++t) {
    order_[t] = t;
    centre[t] = (v_[t_[t][0]] + v_[t_[t][1]] + v_[t_[t][2]]) / 3.0;
  }
  nodes_.reserve(2 * nt / kLeafSize + 2);
  nodes_.push_back({});
  // Top-down median split along the widest axis of the centroids.
  struct Task {
    int node, first, count;
  };
  std::vector<Task> todo{{0, 0, nt}};
  while (!todo.empty()) {
    const Task task = todo.back();
    todo.pop_back();
    Vec3 lo = Vec3::Constant(1e300), hi = -lo, clo = lo, chi = hi;
    for (int k = task.first; k < task.first + task.count; ++k) {
      const auto& tr = t_[order_[k]];
      for (int c : tr) {
        lo = lo.cwiseMin(v_[c]);
        hi = hi.cwiseMax(v_[c]);
      }
      clo = clo.cwiseMin(centre[order_[k]]);
      chi = chi.cwiseMax(centre[order_[k]]);
    }
    Node& nd = nodes_[task.node];
    // Float boxes rounded outward: never smaller than the double box.
    for (int a = 0; a < 3; ++a) {
      nd.lo[a] = std::nextafter(static_cast<float>(lo[a]), -1e30f);
      nd.hi[a] = std::nextafter(static_cast<float>(hi[a]), 1e30f);
    }
    if (task.count <= kLeafSize) {
      nd.first = task.first;
      nd.count = task.count;
      continue;
    }
    int axis;
    (chi - clo).maxCoeff(&axis);
    const int half = task.count / 2;
    std::nth_element(order_.begin() + task.first, order_.begin() + task.first + half,
                     order_.begin() + task.first + task.count,
                     [&](int x, int y) { return centre[x][axis] < centre[y][axis]; });
    const int child = static_cast<int>(nodes_.size());
    nd.first = child;
    nd.count = 0;
    nodes_.push_back({});
    nodes_.push_back({});
    todo.push_back({child, task.first, half});
    todo.push_back({child + 1, task.first + half, task.count - half});
  }
}

TriangleBvh::Closest TriangleBvh::closest(const Vec3& p, double max_distance) const {
  Closest best;
  double best2 = max_distance * max_distance;
  Vec3 best_bary = Vec3::Zero();
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& nd = nodes_[stack[--top]];
    if (box_distance2(nd.lo, nd.hi, p) >= best2) continue;
    if (nd.count > 0) {
      for (int k = nd.first; k < nd.first + nd.count; ++k) {
        const int t = order_[k];
        Vec3 bary;
        const Vec3 q = closest_point_on_triangle(p, v_[t_[t][0]], v_[t_[t][1]], v_[t_[t][2]], bary);
        const double d2 = (p - q).squaredNorm();
        if (d2 < best2) {
          best2 = d2;
          best.point = q;
          best.triangle = t;
          best_bary = bary;
        }
      }
      continue;
    }
    // Nearer child last, so that it is searched first.
    const int a = nd.first, b = nd.first + 1;
    const double da = box_distance2(nodes_[a].lo, nodes_[a].hi, p),
                 db = box_distance2(nodes_[b].lo, nodes_[b].hi, p);
    if (da < db) {
      stack[top++] = b;
      stack[top++] = a;
    } else {
      stack[top++] = a;
      stack[top++] = b;
    }
  }
  if (best.triangle < 0) return best;
  const Vec3 pn = normals_.pseudo_normal(best.triangle, best_bary);
  const Vec3 r = p - best.point;
  const double d = std::sqrt(best2);
  const double s = r.dot(pn) < 0 ? -1.0 : 1.0;
  best.distance = s * d;
  best.normal = d > 1e-12 ? Vec3(s * r / d) : pn;
  return best;
}

}  // namespace vgd::sim
