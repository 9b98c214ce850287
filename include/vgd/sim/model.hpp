#pragma once
// The compiled cloth model: everything about the cloth that does not change
// while it moves (MuJoCo's mjModel). Built once by the scene stage from meshed
// pieces (or the seed's grid), read-only for the engine. The moving part is
// sim::State.
#include <array>
#include <string>
#include <vector>

#include "vgd/sim/types.hpp"

namespace vgd::sim {

struct Model {
  // ---- particles ----
  VecX x0;    // 3N initial positions (m)
  VecX v0;    // 3N initial velocities (m/s)
  VecX mass;  // N lumped masses (kg), all > 0

  // ---- cloth surface ----
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise in material space
  // Material (rest) coordinates of each particle, m: u along the warp (grain
  // line), v along the weft. The rest shape of every force model.
  std::vector<Vec2> uv;
  std::vector<int> triangle_piece;   // piece index of each triangle
  std::vector<std::string> pieces;   // piece names

  int num_particles() const { return static_cast<int>(mass.size()); }
  int num_dofs() const { return 3 * num_particles(); }
};

// Lumped masses: each triangle's area (from uv, m²) × density (kg/m²) shared
// equally by its three corners. Particles of no triangle get 0.
VecX lump_masses(const std::vector<Vec2>& uv, const std::vector<std::array<int, 3>>& triangles,
                 double density_kg_per_m2);

// A regular nu × nv grid of particles (the seed's flag): spacing du along the
// warp (u), dv along the weft (v), placed in 3-D as origin + u·axis_u + v·axis_v,
// split into two triangles per cell, each particle of mass `particle_mass` (kg).
// Particle (i, j) has index j * nu + i.
Model make_grid(int nu, int nv, double du, double dv, const Vec3& origin, const Vec3& axis_u, const Vec3& axis_v,
                double particle_mass);

// Checks the model's invariants (sizes agree, masses positive and finite,
// triangles index existing particles, uv finite); throws SimulationError naming
// the first problem.
void validate(const Model& m);

// The moving part (MuJoCo's mjData): time, positions, velocities.
struct State {
  double t = 0.0;  // s
  VecX x;          // 3N positions (m)
  VecX v;          // 3N velocities (m/s)
};

inline State initial_state(const Model& m) { return {0.0, m.x0, m.v0}; }

}  // namespace vgd::sim
