// The implicit integrators: Baraff–Witkin implicit Euler (implicit_euler.cpp)
// and adaptive BDF on SUNDIALS CVODE (cvode.cpp). Orders, energy behaviour,
// tolerance control, stiff scenes explicit methods refuse, prescribed motion,
// failures that never hand out NaN, the linear and nonlinear solves.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/integrator.hpp"
#include "vgd/sim/run.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

// Linear springs between particle pairs, f_i = -k (l - L) d̂ (d = x_i - x_j,
// l = |d|), with the exact Jacobian including the geometric term:
//   ∂f_i/∂x_i = -k [d̂d̂ᵀ + (1 - L/l)(I - d̂d̂ᵀ)] = -∂f_i/∂x_j.
class Springs final : public Effect {
 public:
  Springs(std::vector<std::array<int, 2>> pairs, double k, double rest) : pairs_(std::move(pairs)), k_(k), rest_(rest) {}
  const char* name() const override { return "springs"; }
  void add_forces(const Eval& e, VecX& f) override {
    for (const auto& [i, j] : pairs_) {
      const Vec3 d = at(e.x, i) - at(e.x, j);
      const double l = d.norm();
      const Vec3 fi = -k_ * (l - rest_) * d / l;
      at(f, i) += fi;
      at(f, j) -= fi;
    }
  }
  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets&) override {
    for (const auto& [i, j] : pairs_) {
      const Vec3 d = at(e.x, i) - at(e.x, j);
      const double l = d.norm();
      const Vec3 u = d / l;
      const Mat3 uu = u * u.transpose();
      const Mat3 b = -k_ * (uu + (1.0 - rest_ / l) * (Mat3::Identity() - uu));
      add_block(dfdx, i, i, b);
      add_block(dfdx, j, j, b);
      add_block(dfdx, i, j, -b);
      add_block(dfdx, j, i, -b);
    }
    return true;
  }
  double energy(const Eval& e) const override {
    double u = 0.0;
    for (const auto& [i, j] : pairs_) u += 0.5 * k_ * std::pow((at(e.x, i) - at(e.x, j)).norm() - rest_, 2);
    return u;
  }
  void add_stiffness_bound(const Model&, VecX& k, VecX&) const override {
    for (const auto& [i, j] : pairs_) k[i] += 2 * k_, k[j] += 2 * k_;
  }

 private:
  std::vector<std::array<int, 2>> pairs_;
  double k_, rest_;
};

// Zeroes every velocity once, after the first step that reaches t_stop.
class Stopper final : public Effect {
 public:
  explicit Stopper(double t_stop) : t_stop_(t_stop) {}
  const char* name() const override { return "stopper"; }
  void add_forces(const Eval&, VecX&) override {}
  bool add_jacobian(const Eval&, Triplets&, Triplets&) override { return true; }
  void after_step(const Model&, State& s) override {
    if (!done_ && s.t >= t_stop_) {
      s.v.setZero();
      done_ = true;
    }
  }

 private:
  double t_stop_;
  bool done_ = false;
};

// One particle on an anchor spring (k, m), displaced 0.1 m along x, released
// at rest: x(t) = 0.1 cos(ω t), ω = sqrt(k/m).
System oscillator(double k = 4.0, double m = 1.0) {
  Model model = particles(1, m);
  auto anchor = std::make_unique<Anchor>(model, k);
  model.x0[0] = 0.1;
  return System(model, effects(std::move(anchor)));
}

IntegratorSettings implicit_euler(double h) {
  IntegratorSettings st;
  st.method = Method::implicit_euler;
  st.step = h;
  return st;
}

IntegratorSettings bdf(double rtol, double atol, bool krylov = false) {
  IntegratorSettings st;
  st.method = Method::bdf;
  st.rtol = rtol;
  st.atol = atol;
  st.krylov = krylov;
  return st;
}

State advance(System& sys, const IntegratorSettings& st, double t_end, IntegratorStats* stats = nullptr) {
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  sys.apply_prescribed(s);
  integ->prepare(sys, s);
  integ->advance(sys, s, t_end);
  if (stats) *stats = integ->stats();
  return s;
}

