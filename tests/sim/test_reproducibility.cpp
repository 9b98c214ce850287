// Reproducibility: the same system, the same build → the same
// trajectory bit for bit, for every integrator, with one thread or two
// (docs/accuracy-vs-time.md, "Reproducibility").
// The shipped scenes (flag, drape-sphere) are checked in tests/stability.
#include <gtest/gtest.h>
#include <omp.h>

#include <string>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/run.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

// A flag: 30 × 20 particles (3 500 springs: enough for the parallel force
// loops), two corners pinned, gravity, viscosity and gusty wind.
std::unique_ptr<System> flag() {
  const int nu = 30, nv = 20;
  const Model m = make_grid(nu, nv, 0.05, 0.05, Vec3(0, 2, 0), Vec3(0, 0, -1), Vec3(0, -1, 0), 0.01);
  MassSpringMaterial mat;
  mat.warp = mat.weft = 200.0;
  mat.shear = mat.bend_warp = mat.bend_weft = 20.0;
  mat.damping = 0.02;
  WindDef wind;
  wind.velocity = Vec3(2, 2, -10);
  wind.coefficient = 1.0;
  wind.turbulence = 0.3;
  PinDef pins;
  pins.particles = {0, (nv - 1) * nu};
  return std::make_unique<System>(m, effects(make_mass_spring(m, {mat}), make_gravity({}), make_viscosity({0.002, 0.0}),
                                             make_wind(wind), make_pins(m, pins)));
}

MemorySink trajectory(Method method, int threads) {
  omp_set_num_threads(threads);
  auto sys = flag();
  IntegratorSettings st;
  st.method = method;
  st.step = is_explicit(method) ? 0.001 : 0.005;  // explicit ones sub-step to their limit
  st.auto_substep = is_explicit(method);
  auto integ = make_integrator(st);
  State s = initial_state(sys->model());
  MemorySink frames;
  const auto r = run(*sys, *integ, s, {25.0, 0.2}, {&frames});
  EXPECT_TRUE(r.ok) << r.error;
  omp_set_num_threads(omp_get_num_procs());
  return frames;
}

double max_distance(const MemorySink& a, const MemorySink& b) {
  double d = 0.0;
  EXPECT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t k = 0; k < std::min(a.frames.size(), b.frames.size()); ++k)
    for (int i = 0; i < a.frames[k].size() / 3; ++i) d = std::max(d, (at(a.frames[k], i) - at(b.frames[k], i)).norm());
  return d;
}

}  // namespace

class Reproducibility : public ::testing::TestWithParam<Method> {};

TEST_P(Reproducibility, OneThreadGivesABitIdenticalTrajectoryTwice) {
  const MemorySink a = trajectory(GetParam(), 1), b = trajectory(GetParam(), 1);
  ASSERT_EQ(a.frames.size(), 6u);
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    ASSERT_EQ(a.times[k], b.times[k]);
    ASSERT_TRUE(a.frames[k] == b.frames[k]) << "frame " << k << " differs";
  }
}

// Every parallel loop either writes independent outputs or sums in chunks
// fixed independently of the thread count (mass-spring: 8 chunks), and
// contact pairs are sorted after threaded detection: so two threads give the
// one-thread trajectory bit for bit. A race, or a sum that depends on the
// thread count, shows as a difference here.
TEST_P(Reproducibility, TwoThreadsGiveTheOneThreadTrajectoryBitForBit) {
  if (omp_get_num_procs() < 2) GTEST_SKIP() << "one core: no second thread to compare";
  const MemorySink a = trajectory(GetParam(), 1), b = trajectory(GetParam(), 2);
  RecordProperty("max_distance_m", sci(max_distance(a, b)));
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    ASSERT_EQ(a.times[k], b.times[k]);
    ASSERT_TRUE(a.frames[k] == b.frames[k]) << "frame " << k << " differs by " << max_distance(a, b) << " m";
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, Reproducibility,
                         ::testing::Values(Method::symplectic_euler, Method::midpoint, Method::rk4,
                                           Method::implicit_euler, Method::bdf),
                         [](const auto& param_info) {
                           std::string s = to_string(param_info.param);
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });
