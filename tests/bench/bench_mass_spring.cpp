// Mass-spring cloth speed on the seed's 30 × 30 flag (seed 000 §4.1: the
// Garment PROTO's constants, 0.1 kg particles, gravity, viscosity 0.2 N·s/m,
// two corners pinned to the staff), per integrator and thread count.
// Target: ≥ 20 million particle-steps/s with symplectic Euler on one core.
// Run: build/tests/bench/vgd_bench --benchmark_filter=MassSpring
#include <benchmark/benchmark.h>
#include <omp.h>

#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/integrator.hpp"

namespace {

using namespace vgd::sim;

constexpr int kSide = 30;

// The flag: 1 m × 1 m, warp along +x, weft hanging along −y, pinned at the
// two corners of its staff side (u = 0).
System flag(double max_strain, bool wind = false) {
  Model m = make_grid(kSide, kSide, 1.0 / (kSide - 1), 1.0 / (kSide - 1), Vec3::Zero(), Vec3::UnitX(),
                      -Vec3::UnitY(), 0.1);
  MassSpringMaterial mat;  // the seed's constants
  mat.max_strain = max_strain;
  MassSpringOptions opt;
  opt.fixed = {0, (kSide - 1) * kSide};
  std::vector<std::unique_ptr<Effect>> effects;
  effects.push_back(make_mass_spring(m, {mat}, opt));
  effects.push_back(make_gravity({}));
  effects.push_back(make_viscosity({0.2, 0.0}));
  effects.push_back(make_pins(m, {opt.fixed}));
  // The shipped flag's wind (data/scenes/flag.json): the seed's (10, 10, -100) m/s, gusty.
  if (wind) effects.push_back(make_wind({Vec3(10, 10, -100), 40.0, 0.1, 1.0, 1}));
  return System(std::move(m), std::move(effects));
}

// Whole steps (forces of every effect, integration, pins, after-step hooks,
// state checks) at the seed's step of 2.5 ms, shortened to the stability
// limit where the method needs it (midpoint: ≈ 1 ms).
void BM_MassSpringFlag(benchmark::State& state, Method method, double max_strain, bool wind = false) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(static_cast<int>(state.range(0)));
  System sys = flag(max_strain, wind);
  IntegratorSettings st;
  st.method = method;
  st.step = 0.0025;
  st.auto_substep = true;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  integ->advance(sys, s, 0.5);  // past the first fall: a hanging flag
  const long before = integ->stats().steps;
  for (auto _ : state) {
    integ->advance(sys, s, s.t + 100 * integ->step());
    benchmark::DoNotOptimize(s.x.data());
  }
  const double steps = static_cast<double>(integ->stats().steps - before);
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(steps * sys.model().num_particles(), benchmark::Counter::kIsRate);
  state.counters["steps_per_s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["step_ms"] = integ->step() * 1e3;
  if (const auto* ms = mass_spring_stats(*sys.effects()[0])) {
    state.counters["springs"] = ms->springs;
    if (max_strain > 0) state.counters["unresolved_steps"] = static_cast<double>(ms->unresolved_steps);
  }
  omp_set_num_threads(saved);
}

// The force kernel alone: one add_forces over the flag's 5 104 springs.
void BM_MassSpringForces(benchmark::State& state) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(static_cast<int>(state.range(0)));
  System sys = flag(0.0);
  const Model& m = sys.model();
  Effect& e = *sys.effects()[0];
  VecX x = m.x0, v = VecX::Constant(m.num_dofs(), 0.01), f = VecX::Zero(m.num_dofs());
  for (int k = 0; k < m.num_dofs(); k += 7) x[k] += 1e-3;
  for (auto _ : state) {
    e.add_forces({m, 0.0, x, v}, f);
    benchmark::DoNotOptimize(f.data());
  }
  state.counters["springs_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * mass_spring_stats(e)->springs, benchmark::Counter::kIsRate);
  omp_set_num_threads(saved);
}

}  // namespace

BENCHMARK_CAPTURE(BM_MassSpringFlag, symplectic_euler, Method::symplectic_euler, 0.0)->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK_CAPTURE(BM_MassSpringFlag, midpoint, Method::midpoint, 0.0)->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK_CAPTURE(BM_MassSpringFlag, rk4, Method::rk4, 0.0)->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK_CAPTURE(BM_MassSpringFlag, symplectic_euler_wind, Method::symplectic_euler, 0.0, true)->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK_CAPTURE(BM_MassSpringFlag, symplectic_euler_provot10, Method::symplectic_euler, 0.1)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
BENCHMARK(BM_MassSpringForces)->Arg(1)->Arg(2)->UseRealTime();