double oscillator_error(const IntegratorSettings& st, double t_end = 2.0) {
  System sys = oscillator();
  const State s = advance(sys, st, t_end);
  return std::abs(s.x[0] - 0.1 * std::cos(2.0 * t_end));
}

double total_energy(System& sys, const State& s) {
  return sys.kinetic_energy(s.v) + sys.potential_energy(s.t, s.x, s.v);
}

// A chain of n particles of mass m hanging along -y from particle 0 (pinned,
// optionally moving), springs of stiffness k and rest length L between
// neighbours, gravity and mass-proportional air drag alpha (1/s). It starts
// unstretched and at rest.
struct ChainDef {
  int n = 5;
  double m = 0.01, k = 1.0e4, rest = 0.1, alpha = 50.0;
  Vec3 pin_velocity = Vec3::Zero();
};

System chain(const ChainDef& d) {
  Model model = particles(d.n, d.m);
  for (int i = 0; i < d.n; ++i) at(model.x0, i) = Vec3(0.0, -i * d.rest, 0.0);
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i + 1 < d.n; ++i) pairs.push_back({i, i + 1});
  auto pins = make_pins(model, {{0}, d.pin_velocity});
  return System(model, effects(make_gravity({}), make_viscosity({0.0, d.alpha}), std::move(pins),
                               std::make_unique<Springs>(pairs, d.k, d.rest)));
}

// The static equilibrium of the chain: spring j carries the weight of the n-1-j particles below it.
double chain_bottom_y(const ChainDef& d) {
  double y = 0.0;
  for (int j = 0; j + 1 < d.n; ++j) y -= d.rest + (d.n - 1 - j) * d.m * 9.81 / d.k;
  return y;
}

}  // namespace

// ---- implicit Euler on the oscillator -----------------------------------------

TEST(ImplicitEuler, IsFirstOrder) {
  const double e1 = oscillator_error(implicit_euler(0.02));
  const double e2 = oscillator_error(implicit_euler(0.01));
  const double e3 = oscillator_error(implicit_euler(0.005));
  std::printf("implicit Euler error at t = 2 s: %.3e (h 0.02), %.3e (0.01), %.3e (0.005); orders %.3f, %.3f\n", e1, e2,
              e3, std::log2(e1 / e2), std::log2(e2 / e3));
  EXPECT_NEAR(std::log2(e1 / e2), 1.0, 0.15);
  EXPECT_NEAR(std::log2(e2 / e3), 1.0, 0.1);
}

TEST(ImplicitEuler, DissipatesOscillatorEnergyMonotonicallyAtAnyStep) {
  // A-stable: |1/(1 - iωh)| < 1 for every h, so the energy never grows (ω = 2 rad/s: hω from 0.002 to 2000).
  for (double h : {1e-3, 1e-2, 0.1, 1.0, 10.0, 1000.0}) {
    System sys = oscillator();
    auto integ = make_integrator(implicit_euler(h));
    State s = initial_state(sys.model());
    integ->prepare(sys, s);
    const double e0 = total_energy(sys, s);
    double prev = e0;
    for (int k = 1; k <= 200; ++k) {
      integ->advance(sys, s, k * h);
      const double e = total_energy(sys, s);
      ASSERT_LE(e, prev) << "energy grew at step " << k << " with h = " << h;
      prev = e;
    }
    EXPECT_LT(prev, e0) << "h = " << h;
  }
}

TEST(ImplicitEuler, StiffAnchorDecaysWhereExplicitEulerWouldExplode) {
  // k = 1e6 N/m on 1 g: ω ≈ 31 600 rad/s, hω = 316 at h = 0.01 s.
  System sys = oscillator(1e6, 1e-3);
  IntegratorSettings euler;
  euler.step = 0.01;
  State s = initial_state(sys.model());
  EXPECT_THROW(make_integrator(euler)->prepare(sys, s), SimulationError);
  const State end = advance(sys, implicit_euler(0.01), 1.0);
  EXPECT_LT(std::abs(end.x[0]), 1e-6);
  EXPECT_TRUE(end.v.allFinite());
}

