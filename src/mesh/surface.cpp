// Plain-C++ helpers on closed 3-D surfaces (surface.hpp).
#include "vgd/mesh/surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

namespace vgd::mesh {

namespace {

bool valid_triangle(const SurfaceMesh& m, const std::array<int, 3>& t) {
  for (int v : t)
    if (v < 0 || v >= m.num_vertices()) return false;
  return true;
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

}  // namespace

Box3 bounding_box(const SurfaceMesh& m) {
  Box3 b;
  for (const auto& v : m.vertices) b.extend(v);
  return b;
}

double surface_area(const SurfaceMesh& m) {
  double a = 0.0;
  for (const auto& t : m.triangles)
    if (valid_triangle(m, t))
      a += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
  return a;
}

double signed_volume(const SurfaceMesh& m) {
  // Sum of signed tetrahedra (origin, triangle); origin-independent for a closed mesh.
  double v = 0.0;
  for (const auto& t : m.triangles)
    if (valid_triangle(m, t)) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]]));
  return v / 6.0;
}

SurfaceCheck check_surface(const SurfaceMesh& m, double degenerate_area) {
  SurfaceCheck c;
  c.vertices = m.num_vertices();
  c.triangles = m.num_triangles();
  // Per undirected edge: how many triangles use it, and the net direction
  // (+1 for a -> b with a < b, -1 for b -> a). Two triangles sharing an edge
  // consistently traverse it in opposite directions (net 0).
  struct Use {
    int count = 0, net = 0;
  };
  std::unordered_map<std::uint64_t, Use> edges;
  edges.reserve(m.triangles.size() * 2);
  std::vector<char> used(m.vertices.size(), 0);
  for (const auto& t : m.triangles) {
    if (!valid_triangle(m, t)) {
      ++c.invalid_indices;
      continue;
    }
    const Vec3 &p0 = m.vertices[t[0]], &p1 = m.vertices[t[1]], &p2 = m.vertices[t[2]];
    const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || area <= degenerate_area) ++c.degenerate_triangles;
    c.area += area;
    c.volume += p0.dot(p1.cross(p2)) / 6.0;
    for (int k = 0; k < 3; ++k) {
      used[t[k]] = 1;
      const int a = t[k], b = t[(k + 1) % 3];
      if (a == b) continue;
      auto& u = edges[edge_key(a, b)];
      ++u.count;
      u.net += a < b ? 1 : -1;
    }
  }
  c.unused_vertices = static_cast<int>(std::count(used.begin(), used.end(), 0));
  c.edges = static_cast<int>(edges.size());
  double sum = 0.0;
  c.min_edge = edges.empty() ? 0.0 : 1e300;
  for (const auto& [key, u] : edges) {
    if (u.count == 1) ++c.boundary_edges;
    else if (u.count > 2) ++c.non_manifold_edges;
    else if (u.net != 0) ++c.inconsistent_edges;
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    const double len = (m.vertices[a] - m.vertices[b]).norm();
    c.min_edge = std::min(c.min_edge, len);
    c.max_edge = std::max(c.max_edge, len);
    sum += len;
  }
  c.mean_edge = edges.empty() ? 0.0 : sum / static_cast<double>(edges.size());
  return c;
}

std::vector<Vec3> vertex_normals(const SurfaceMesh& m) {
  std::vector<Vec3> n(m.vertices.size(), Vec3::Zero());
  for (const auto& t : m.triangles) {
    if (!valid_triangle(m, t)) continue;
    // The cross product's length is twice the area: area weighting for free.
    const Vec3 f = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    for (int v : t) n[v] += f;
  }
  for (auto& v : n)
    if (const double len = v.norm(); len > 0) v /= len;
  return n;
}

void transform(SurfaceMesh& m, const Eigen::Matrix3d& linear, const Vec3& translation) {
  for (auto& v : m.vertices) v = linear * v + translation;
  if (linear.determinant() < 0)
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
}

int remove_unused_vertices(SurfaceMesh& m) {
  std::vector<int> map(m.vertices.size(), -1);
  for (const auto& t : m.triangles)
    for (int v : t)
      if (v >= 0 && v < m.num_vertices()) map[v] = 0;
  std::vector<Vec3> kept;
  kept.reserve(m.vertices.size());
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map[i] == 0) {
      map[i] = static_cast<int>(kept.size());
      kept.push_back(m.vertices[i]);
    }
  const int removed = m.num_vertices() - static_cast<int>(kept.size());
  for (auto& t : m.triangles)
    for (int& v : t) v = (v >= 0 && v < static_cast<int>(map.size())) ? map[v] : v;
  m.vertices = std::move(kept);
  return removed;
}

