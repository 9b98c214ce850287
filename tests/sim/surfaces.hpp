#pragma once
// Closed colliders built inside the collision tests: a UV sphere, a box and a rod,
// counter-clockwise seen from outside (vgd::mesh::SurfaceMesh).
#include <cmath>

#include "vgd/mesh/surface.hpp"
#include "vgd/sim/types.hpp"

namespace vgd::sim::test {

// Orients every triangle of a convex mesh outward (its normal away from `inside`).
inline void orient_outward(mesh::SurfaceMesh& m, const Vec3& inside) {
  for (auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - inside) < 0) std::swap(t[1], t[2]);
  }
}

// A UV sphere of `rings` latitude bands and `segments` meridians:
// 2·segments·(rings − 1) triangles (64 × 40: 4 992, the benchmark's sphere).
inline mesh::SurfaceMesh uv_sphere(double radius, int segments = 64, int rings = 40, const Vec3& centre = Vec3::Zero()) {
  mesh::SurfaceMesh m;
  m.vertices.push_back(centre + Vec3(0, radius, 0));
  for (int j = 1; j < rings; ++j) {
    const double th = M_PI * j / rings;
    for (int i = 0; i < segments; ++i) {
      const double ph = 2 * M_PI * i / segments;
      m.vertices.push_back(centre + radius * Vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)));
    }
  }
  m.vertices.push_back(centre - Vec3(0, radius, 0));
  const int south = static_cast<int>(m.vertices.size()) - 1;
  auto ring = [&](int j, int i) { return 1 + (j - 1) * segments + (i % segments); };
  for (int i = 0; i < segments; ++i) {
    m.triangles.push_back({0, ring(1, i), ring(1, i + 1)});
    for (int j = 1; j < rings - 1; ++j) {
      m.triangles.push_back({ring(j, i), ring(j + 1, i), ring(j + 1, i + 1)});
      m.triangles.push_back({ring(j, i), ring(j + 1, i + 1), ring(j, i + 1)});
    }
    m.triangles.push_back({ring(rings - 1, i), south, ring(rings - 1, i + 1)});
  }
  orient_outward(m, centre);
  return m;
}

// The box [-h, h] (half extents h), rotated by `rotation`, then moved to `centre`.
inline mesh::SurfaceMesh box(const Vec3& h, const Mat3& rotation = Mat3::Identity(), const Vec3& centre = Vec3::Zero()) {
  mesh::SurfaceMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back(centre + rotation * Vec3((k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(), (k & 4 ? 1 : -1) * h.z()));
  const int quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  orient_outward(m, centre);
  return m;
}

// A closed rod along x (a capped cylinder of `segments` sides), `length` long,
// centred on `centre`, its side cut every `ring` metres along its length.
inline mesh::SurfaceMesh rod(double radius, double length, int segments = 16, double ring = 0.01,
                             const Vec3& centre = Vec3::Zero()) {
  mesh::SurfaceMesh m;
  const int rings = std::max(1, static_cast<int>(std::ceil(length / ring)));
  for (int i = 0; i <= rings; ++i)
    for (int k = 0; k < segments; ++k) {
      const double a = 2.0 * M_PI * k / segments;
      m.vertices.push_back(centre + Vec3(-0.5 * length + length * i / rings, radius * std::cos(a), radius * std::sin(a)));
    }
  for (int i = 0; i < rings; ++i)
    for (int k = 0; k < segments; ++k) {
      const int a = i * segments + k, b = i * segments + (k + 1) % segments;
      m.triangles.push_back({a, b, b + segments});
      m.triangles.push_back({a, b + segments, a + segments});
    }
  for (int end = 0; end <= 1; ++end) {
    const int c = static_cast<int>(m.vertices.size());
    m.vertices.push_back(centre + Vec3(end ? 0.5 * length : -0.5 * length, 0, 0));
    const int base = end * rings * segments;
    for (int k = 0; k < segments; ++k) m.triangles.push_back({c, base + k, base + (k + 1) % segments});
  }
  orient_outward(m, centre);
  return m;
}

}  // namespace vgd::sim::test
