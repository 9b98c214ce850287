// The fixed-step integrators: orders of convergence, energy behaviour,
// stability limits and refusals.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/integrator.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

// One particle on an anchor spring, displaced by 0.1 m along x, released at rest.
// Exact: x(t) = 0.1 cos(ω t).
System oscillator(double k = 4.0, double m = 1.0) {
  Model model = particles(1, m);
  model.x0[0] = 0.0;
  auto anchor = std::make_unique<Anchor>(model, k);
  model.x0[0] = 0.1;  // start displaced; the anchor keeps the origin
  return System(model, effects(std::move(anchor)));
}

double error_at(Method method, double h, double t_end) {
  System sys = oscillator();
  IntegratorSettings st;
  st.method = method;
  st.step = h;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  integ->advance(sys, s, t_end);
  return std::abs(s.x[0] - 0.1 * std::cos(2.0 * t_end));
}

double observed_order(Method m) {
  const double e1 = error_at(m, 0.02, 2.0), e2 = error_at(m, 0.01, 2.0);
  return std::log2(e1 / e2);
}

}  // namespace

TEST(Integrators, SymplecticEulerIsFirstOrder) { EXPECT_NEAR(observed_order(Method::symplectic_euler), 1.0, 0.15); }
TEST(Integrators, MidpointIsSecondOrder) { EXPECT_NEAR(observed_order(Method::midpoint), 2.0, 0.15); }
TEST(Integrators, Rk4IsFourthOrder) { EXPECT_NEAR(observed_order(Method::rk4), 4.0, 0.2); }

TEST(Integrators, Rk4IsExactForFreeFall) {
  Model m = particles(1, 2.0);
  System sys(m, effects(make_gravity({})));
  IntegratorSettings st;
  st.method = Method::rk4;
  st.step = 0.01;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->advance(sys, s, 0.5);
  EXPECT_NEAR(s.x[1], -0.5 * 9.81 * 0.25, 1e-12);
  EXPECT_NEAR(s.v[1], -9.81 * 0.5, 1e-12);
}

TEST(Integrators, SymplecticEulerKeepsOscillatorEnergyBounded) {
  // 10 000 steps at h ω = 0.2: energy oscillates within O(h ω) but never drifts.
  System sys = oscillator();
  IntegratorSettings st;
  st.step = 0.1;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  const double e0 = sys.kinetic_energy(s.v) + sys.potential_energy(0, s.x, s.v);
  double lo = e0, hi = e0;
  for (int k = 1; k <= 100; ++k) {
    integ->advance(sys, s, k * 10.0);
    const double e = sys.kinetic_energy(s.v) + sys.potential_energy(s.t, s.x, s.v);
    lo = std::min(lo, e), hi = std::max(hi, e);
  }
  EXPECT_LT(hi / e0, 1.12);
  EXPECT_GT(lo / e0, 0.88);
}

TEST(Integrators, Rk4EnergyDriftIsTinyBelowItsLimit) {
  // RK4 dissipates slightly (h ω = 0.2: |amplification| ≈ 1 - (hω)⁶/144 per step).
  System sys = oscillator();
  IntegratorSettings st;
  st.method = Method::rk4;
  st.step = 0.1;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  const double e0 = sys.potential_energy(0, s.x, s.v);
  integ->advance(sys, s, 100.0);
  const double e = sys.kinetic_energy(s.v) + sys.potential_energy(s.t, s.x, s.v);
  EXPECT_LT(std::abs(e / e0 - 1.0), 1e-3);
}

TEST(Integrators, StepAboveTheLimitIsRefusedWithAdvice) {
  System sys = oscillator(1.0e4);  // ω = 100 rad/s: symplectic Euler needs h < 0.02 s
  IntegratorSettings st;
  st.step = 0.05;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  try {
    integ->prepare(sys, s);
    FAIL() << "expected a refusal";
  } catch (const SimulationError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("stability limit"), std::string::npos) << msg;
    EXPECT_NE(msg.find("0.018"), std::string::npos) << msg;  // 0.9 × 2/100
    EXPECT_NE(msg.find("particle 0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("anchor"), std::string::npos) << msg;
    EXPECT_NE(msg.find("implicit"), std::string::npos) << msg;
  }
}

TEST(Integrators, AutoSubstepStaysStableWhereAFixedStepWouldExplode) {
  System sys = oscillator(1.0e4);
  IntegratorSettings st;
  st.step = 0.05;
  st.auto_substep = true;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  EXPECT_LE(integ->step(), 0.9 * 2.0 / 100.0 + 1e-15);
  // Bounded: the amplitude in the last second is no larger than in the first.
  double first = 0.0, last = 0.0;
  for (int k = 1; k <= 500; ++k) {
    integ->advance(sys, s, k * 0.01);
    if (k <= 100) first = std::max(first, std::abs(s.x[0]));
    if (k > 400) last = std::max(last, std::abs(s.x[0]));
  }
  EXPECT_LE(last, 1.01 * first);
  EXPECT_LT(first, 0.1 / std::sqrt(1.0 - 0.81) + 1e-3);  // symplectic Euler's amplitude at h ω = 1.8
}

TEST(Integrators, StabilityLimitsFollowTheMethods) {
  Stiffness k;
  k.omega2 = 100.0 * 100.0;
  EXPECT_DOUBLE_EQ(stability_limit(Method::symplectic_euler, k), 0.02);
  EXPECT_NEAR(stability_limit(Method::rk4, k), 2.0 * std::sqrt(2.0) / 100.0, 1e-15);
  // Midpoint: growth (hω)⁴/8 per step held to 1 %/s: h = (0.08 / ω⁴)^{1/3}.
  EXPECT_NEAR(stability_limit(Method::midpoint, k), std::cbrt(0.08) * std::pow(100.0, -4.0 / 3.0), 1e-15);
  EXPECT_TRUE(std::isinf(stability_limit(Method::implicit_euler, k)));
  k.damping_rate = 1000.0;  // heavy damping limits explicit steps too
  EXPECT_DOUBLE_EQ(stability_limit(Method::symplectic_euler, k), 0.002);
  k.damping_rate = 1.0;  // damping pays for some of midpoint's growth: a longer step
  EXPECT_NEAR(stability_limit(Method::midpoint, k), std::cbrt(4.08) * std::pow(100.0, -4.0 / 3.0), 1e-15);
}

TEST(Integrators, MethodNamesParse) {
  EXPECT_EQ(parse_method("euler"), Method::symplectic_euler);
  EXPECT_EQ(parse_method("rk4"), Method::rk4);
  EXPECT_EQ(parse_method("cvode"), Method::bdf);
  EXPECT_THROW(parse_method("leapfrog"), std::invalid_argument);
}