// ---- BDF on the oscillator ----------------------------------------------------

TEST(Bdf, ErrorFollowsItsTolerance) {
  // The error of the state at t = 2 s, positions and velocities / ω (m), with atol = rtol.
  auto error = [](double tol) {
    System sys = oscillator();
    const State s = advance(sys, bdf(tol, tol), 2.0);
    return std::hypot(s.x[0] - 0.1 * std::cos(4.0), (s.v[0] + 0.2 * std::sin(4.0)) / 2.0);
  };
  const double e3 = error(1e-3), e5 = error(1e-5), e7 = error(1e-7);
  std::printf("BDF error at t = 2 s: %.3e (rtol 1e-3), %.3e (1e-5), %.3e (1e-7); ratios %.1f, %.1f\n", e3, e5, e7,
              e3 / e5, e5 / e7);
  // Each hundredfold tighter tolerance gives a clearly smaller error, and over the
  // ten-thousandfold range the error falls roughly in proportion (CVODE controls
  // the local error per step, so the global error goes like tol^(q/(q+1)) for order q).
  EXPECT_GT(e3 / e5, 5.0);
  EXPECT_LT(e3 / e5, 1000.0);
  EXPECT_GT(e5 / e7, 5.0);
  EXPECT_LT(e5 / e7, 1000.0);
  EXPECT_GT(e3 / e7, std::pow(10.0, 2.5));
  EXPECT_LT(e3 / e7, std::pow(10.0, 4.5));
}

TEST(Bdf, StatsArePlausibleAndBeatRk4OnAStiffChain) {
  const ChainDef d;
  System sys = chain(d);
  IntegratorStats st;
  auto settings = bdf(1e-4, 1e-7);
  settings.max_order = 2;
  advance(sys, settings, 5.0, &st);
  // RK4 at its stability limit (0.9 of it, as the explicit methods use) for the same 5 s.
  const double h_rk4 = 0.9 * stability_limit(Method::rk4, sys.stiffness());
  const double rk4_rhs = 4.0 * std::ceil(5.0 / h_rk4);
  std::printf("BDF stiff chain, 5 s: %ld steps, %ld RHS, %ld Jacobians, %ld Newton, %ld error-test fails, "
              "%ld convergence fails, last step %.3g s, order %d; RK4 at its limit: %.0f RHS\n",
              st.steps, st.rhs_evaluations, st.jacobian_evaluations, st.newton_iterations, st.error_test_failures,
              st.convergence_failures, st.last_step, st.order, rk4_rhs);
  EXPECT_GT(st.steps, 0);
  EXPECT_GT(st.jacobian_evaluations, 0);
  EXPECT_LT(st.jacobian_evaluations, st.steps);  // Jacobians are reused across steps
  EXPECT_GE(st.newton_iterations, st.steps);
  EXPECT_GE(st.rhs_evaluations, st.newton_iterations);
  EXPECT_GE(st.order, 1);
  EXPECT_LE(st.order, 2);
  EXPECT_GT(st.last_step, 100 * h_rk4);  // once the chain has settled, steps far beyond the explicit limit
  EXPECT_LT(st.rhs_evaluations, rk4_rhs / 4);
}

TEST(Bdf, OrdersAboveTwoAreStabilityLimitedOnLightlyDampedStiffModes) {
  // The chain's fast modes (ω ≈ 1400 rad/s, decay 25 1/s) sit close to the
  // imaginary axis, where BDF3–5 are unstable unless hω is small: CVODE then
  // keeps the step near 0.3 ms whatever the tolerance. BDF2 is A-stable.
  const ChainDef d;
  IntegratorStats order2, order5;
  for (int order : {2, 5}) {
    System sys = chain(d);
    auto settings = bdf(1e-3, 1e-6);
    settings.max_order = order;
    advance(sys, settings, 2.0, order == 2 ? &order2 : &order5);
  }
  std::printf("stiff chain, 2 s, rtol 1e-3: max order 2: %ld steps (last %.3g s); max order 5: %ld steps (last %.3g s)\n",
              order2.steps, order2.last_step, order5.steps, order5.last_step);
  EXPECT_LT(4 * order2.steps, order5.steps);
}

