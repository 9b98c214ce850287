#pragma once
// Tiny models and effects built inside the tests (style guide: build tiny
// scenes inside the test).
#include <cstdio>
#include <functional>
#include <string>

#include "vgd/sim/effect.hpp"
#include "vgd/sim/model.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/integrator.hpp"
#include "vgd/sim/system.hpp"

namespace vgd::sim::test {

// n particles of mass m in a row along x, spacing d (m), no triangles.
inline Model particles(int n, double m = 1.0, double d = 1.0) {
  Model model;
  model.x0 = VecX::Zero(3 * n);
  model.v0 = VecX::Zero(3 * n);
  model.mass = VecX::Constant(n, m);
  model.uv.assign(n, Vec2::Zero());
  for (int i = 0; i < n; ++i) model.x0[3 * i] = i * d;
  return model;
}

// Each particle tied to its start by a linear spring of stiffness k (N/m):
// an undamped harmonic oscillator per particle, ω = sqrt(k/m).
class Anchor final : public Effect {
 public:
  Anchor(const Model& m, double k) : k_(k), x0_(m.x0) {}
  const char* name() const override { return "anchor"; }
  void add_forces(const Eval& e, VecX& f) override { f -= k_ * (e.x - x0_); }
  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets&) override {
    for (int i = 0; i < e.model.num_particles(); ++i) add_block(dfdx, i, i, -k_ * Mat3::Identity());
    return true;
  }
  double energy(const Eval& e) const override { return 0.5 * k_ * (e.x - x0_).squaredNorm(); }
  void add_stiffness_bound(const Model&, VecX& k, VecX&) const override { k.array() += k_; }

 private:
  double k_;
  VecX x0_;
};

// Counts its evaluations and applies a force given by a function.
class Probe final : public Effect {
 public:
  std::function<void(const Eval&, VecX&)> force;
  int calls = 0;
  const char* name() const override { return "probe"; }
  void add_forces(const Eval& e, VecX& f) override {
    ++calls;
    if (force) force(e, f);
  }
};

// Forces (N) of one effect at (x, v, t).
inline VecX forces(Effect& e, const Model& m, const VecX& x, const VecX& v, double t = 0.0) {
  VecX f = VecX::Zero(m.num_dofs());
  e.add_forces({m, t, x, v}, f);
  return f;
}
inline VecX forces(Effect& e, const Model& m, const VecX& x) { return forces(e, m, x, m.v0); }

// `steps` steps of h seconds from the model's start with the default
// integrator, calling after(k, state) after step k (1-based); stops early
// when it returns false.
template <class After>
void step_through(System& sys, double h, int steps, After&& after) {
  IntegratorSettings st;
  st.step = h;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  for (int k = 1; k <= steps; ++k) {
    integ->advance(sys, s, k * h);
    if (!after(k, s)) return;
  }
}

// A figure for the test report (--gtest_output=xml).
inline std::string sci(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3e", v);
  return b;
}

template <class... E>
std::vector<std::unique_ptr<Effect>> effects(std::unique_ptr<E>... e) {
  std::vector<std::unique_ptr<Effect>> v;
  (v.push_back(std::move(e)), ...);
  return v;
}

// Two nu × nv grids of 0.1 m cells side by side, `gap` (m) apart along x, as
// one model of two pieces (A, B); particle masses mass_a and mass_b (kg).
// The seams tests sew A's right column to B's left one.
inline Model two_grids(int nu, int nv, double gap, double mass_a = 0.01, double mass_b = 0.01) {
  const double d = 0.1;
  Model a = make_grid(nu, nv, d, d, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), mass_a);
  Model b = make_grid(nu, nv, d, d, Vec3((nu - 1) * d + gap, 0, 0), Vec3::UnitX(), Vec3::UnitY(), mass_b);
  const int na = a.num_particles(), nb = b.num_particles();
  Model m = a;
  m.x0.conservativeResize(3 * (na + nb));
  m.x0.tail(3 * nb) = b.x0;
  m.v0 = VecX::Zero(3 * (na + nb));
  m.mass.conservativeResize(na + nb);
  m.mass.tail(nb) = b.mass;
  for (auto uv : b.uv) m.uv.push_back(uv + Vec2((nu - 1) * d, 0));
  for (auto t : b.triangles) m.triangles.push_back({t[0] + na, t[1] + na, t[2] + na});
  m.triangle_piece.assign(m.triangles.size(), 0);
  for (std::size_t t = a.triangles.size(); t < m.triangles.size(); ++t) m.triangle_piece[t] = 1;
  m.pieces = {"A", "B"};
  return m;
}

// A soft mass-spring cloth (N/m per spring): cheap stable steps for tests
// whose subject is not the cloth.
inline MassSpringMaterial soft_cloth() {
  MassSpringMaterial mat;
  mat.warp = mat.weft = 50.0;
  mat.shear = mat.bend_warp = mat.bend_weft = 10.0;
  mat.damping = 0.01;
  return mat;
}

// n × n cloths at a 3 cm spacing, 2 g particles, `layers` of them 1 cm apart,
// the lowest at height y, centred over the origin.
inline Model sheets(int n, double y, int layers) {
  constexpr double d = 0.03;
  const Vec3 corner(-0.5 * d * (n - 1), y, -0.5 * d * (n - 1));
  Model m = make_grid(n, n, d, d, corner, Vec3::UnitX(), Vec3::UnitZ(), 0.002);
  m.triangle_piece.assign(m.triangles.size(), 0);
  m.pieces = {"A"};
  for (int l = 1; l < layers; ++l) {
    const Model b = make_grid(n, n, d, d, corner + Vec3(0, 0.01 * l, 0), Vec3::UnitX(), Vec3::UnitZ(), 0.002);
    const int na = m.num_particles(), nb = b.num_particles();
    m.x0.conservativeResize(3 * (na + nb));
    m.x0.tail(3 * nb) = b.x0;
    m.mass.conservativeResize(na + nb);
    m.mass.tail(nb) = b.mass;
    m.uv.insert(m.uv.end(), b.uv.begin(), b.uv.end());
    for (auto t : b.triangles) {
      m.triangles.push_back({t[0] + na, t[1] + na, t[2] + na});
      m.triangle_piece.push_back(l);
    }
    m.pieces.push_back(std::string(1, static_cast<char>('A' + l)));
  }
  m.v0 = VecX::Zero(m.x0.size());
  return m;
}

}  // namespace vgd::sim::test
