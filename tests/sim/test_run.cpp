// Running: frames at the frame rate, progress, and a blow-up that stops the
// run with a message while every emitted frame stays finite.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/run.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

TEST(Run, EmitsOneFramePerFrameTimeIncludingTheStart) {
  System sys(particles(2), effects(make_gravity({})));
  auto integ = make_integrator({});
  State s = initial_state(sys.model());
  MemorySink mem;
  int calls = 0;
  const auto r = run(sys, *integ, s, {30.0, 1.0}, {&mem}, [&](const Progress& p) {
    ++calls;
    EXPECT_LE(p.frame, p.frames);
    EXPECT_GE(p.eta_s, 0.0);
  });
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.frames, 31);
  EXPECT_EQ(mem.frames.size(), 31u);
  EXPECT_DOUBLE_EQ(mem.times.back(), 1.0);
  EXPECT_NEAR(mem.times[1], 1.0 / 30.0, 1e-15);
  EXPECT_EQ(calls, 30);
  EXPECT_EQ(r.stats.steps, 30 * 9);  // 1/30 s in steps of at most 4 ms
}

// The start moved by a jitter: every coordinate within it, the same seed the
// same start, another seed another one.
TEST(Run, StartJitterMovesEachCoordinateWithinItBySeed) {
  auto frame0 = [](double jitter, unsigned seed) {
    System sys(particles(50), effects(make_gravity({})));
    auto integ = make_integrator({});
    State s = initial_state(sys.model());
    MemorySink mem;
    RunSettings rs{30.0, 0.0};
    rs.start_jitter = jitter;
    rs.start_jitter_seed = seed;
    EXPECT_TRUE(run(sys, *integ, s, rs, {&mem}).ok);
    return VecX(mem.frames.front() - sys.model().x0);
  };
  const VecX a = frame0(1e-6, 1), b = frame0(1e-6, 1), c = frame0(1e-6, 2), none = frame0(0.0, 1);
  EXPECT_LE(a.cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_GT(a.cwiseAbs().maxCoeff(), 5e-7);  // 150 uniform draws: one lands in the outer half
  EXPECT_EQ(a, b);
  EXPECT_GT((a - c).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(none.cwiseAbs().maxCoeff(), 0.0);
}

TEST(Run, ABlowUpStopsTheRunAndNoNaNReachesASink) {
  auto probe = std::make_unique<Probe>();
  probe->force = [](const Eval& e, VecX& f) {
    if (e.t > 0.25) f[0] += std::numeric_limits<double>::infinity();
  };
  System sys(particles(1), effects(std::move(probe)));
  auto integ = make_integrator({});
  State s = initial_state(sys.model());
  MemorySink mem;
  const auto r = run(sys, *integ, s, {10.0, 1.0}, {&mem});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("non-finite"), std::string::npos) << r.error;
  EXPECT_EQ(r.frames, 3);  // 0, 0.1, 0.2 s
  for (const auto& f : mem.frames) EXPECT_TRUE(f.allFinite());
  // The state is left at the last frame the sink received, not half-way
  // through the failing step.
  EXPECT_DOUBLE_EQ(s.t, 0.2);
  EXPECT_EQ(s.x, mem.frames.back());
  EXPECT_DOUBLE_EQ(r.simulated_s, 0.2);
}

TEST(Run, AnUnstableStepIsRefusedBeforeTheFirstFrame) {
  Model m = particles(1);
  auto anchor = std::make_unique<Anchor>(m, 1e6);
  System sys(m, effects(std::move(anchor)));
  IntegratorSettings st;
  st.step = 0.01;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  MemorySink mem;
  const auto r = run(sys, *integ, s, {30.0, 1.0}, {&mem});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("stability limit"), std::string::npos);
  EXPECT_TRUE(mem.frames.empty());
}