// ---- stiff scenes ---------------------------------------------------------------

TEST(Implicit, StiffChainExplicitEulerRefusesSettlesAtItsStaticExtension) {
  // k = 1e4 N/m between 10 g particles: explicit Euler needs h < 1.4 ms; we ask for 10 ms.
  const ChainDef d;
  {
    System sys = chain(d);
    IntegratorSettings euler;
    euler.step = 0.01;
    State s = initial_state(sys.model());
    EXPECT_THROW(make_integrator(euler)->prepare(sys, s), SimulationError);
  }
  const double expected = chain_bottom_y(d), stretch = expected + (d.n - 1) * d.rest;
  for (const auto& st : {implicit_euler(0.01), bdf(1e-6, 1e-10), bdf(1e-6, 1e-10, true)}) {
    System sys = chain(d);
    auto integ = make_integrator(st);
    State s = initial_state(sys.model());
    integ->prepare(sys, s);
    const double e0 = total_energy(sys, s);
    double e_max = e0;
    for (int k = 1; k <= 60; ++k) {  // 2 s in frames of 1/30 s
      integ->advance(sys, s, k / 30.0);
      ASSERT_TRUE(s.x.allFinite() && s.v.allFinite());
      e_max = std::max(e_max, total_energy(sys, s));
    }
    const double y = s.x[3 * (d.n - 1) + 1];
    SCOPED_TRACE(to_string(st.method) + std::string(st.krylov ? " (GMRES)" : ""));
    // Energy never rises above the start: gravity's work goes into the springs and the drag.
    EXPECT_LE(e_max, e0 + 1e-12);
    // Each spring stretched by the weight it carries: m g (n-1-j) / k (1e-3 of the total stretch).
    EXPECT_NEAR(y, expected, 1e-3 * std::abs(stretch)) << "stretch " << stretch;
    for (int j = 0; j + 1 < d.n; ++j) {
      const double l = (at(s.x, j) - at(s.x, j + 1)).norm();
      EXPECT_NEAR(l - d.rest, (d.n - 1 - j) * d.m * 9.81 / d.k, 1e-3 * std::abs(stretch)) << "spring " << j;
    }
    EXPECT_LT(s.v.norm(), 1e-6);
  }
}

// ---- prescribed motion ------------------------------------------------------------

TEST(Implicit, PinnedParticlesStayExactlyOnTheirPath) {
  ChainDef d;
  d.pin_velocity = Vec3(0.3, 0.1, -0.2);
  const Vec3 start(0.0, 0.0, 0.0);
  for (const auto& st : {implicit_euler(1.0 / 120), bdf(1e-5, 1e-8), bdf(1e-5, 1e-8, true)}) {
    SCOPED_TRACE(to_string(st.method) + std::string(st.krylov ? " (GMRES)" : ""));
    System sys = chain(d);
    auto integ = make_integrator(st);
    State s = initial_state(sys.model());
    MemorySink mem;
    const auto r = run(sys, *integ, s, {30.0, 1.0}, {&mem});
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_EQ(mem.frames.size(), 31u);
    for (std::size_t k = 0; k < mem.frames.size(); ++k) {
      const Vec3 expected = start + mem.times[k] * d.pin_velocity;
      EXPECT_DOUBLE_EQ(mem.frames[k][0], expected.x());
      EXPECT_DOUBLE_EQ(mem.frames[k][1], expected.y());
      EXPECT_DOUBLE_EQ(mem.frames[k][2], expected.z());
    }
    // The chain is dragged along (trailing behind the pin in the air drag).
    EXPECT_GT(mem.frames.back()[3 * (d.n - 1)], 0.05);
  }
}

// ---- failures ----------------------------------------------------------------------