int weld_vertices(SurfaceMesh& m, double tolerance) {
  const int before = m.num_vertices();
  // Hash grid of cell `tolerance`: a vertex's match is in its cell or a neighbour.
  const double cell = tolerance > 0 ? tolerance : 1e-12;
  struct Key {
    std::int64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return static_cast<std::size_t>(k.x * 73856093LL ^ k.y * 19349663LL ^ k.z * 83492791LL);
    }
  };
  std::unordered_map<Key, std::vector<int>, Hash> grid;
  grid.reserve(m.vertices.size());
  std::vector<int> rep(m.vertices.size());
  std::vector<Vec3> kept;
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3& p = m.vertices[i];
    const Key k{static_cast<std::int64_t>(std::floor(p.x() / cell)), static_cast<std::int64_t>(std::floor(p.y() / cell)),
                static_cast<std::int64_t>(std::floor(p.z() / cell))};
    int found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          const auto it = grid.find({k.x + dx, k.y + dy, k.z + dz});
          if (it == grid.end()) continue;
          for (int j : it->second)
            if ((kept[j] - p).norm() <= tolerance) {
              found = j;
              break;
            }
        }
    if (found < 0) {
      found = static_cast<int>(kept.size());
      kept.push_back(p);
      grid[k].push_back(found);
    }
    rep[i] = found;
  }
  std::vector<std::array<int, 3>> tris;
  tris.reserve(m.triangles.size());
  for (auto t : m.triangles) {
    if (!valid_triangle(m, t)) continue;
    for (int& v : t) v = rep[v];
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) tris.push_back(t);
  }
  m.vertices = std::move(kept);
  m.triangles = std::move(tris);
  remove_unused_vertices(m);
  return before - m.num_vertices();
}

std::vector<std::vector<Vec2d>> slice_horizontal(const SurfaceMesh& m, double height) {
  // Each triangle crossing the plane gives one segment between two of its edges;
  // segments are chained through the (undirected) mesh edges they start and end on.
  // A vertex exactly on the plane counts as above, so every crossing is on an edge's interior.
  auto above = [&](int v) { return m.vertices[v].y() >= height; };
  auto cut = [&](int a, int b) {
    const Vec3 &p = m.vertices[a], &q = m.vertices[b];
    const double t = (height - p.y()) / (q.y() - p.y());
    return Vec2d(p.x() + t * (q.x() - p.x()), p.z() + t * (q.z() - p.z()));
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint64_t>> next;  // edge -> the edges it is chained to
  std::map<std::uint64_t, Vec2d> point;
  for (const auto& t : m.triangles) {
    if (!valid_triangle(m, t)) continue;
    std::uint64_t e[2];
    int n = 0;
    for (int k = 0; k < 3 && n < 2; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (above(a) != above(b)) {
        e[n++] = edge_key(a, b);
        point.emplace(edge_key(a, b), cut(a, b));
      }
    }
    if (n != 2) continue;
    next[e[0]].push_back(e[1]);
    next[e[1]].push_back(e[0]);
  }
  std::vector<std::vector<Vec2d>> loops;
  std::unordered_map<std::uint64_t, bool> seen;
  for (const auto& [key, p] : point) {  // std::map: deterministic order
    if (seen[key]) continue;
    // Walk from this edge one way; prepend the other way when the chain is open.
    std::vector<std::uint64_t> chain{key};
    seen[key] = true;
    for (int dir = 0; dir < 2; ++dir) {
      std::uint64_t cur = key;
      for (;;) {
        std::uint64_t nxt = 0;
        bool ok = false;
        for (const auto e : next[cur])
          if (!seen[e]) {
            nxt = e, ok = true;
            break;
          }
        if (!ok) break;
        seen[nxt] = true;
        if (dir == 0) chain.push_back(nxt);
        else chain.insert(chain.begin(), nxt);
        cur = nxt;
      }
    }
    std::vector<Vec2d> loop;
    loop.reserve(chain.size());
    for (auto e : chain) loop.push_back(point[e]);
    loops.push_back(std::move(loop));
  }
  return loops;
}

std::vector<Vec2d> convex_hull(std::vector<Vec2d> p) {
  // Andrew's monotone chain.
  std::sort(p.begin(), p.end(), [](const Vec2d& a, const Vec2d& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  auto cross = [](const Vec2d& o, const Vec2d& a, const Vec2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec2d> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

double loop_area(const std::vector<Vec2d>& l) {
  double a = 0;
  for (std::size_t i = 0, j = l.size() - 1; i < l.size(); j = i++) a += l[j].x() * l[i].y() - l[i].x() * l[j].y();
  return std::abs(0.5 * a);
}

double convex_hull_perimeter(const std::vector<Vec2d>& points) {
  const auto h = convex_hull(points);
  if (h.size() < 2) return 0.0;
  double len = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) len += (h[(i + 1) % h.size()] - h[i]).norm();
  return len;
}

bool point_in_polygon(const std::vector<Vec2d>& poly, const Vec2d& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2d &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

}  // namespace vgd::mesh
