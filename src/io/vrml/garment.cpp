// The garment as the exporters see it: checks, the output mesh (welded or
// not), normals, and the seed's creaseAngle rule.
#include "vgd/io/vrml/garment.hpp"

#include <algorithm>
#include <cmath>

#include "vgd/core/diagnostics.hpp"

namespace vgd::io::vrml {

namespace {

double distance2(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

const PieceLook& Garment::look(int piece) const {
  static const PieceLook fallback{};
  return piece >= 0 && piece < static_cast<int>(looks.size()) ? looks[piece] : fallback;
}

void Garment::validate() const {
  auto fail = [&](const std::string& msg) { throw Error(name, "", msg); };
  const int n = cloth.num_particles();
  if (n == 0) fail("the garment has no particles (no material coordinates)");
  if (frames.positions.empty()) fail("the garment has no frames");
  if (frames.times.size() != frames.positions.size())
    fail(std::to_string(frames.times.size()) + " frame times for " + std::to_string(frames.positions.size()) +
         " frames");
  for (std::size_t f = 0; f < frames.positions.size(); ++f)
    if (frames.positions[f].size() != static_cast<std::size_t>(3 * n))
      fail("frame " + std::to_string(f) + " has " + std::to_string(frames.positions[f].size()) +
           " coordinates, expected 3 × " + std::to_string(n));
  if (!cloth.triangle_piece.empty() && cloth.triangle_piece.size() != cloth.triangles.size())
    fail("triangle_piece has " + std::to_string(cloth.triangle_piece.size()) + " entries for " +
         std::to_string(cloth.triangles.size()) + " triangles");
  for (std::size_t t = 0; t < cloth.triangles.size(); ++t) {
    for (int k : cloth.triangles[t])
      if (k < 0 || k >= n) fail("triangle " + std::to_string(t) + " names particle " + std::to_string(k) +
                                " of " + std::to_string(n));
    const int p = cloth.piece_of(t);
    if (p < 0 || p >= cloth.num_pieces())
      fail("triangle " + std::to_string(t) + " is in piece " + std::to_string(p) + " of " +
           std::to_string(cloth.num_pieces()));
  }
  if (!cloth.representative.empty()) {
    if (cloth.representative.size() != static_cast<std::size_t>(n))
      fail("the merge map has " + std::to_string(cloth.representative.size()) + " entries for " +
           std::to_string(n) + " particles");
    for (int r : cloth.representative)
      if (r < 0 || r >= n) fail("a merge names particle " + std::to_string(r) + " of " + std::to_string(n));
  }
  if (body) {
    const int nb = static_cast<int>(body->vertices.size());
    for (const auto& t : body->triangles)
      for (int k : t)
        if (k < 0 || k >= nb) fail("the body's triangle names vertex " + std::to_string(k) + " of " +
                                   std::to_string(nb));
  }
}

int OutputMesh::face_count() const {
  int n = 0;
  for (const auto& p : pieces) n += static_cast<int>(p.coord.size());
  return n;
}

OutputMesh output_mesh(const Cloth& cloth, bool welded) {
  const int n = cloth.num_particles();
  OutputMesh m;
  m.particle_vertex.assign(n, -1);
  // Vertices: one per particle, or one per merged group (its representative).
  const bool weld = welded && cloth.representative.size() == static_cast<std::size_t>(n);
  for (int i = 0; i < n; ++i) {
    const int r = weld ? cloth.representative[i] : i;
    if (m.particle_vertex[r] < 0) {
      m.particle_vertex[r] = static_cast<int>(m.vertex_particle.size());
      m.vertex_particle.push_back(r);
    }
    m.particle_vertex[i] = m.particle_vertex[r];
  }
  // Faces per piece; collapsed ones (two corners merged) dropped.
  m.pieces.resize(cloth.num_pieces());
  for (std::size_t t = 0; t < cloth.triangles.size(); ++t) {
    const auto& tri = cloth.triangles[t];
    const std::array<int, 3> c{m.particle_vertex[tri[0]], m.particle_vertex[tri[1]], m.particle_vertex[tri[2]]};
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    auto& p = m.pieces[cloth.piece_of(t)];
    p.coord.push_back(c);
    p.tex.push_back(tri);
  }
  return m;
}

std::vector<std::array<double, 3>> vertex_normals(const OutputMesh& mesh, const std::vector<float>& x) {
  std::vector<std::array<double, 3>> nrm(mesh.vertex_particle.size(), {0.0, 0.0, 0.0});
  auto pos = [&](int v, int k) { return static_cast<double>(x[3 * static_cast<std::size_t>(mesh.vertex_particle[v]) + k]); };
  // Σ of unnormalised face normals (twice the area along the normal) at each corner.
  for (const auto& piece : mesh.pieces)
    for (const auto& f : piece.coord) {
      const double ax = pos(f[1], 0) - pos(f[0], 0), ay = pos(f[1], 1) - pos(f[0], 1), az = pos(f[1], 2) - pos(f[0], 2);
      const double bx = pos(f[2], 0) - pos(f[0], 0), by = pos(f[2], 1) - pos(f[0], 1), bz = pos(f[2], 2) - pos(f[0], 2);
      const std::array<double, 3> c{ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx};
      for (int v : f)
        for (int k = 0; k < 3; ++k) nrm[v][k] += c[k];
    }
  for (auto& v : nrm) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v = l > 0 ? std::array<double, 3>{v[0] / l, v[1] / l, v[2] / l} : std::array<double, 3>{0.0, 1.0, 0.0};
  }
  return nrm;
}

double median_edge_length(const Cloth& cloth) {
  std::vector<double> e;
  e.reserve(cloth.triangles.size() * 3);
  for (const auto& t : cloth.triangles)
    for (int k = 0; k < 3; ++k) e.push_back(distance2(cloth.uv[t[k]], cloth.uv[t[(k + 1) % 3]]));
  return median(std::move(e));
}

double median_edge_length(const Body& body) {
  std::vector<double> e;
  e.reserve(body.triangles.size() * 3);
  for (const auto& t : body.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto& a = body.vertices[t[k]];
      const auto& b = body.vertices[t[(k + 1) % 3]];
      e.push_back(std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
    }
  return median(std::move(e));
}

double crease_angle(double median_edge_m) {
  if (!(median_edge_m > 0)) return 0.5;
  return std::clamp(median_edge_m / kCreaseRadius, 0.5, 3.14);
}

}  // namespace vgd::io::vrml