TEST(Implicit, ANaNForceStopsBothMethodsAndNoNaNReachesASink) {
  for (const auto& st : {implicit_euler(0.01), bdf(1e-4, 1e-6), bdf(1e-4, 1e-6, true)}) {
    SCOPED_TRACE(to_string(st.method) + std::string(st.krylov ? " (GMRES)" : ""));
    Model m = particles(1);
    auto anchor = std::make_unique<Anchor>(m, 4.0);
    m.x0[0] = 0.1;
    auto probe = std::make_unique<Probe>();
    probe->force = [](const Eval& e, VecX& f) {
      if (e.t > 0.25) f[0] += std::numeric_limits<double>::quiet_NaN();
    };
    System sys(m, effects(std::move(anchor), std::move(probe)));
    auto integ = make_integrator(st);
    State s = initial_state(sys.model());
    MemorySink mem;
    const auto r = run(sys, *integ, s, {10.0, 1.0}, {&mem});
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find("non-finite"), std::string::npos) << r.error;
    if (st.method == Method::bdf) {
      EXPECT_NE(r.error.find("CV_"), std::string::npos) << r.error;
    }
    EXPECT_EQ(r.frames, 3);  // 0, 0.1, 0.2 s
    for (const auto& f : mem.frames) EXPECT_TRUE(f.allFinite());
    std::printf("%s: %s\n", to_string(st.method), r.error.c_str());
  }
}

TEST(Bdf, RefusesSettingsThatCannotWork) {
  System sys = oscillator();
  State s = initial_state(sys.model());
  EXPECT_THROW(make_integrator(bdf(0.0, 1e-6))->prepare(sys, s), SimulationError);
  EXPECT_THROW(make_integrator(bdf(1e-4, -1.0))->prepare(sys, s), SimulationError);
  auto st = bdf(1e-4, 1e-6);
  st.max_order = 6;
  EXPECT_THROW(make_integrator(st)->prepare(sys, s), SimulationError);
}

// ---- the linear and nonlinear solves of implicit Euler ---------------------------

namespace {

// A chain hanging stretched (rest length 0.08 m at 0.1 m spacing) and swinging:
// every spring in tension, so M - h D - h² K is symmetric positive definite.
System swinging_chain(int n, State& s0) {
  ChainDef d;
  d.n = n;
  d.rest = 0.08;
  d.k = 100.0;
  System sys = chain(d);
  s0 = initial_state(sys.model());
  for (int i = 1; i < n; ++i) at(s0.v, i) = Vec3(0.5 * std::sin(i), 0.2 * std::cos(3.0 * i), 0.3);
  return sys;
}

// |M (v1 - v0) - h f(x0 + h v1, v1)| over free dofs: the backward Euler residual.
double backward_euler_residual(System& sys, const State& s0, const State& s1, double h) {
  VecX f;
  sys.force(s0.t + h, s1.x, s1.v, f);
  VecX r = VecX::Zero(s0.x.size());
  for (int i = 0; i < sys.model().num_particles(); ++i)
    at(r, i) = sys.model().mass[i] * (at(s1.v, i) - at(s0.v, i)) - h * at(f, i);
  return r.cwiseProduct(sys.free_dofs()).norm();
}

}  // namespace

TEST(ImplicitEuler, ConjugateGradientsReachTheToleranceOnAnSpdSystem) {
  const double h = 0.02;
  for (double tol : {1e-2, 1e-6, 1e-10}) {
    State s0;
    System sys = swinging_chain(12, s0);
    // The Baraff–Witkin system at the start: (M - h D - h² K) Δv = h (f + h K v0).
    VecX f;
    SparseMatrix dfdx, dfdv;
    sys.force(s0.t, s0.x, s0.v, f);
    sys.jacobian(s0.t, s0.x, s0.v, dfdx, dfdv);
    VecX mass_dof(s0.x.size());
    for (int i = 0; i < sys.model().num_particles(); ++i) at(mass_dof, i).setConstant(sys.model().mass[i]);
    SparseMatrix mass(s0.x.size(), s0.x.size());
    mass.setIdentity();
    mass.diagonal() = mass_dof;
    const SparseMatrix a = mass - h * dfdv - h * h * dfdx;
    const VecX b = (h * (f + h * dfdx * s0.v)).cwiseProduct(sys.free_dofs());

    auto st = implicit_euler(h);
    st.cg_tolerance = tol;
    auto integ = make_integrator(st);
    State s = s0;
    integ->prepare(sys, s);
    integ->advance(sys, s, h);
    const VecX dv = (s.v - s0.v).cwiseProduct(sys.free_dofs());
    const double rel = (a * dv - b).cwiseProduct(sys.free_dofs()).norm() / b.norm();
    const auto stats = integ->stats();
    std::printf("CG tolerance %.0e: relative residual %.2e after %ld iterations (%ld dofs)\n", tol, rel,
                stats.linear_iterations, s0.x.size());
    EXPECT_LE(rel, tol * (1 + 1e-6));
    EXPECT_GT(stats.linear_iterations, 0);
    EXPECT_LE(stats.linear_iterations, s0.x.size());
    EXPECT_EQ(stats.newton_iterations, 1);
    EXPECT_EQ(stats.convergence_failures, 0);
    if (tol == 1e-2) {
      EXPECT_GT(rel, 1e-10);  // a loose tolerance is not silently exceeded
    }
  }
}

