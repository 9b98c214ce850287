// The system: only listed effects are built and evaluated, forces sum, pins
// prescribe, states are checked, every effect is counted and timed.
#include <gtest/gtest.h>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

TEST(System, EvaluatesExactlyTheEffectsItWasGiven) {
  auto probe = std::make_unique<Probe>();
  Probe* p = probe.get();
  System sys(particles(3), effects(make_gravity({}), std::move(probe)));
  ASSERT_EQ(sys.profile().size(), 2u);
  EXPECT_EQ(sys.profile()[0].name, "gravity");
  EXPECT_EQ(sys.profile()[1].name, "probe");
  VecX f;
  const State s = initial_state(sys.model());
  for (int k = 0; k < 5; ++k) sys.force(0.0, s.x, s.v, f);
  EXPECT_EQ(p->calls, 5);
  EXPECT_EQ(sys.profile()[0].force_calls, 5);
  EXPECT_EQ(sys.force_evaluations(), 5);
}

TEST(System, AccelerationIsForceOverMass) {
  System sys(particles(2, 0.5), effects(make_gravity({Vec3(0, 0, -2.0)})));
  VecX a;
  const State s = initial_state(sys.model());
  sys.acceleration(0.0, s.x, s.v, a);
  EXPECT_DOUBLE_EQ(a[2], -2.0);
  EXPECT_DOUBLE_EQ(a[5], -2.0);
}

TEST(System, PinnedParticlesFeelNoForceAndFollowTheirPath) {
  Model m = particles(3);
  auto pins = make_pins(m, {{0, 2}, Vec3(0.0, 1.0, 0.0)});
  System sys(m, effects(make_gravity({}), std::move(pins)));
  VecX a;
  State s = initial_state(sys.model());
  sys.acceleration(0.0, s.x, s.v, a);
  EXPECT_EQ(a.segment<3>(0).norm(), 0.0);
  EXPECT_NE(a.segment<3>(3).norm(), 0.0);
  EXPECT_EQ(a.segment<3>(6).norm(), 0.0);
  s.t = 2.0;
  sys.apply_prescribed(s);
  EXPECT_DOUBLE_EQ(s.x[7], 2.0);
  EXPECT_DOUBLE_EQ(s.v[7], 1.0);
  EXPECT_EQ(sys.free_dofs().sum(), 3.0);
}

TEST(System, PinOfAMissingParticleIsRefused) {
  Model m = particles(2);
  EXPECT_THROW(make_pins(m, {{5}}), SimulationError);
}

TEST(System, NonFiniteStateIsCaughtAndNamed) {
  System sys(particles(4), effects(make_gravity({})));
  State s = initial_state(sys.model());
  s.x[7] = std::numeric_limits<double>::quiet_NaN();
  try {
    sys.check_state(s, 340.0);
    FAIL();
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("particle 2"), std::string::npos) << e.what();
  }
  s.x[7] = 0.0;
  s.v[3] = 500.0;
  EXPECT_THROW(sys.check_state(s, 340.0), SimulationError);
}

TEST(System, InvalidModelIsRefused) {
  Model m = particles(2);
  m.mass[1] = 0.0;
  EXPECT_THROW(System(m, {}), SimulationError);
  m = particles(2);
  m.triangles.push_back({0, 1, 7});
  EXPECT_THROW(System(m, {}), SimulationError);
}

TEST(System, StiffnessNamesTheStiffestParticleAndEffect) {
  Model m = particles(3, 1.0);
  m.mass[1] = 0.01;  // light particle: highest k/m
  auto anchor = std::make_unique<Anchor>(m, 100.0);
  System sys(m, effects(make_viscosity({0.5, 0.0}), std::move(anchor)));
  EXPECT_EQ(sys.stiffness().particle, 1);
  EXPECT_DOUBLE_EQ(sys.stiffness().omega2, 100.0 / 0.01);
  EXPECT_EQ(sys.stiffness().effect, "anchor");
  EXPECT_DOUBLE_EQ(sys.stiffness().damping_rate, 0.5 / 0.01);
}

TEST(System, LumpedMassesAddUpToDensityTimesArea) {
  const Model g = make_grid(11, 6, 0.1, 0.1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1.0);
  const VecX m = lump_masses(g.uv, g.triangles, 0.2);
  EXPECT_NEAR(m.sum(), 0.2 * 1.0 * 0.5, 1e-12);
  EXPECT_GT(m.minCoeff(), 0.0);
}

TEST(System, GridHasTwoTrianglesPerCellAndPositionsInItsPlane) {
  const Model g = make_grid(4, 3, 0.5, 0.25, Vec3(0, 1, 0), Vec3::UnitX(), -Vec3::UnitY(), 0.1);
  EXPECT_EQ(g.num_particles(), 12);
  EXPECT_EQ(g.triangles.size(), 12u);
  EXPECT_DOUBLE_EQ(g.x0[3 * 11 + 0], 1.5);
  EXPECT_DOUBLE_EQ(g.x0[3 * 11 + 1], 0.5);
  for (const auto& t : g.triangles) {  // counter-clockwise in (u, v)
    const Vec2 a = g.uv[t[1]] - g.uv[t[0]], b = g.uv[t[2]] - g.uv[t[0]];
    EXPECT_GT(a.x() * b.y() - a.y() * b.x(), 0.0);
  }
}
