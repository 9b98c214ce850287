#include "vgd/mesh/primitives.hpp"

#include <cmath>
#include <numbers>

#include "vgd/core/diagnostics.hpp"

namespace vgd::mesh {

SurfaceMesh uv_sphere(const Vec3& c, double r, int segments, int rings) {
  if (segments < 3 || rings < 2 || !(r > 0)) throw Error("", "uv_sphere", "needs segments >= 3, rings >= 2, radius > 0");
  SurfaceMesh m;
  const double pi = std::numbers::pi;
  m.vertices.push_back(c + Vec3(0, r, 0));  // north pole: 0
  for (int i = 1; i < rings; ++i) {
    const double th = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * pi * j / segments;
      m.vertices.push_back(c + r * Vec3(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph)));
    }
  }
  m.vertices.push_back(c + Vec3(0, -r, 0));  // south pole
  const int south = m.num_vertices() - 1;
  const auto ring = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      m.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.triangles.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
  return m;
}

SurfaceMesh cylinder(const Vec3& base, double r, double h, int segments, int stacks) {
  if (segments < 3 || stacks < 1 || !(r > 0) || !(h > 0))
    throw Error("", "cylinder", "needs segments >= 3, stacks >= 1, radius > 0, height > 0");
  SurfaceMesh m;
  const double pi = std::numbers::pi;
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * pi * j / segments;
      m.vertices.push_back(base + Vec3(r * std::cos(ph), h * i / stacks, -r * std::sin(ph)));
    }
  const int bottom = m.num_vertices(), top = bottom + 1;
  m.vertices.push_back(base);
  m.vertices.push_back(base + Vec3(0, h, 0));
  const auto at = [&](int i, int j) { return i * segments + (j % segments); };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < segments; ++j) {
      m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({bottom, at(0, j + 1), at(0, j)});
    m.triangles.push_back({top, at(stacks, j), at(stacks, j + 1)});
  }
  return m;
}

SurfaceMesh box(const Vec3& lo, const Vec3& hi) {
  SurfaceMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back(Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()));
  // Two triangles per face, outward normals.
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

}  // namespace vgd::mesh