// A pinned particle moving at v is, to the step, a free particle so heavy
// that nothing changes its velocity: implicit Euler must move the chain the
// same way in both cases. Pulled along the chain (first order in the
// springs), light particles (1e-5 kg, k = 4 500 N/m: ω h ≈ 100) next to the
// pin feel its move within the step, through K_fp v_p in the right-hand
// side. Before that term the pinned chain lagged a step behind and every
// step was refused (the fingers case in tests/stability).
TEST(ImplicitEuler, AMovingPinPullsItsNeighboursWithinTheStep) {
  const int n = 5;
  const double m = 1e-5, k = 4500.0, rest = 0.005, h = 0.005;
  const Vec3 v_pin(0.0, 0.3, 0.0);  // m/s, along the chain: stretches the first spring
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i + 1 < n; ++i) pairs.push_back({i, i + 1});
  auto make = [&](bool pinned) {
    Model model = particles(n, m);
    for (int i = 0; i < n; ++i) at(model.x0, i) = Vec3(0.0, -i * rest, 0.0);
    if (!pinned) model.mass[0] = 1e12;  // kg: its velocity cannot change
    std::vector<std::unique_ptr<Effect>> fx;
    fx.push_back(std::make_unique<Springs>(pairs, k, rest));
    if (pinned) fx.push_back(make_pins(model, {{0}, v_pin}));
    return System(std::move(model), std::move(fx));
  };
  System pinned = make(true), heavy = make(false);
  State a = initial_state(pinned.model()), b = initial_state(heavy.model());
  pinned.apply_prescribed(a);
  at(b.v, 0) = v_pin;
  auto ia = make_integrator(implicit_euler(h)), ib = make_integrator(implicit_euler(h));
  ia->prepare(pinned, a);
  ib->prepare(heavy, b);
  for (int step = 1; step <= 10; ++step) {
    ia->advance(pinned, a, step * h);
    ib->advance(heavy, b, step * h);
  }
  EXPECT_EQ(ia->stats().convergence_failures, 0);
  EXPECT_EQ(ia->stats().steps, ib->stats().steps);
  // The chain followed the pin 15 mm up, particle for particle as the heavy one's.
  EXPECT_NEAR(a.x[3 * (n - 1) + 1], b.x[3 * (n - 1) + 1], 1e-6);
  EXPECT_GT(a.x[3 * (n - 1) + 1] - pinned.model().x0[3 * (n - 1) + 1], 0.01);
  for (int i = 1; i < n; ++i) EXPECT_NEAR((at(a.x, i) - at(b.x, i)).norm(), 0.0, 1e-6) << "particle " << i;
}

