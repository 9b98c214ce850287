#pragma once
// The environment's effects (seed 000 §4.1.2) and the seed's constrictions.
// Each is its own unit; a scene creates only those it lists.
#include <memory>
#include <vector>

#include "vgd/sim/effect.hpp"

namespace vgd::sim {

// f = m g.
struct GravityDef {
  Vec3 g{0.0, -9.81, 0.0};  // m/s², +Y up (vgd's world frame)
};
std::unique_ptr<Effect> make_gravity(const GravityDef& def);

// Air viscosity, f = -k_v v per particle (seed 000), plus an optional
// mass-proportional part -α m v that does not depend on mesh resolution.
struct ViscosityDef {
  double k = 0.0;      // N·s/m per particle (the seed's viscosity_const, e.g. 0.2 for its flag)
  double alpha = 0.0;  // 1/s, mass-proportional drag rate
};
std::unique_ptr<Effect> make_viscosity(const ViscosityDef& def);

// Material damping: a dashpot along every mesh edge, f_i = -c ((v_i - v_j)·d) d
// with d the unit edge direction; damps stretching, not rigid motion.
struct DampingDef {
  double c = 0.0;  // N·s/m per edge
};
std::unique_ptr<Effect> make_damping(const Model& model, const DampingDef& def);

// Pins (the seed's constrictions: a flag on its staff, a garment on a hanger):
// the listed particles move with a prescribed velocity from where they start.
struct PinDef {
  std::vector<int> particles;
  Vec3 velocity = Vec3::Zero();  // m/s; non-zero for a moving pin (a yanked hanger)
};
std::unique_ptr<Effect> make_pins(const Model& model, const PinDef& def);

// Wind on the cloth's faces, proportional to the wind's component along each
// face normal (seed 000): f_face = c · A · ((w - v_face)·n) n, shared by the
// face's three particles. Turbulence modulates the wind smoothly in time and
// along the wind (deterministic: the same seed gives the same gusts).
struct WindDef {
  Vec3 velocity = Vec3::Zero();  // m/s, mean wind
  double coefficient = 1.0;      // N·s/m³ (force per area per relative normal speed); ~ air density × drag
  double turbulence = 0.0;       // relative gust amplitude (0: steady, 0.3: gusty, 1: very gusty)
  double gust_frequency = 1.0;   // Hz, typical gust rate
  unsigned seed = 1;
};
std::unique_ptr<Effect> make_wind(const WindDef& def);
// The wind velocity (m/s) the effect applies at time t and position p.
Vec3 wind_at(const WindDef& def, double t, const Vec3& p);

// Every undirected edge of the triangles, each once, smaller index first.
std::vector<std::array<int, 2>> mesh_edges(const std::vector<std::array<int, 3>>& triangles);

// A speed limit (m/s): after each step no particle moves faster, and none has
// moved farther than max_speed × h in it (the position is pulled back along
// its motion). Not a physical force: drapes use it while seams pull pieces
// together (a 1 N seam on a 40 mg particle reaches tens of m/s), so contact
// and self-collision tests, which grow with each particle's motion over a
// step, stay local. The scene switches it on.
struct SpeedLimitDef {
  double max_speed = 1.0;  // m/s
};
std::unique_ptr<Effect> make_speed_limit(const Model& model, const SpeedLimitDef& def);

}  // namespace vgd::sim
