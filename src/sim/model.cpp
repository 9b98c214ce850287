#include "vgd/sim/model.hpp"

#include <cmath>

namespace vgd::sim {

VecX lump_masses(const std::vector<Vec2>& uv, const std::vector<std::array<int, 3>>& triangles,
                 double density_kg_per_m2) {
  VecX m = VecX::Zero(static_cast<Eigen::Index>(uv.size()));
  for (const auto& t : triangles) {
    const Vec2 a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
    const double area = 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    for (int k = 0; k < 3; ++k) m[t[k]] += density_kg_per_m2 * area / 3.0;
  }
  return m;
}

Model make_grid(int nu, int nv, double du, double dv, const Vec3& origin, const Vec3& axis_u, const Vec3& axis_v,
                double particle_mass) {
  Model m;
  const int n = nu * nv;
  m.x0.resize(3 * n);
  m.v0 = VecX::Zero(3 * n);
  m.mass = VecX::Constant(n, particle_mass);
  m.uv.resize(n);
  const Vec3 eu = axis_u.normalized(), ev = axis_v.normalized();
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int k = j * nu + i;
      m.uv[k] = Vec2(i * du, j * dv);
      at(m.x0, k) = origin + i * du * eu + j * dv * ev;
    }
  // Two triangles per cell, alternating the diagonal so the grid has no bias.
  for (int j = 0; j + 1 < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i) {
      const int a = j * nu + i, b = a + 1, c = a + nu, d = c + 1;
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({a, d, c});
      } else {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({b, d, c});
      }
    }
  m.triangle_piece.assign(m.triangles.size(), 0);
  m.pieces = {"grid"};
  return m;
}

void validate(const Model& m) {
  const int n = m.num_particles();
  auto fail = [](const std::string& what) { throw SimulationError("invalid model: " + what); };
  if (n == 0) fail("no particles");
  if (m.x0.size() != 3 * n || m.v0.size() != 3 * n) fail("positions or velocities do not have 3 values per particle");
  if (static_cast<int>(m.uv.size()) != n) fail("material coordinates do not match the particle count");
  for (int i = 0; i < n; ++i) {
    if (!(m.mass[i] > 0.0) || !std::isfinite(m.mass[i]))
      fail("particle " + std::to_string(i) + " has mass " + std::to_string(m.mass[i]) + " kg (must be > 0)");
    if (!at(m.x0, i).allFinite() || !at(m.v0, i).allFinite() || !m.uv[i].allFinite())
      fail("particle " + std::to_string(i) + " has a non-finite position, velocity or material coordinate");
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k : m.triangles[t])
      if (k < 0 || k >= n) fail("triangle " + std::to_string(t) + " names particle " + std::to_string(k));
  if (!m.triangle_piece.empty() && m.triangle_piece.size() != m.triangles.size())
    fail("triangle_piece does not match the triangle count");
}

}  // namespace vgd::sim