TEST(ImplicitEuler, NewtonIterationsSolveTheBackwardEulerEquations) {
  // Large swings and a large step make the springs' nonlinearity matter.
  const double h = 0.05;
  double prev = INFINITY;
  for (int iterations : {1, 2, 3, 5}) {
    State s0;
    System sys = swinging_chain(8, s0);
    for (int i = 1; i < 8; ++i) at(s0.v, i) *= 4.0;
    auto st = implicit_euler(h);
    st.newton_iterations = iterations;
    st.cg_tolerance = 1e-12;
    auto integ = make_integrator(st);
    State s = s0;
    integ->prepare(sys, s);
    integ->advance(sys, s, h);
    const double r = backward_euler_residual(sys, s0, s, h);
    std::printf("Newton iterations %d (%ld done): backward Euler residual %.3e\n", iterations,
                integ->stats().newton_iterations, r);
    EXPECT_LT(r, prev);
    if (iterations == 5) {
      EXPECT_LT(r, 1e-9);
    }
    prev = r;
  }
}

TEST(ImplicitEuler, RetriesIndefiniteStepsAsHalfSteps) {
  // Two particles 0.1 m apart on a spring of rest length 1 m moving sideways:
  // the compressed spring's geometric stiffness +9k(I - d̂d̂ᵀ) makes M - h²K
  // indefinite until h²·18k/m < 1, i.e. three halvings of 0.01 s for k = 1e4.
  Model m = particles(2, 1.0, 0.1);
  m.v0 = VecX::Zero(6);
  m.v0[1] = 0.1;
  m.v0[4] = -0.1;
  System sys(m, effects(std::make_unique<Springs>(std::vector<std::array<int, 2>>{{0, 1}}, 1e4, 1.0)));
  auto integ = make_integrator(implicit_euler(0.01));
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  integ->advance(sys, s, 0.01);
  EXPECT_GE(integ->stats().convergence_failures, 3);
  EXPECT_TRUE(s.x.allFinite() && s.v.allFinite());

  // Far stiffer, it cannot be helped within 2⁸ halvings: the run stops and says why.
  System stiff(m, effects(std::make_unique<Springs>(std::vector<std::array<int, 2>>{{0, 1}}, 1e12, 1.0)));
  auto integ2 = make_integrator(implicit_euler(0.01));
  State s2 = initial_state(stiff.model());
  integ2->prepare(stiff, s2);
  try {
    integ2->advance(stiff, s2, 0.01);
    FAIL() << "expected a refusal";
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos) << e.what();
  }
}

TEST(ImplicitEuler, ANearlySingularStepIsRetriedInsteadOfInjectingEnergy) {
  // As above, with k such that M - h²K is positive definite but nearly singular
  // (smallest eigenvalue 0.001 m): CG succeeds, and the linearised step would
  // throw the particles sideways at ~1000x their speed. The residual test
  // rejects it; half steps (smallest eigenvalue 0.75 m) do well.
  const double h = 0.01, k = 0.999 / (18.0 * h * h);
  Model m = particles(2, 1.0, 0.1);
  m.v0 = VecX::Zero(6);
  m.v0[1] = 0.1;
  m.v0[4] = -0.1;
  System sys(m, effects(std::make_unique<Springs>(std::vector<std::array<int, 2>>{{0, 1}}, k, 1.0)));
  auto integ = make_integrator(implicit_euler(h));
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  const double e0 = total_energy(sys, s);
  integ->advance(sys, s, h);
  const double e1 = total_energy(sys, s);
  std::printf("nearly singular step: %ld retries, energy %.6g J -> %.6g J, transverse speed %.3g m/s\n",
              integ->stats().convergence_failures, e0, e1, std::abs(s.v[1]));
  EXPECT_GE(integ->stats().convergence_failures, 1);
  EXPECT_LE(e1, e0);
  EXPECT_LT(std::abs(s.v[1]), 1.0);
}

// ---- effects without a Jacobian -----------------------------------------------------

TEST(Implicit, AnEffectWithoutAJacobianStillIntegrates) {
  // The anchor force of k = 100 N/m (ω = 10 rad/s) given by a Probe, which has no Jacobian.
  auto make = [](bool with_jacobian) {
    Model m = particles(1);
    auto anchor = std::make_unique<Anchor>(m, 100.0);
    m.x0[0] = 0.1;
    if (with_jacobian) return System(m, effects(std::move(anchor)));
    auto probe = std::make_unique<Probe>();
    probe->force = [](const Eval& e, VecX& f) { f -= 100.0 * e.x; };
    return System(m, effects(std::move(probe)));
  };
  const double exact = 0.1 * std::cos(10.0 * 2.0);
  for (bool krylov : {false, true}) {
    SCOPED_TRACE(krylov ? "GMRES" : "KLU");
    System with = make(true), without = make(false);
    IntegratorStats sw, so;
    const State a = advance(with, bdf(1e-6, 1e-8, krylov), 2.0, &sw);
    const State b = advance(without, bdf(1e-6, 1e-8, krylov), 2.0, &so);
    std::printf("%s: with Jacobian error %.2e, %ld steps, %ld Newton, %ld RHS; without: error %.2e, %ld steps, "
                "%ld Newton, %ld RHS\n",
                krylov ? "GMRES" : "KLU", std::abs(a.x[0] - exact), sw.steps, sw.newton_iterations,
                sw.rhs_evaluations, std::abs(b.x[0] - exact), so.steps, so.newton_iterations, so.rhs_evaluations);
    EXPECT_NEAR(a.x[0], exact, 1e-4);
    EXPECT_NEAR(b.x[0], exact, 1e-4);
    EXPECT_GE(so.rhs_evaluations, sw.rhs_evaluations);  // the missing Jacobian costs work, not accuracy
  }
  // Implicit Euler: the force enters explicitly (then it is symplectic Euler), stable below 2/ω.
  System without = make(false);
  const State c = advance(without, implicit_euler(0.01), 2.0);
  EXPECT_TRUE(c.x.allFinite());
  EXPECT_LT(std::abs(c.x[0]), 0.1 * 1.06);
}

// ---- hooks under CVODE, determinism ---------------------------------------------------

TEST(Bdf, RestartsFromAStateAnAfterStepHookChanged) {
  // Free fall; a hook stops the particle at t = 0.5 s. From there it falls afresh:
  // y(1) = -g/2 (0.5)² - g/2 (0.5)², v(1) = -g 0.5.
  Model m = particles(1);
  System sys(m, effects(make_gravity({}), std::make_unique<Stopper>(0.5)));
  auto integ = make_integrator(bdf(1e-8, 1e-10));
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  for (int k = 1; k <= 10; ++k) integ->advance(sys, s, 0.1 * k);
  EXPECT_NEAR(s.x[1], -9.81 * 0.25, 1e-6);
  EXPECT_NEAR(s.v[1], -9.81 * 0.5, 1e-6);
}

TEST(Implicit, RunsAreDeterministic) {
  ChainDef d;
  d.pin_velocity = Vec3(0.2, 0.0, 0.1);
  for (const auto& st : {implicit_euler(0.01), bdf(1e-5, 1e-8), bdf(1e-5, 1e-8, true)}) {
    SCOPED_TRACE(to_string(st.method) + std::string(st.krylov ? " (GMRES)" : ""));
    System a = chain(d), b = chain(d);
    const State sa = advance(a, st, 1.0), sb = advance(b, st, 1.0);
    EXPECT_TRUE(sa.x == sb.x);
    EXPECT_TRUE(sa.v == sb.v);
  }
}

TEST(Bdf, GmresAgreesWithTheSparseDirectSolver) {
  ChainDef d;
  d.pin_velocity = Vec3(0.2, 0.0, 0.1);
  System a = chain(d), b = chain(d);
  IntegratorStats sa, sb;
  const State xa = advance(a, bdf(1e-7, 1e-10), 1.0, &sa);
  const State xb = advance(b, bdf(1e-7, 1e-10, true), 1.0, &sb);
  std::printf("KLU: %ld steps, %ld Newton; GMRES: %ld steps, %ld Newton, %ld linear iterations; |dx| = %.2e m\n",
              sa.steps, sa.newton_iterations, sb.steps, sb.newton_iterations, sb.linear_iterations,
              (xa.x - xb.x).lpNorm<Eigen::Infinity>());
  EXPECT_LT((xa.x - xb.x).lpNorm<Eigen::Infinity>(), 1e-5);
  EXPECT_GT(sb.linear_iterations, 0);
  EXPECT_EQ(sa.linear_iterations, 0);  // a direct solve has no iterations
}
