// The implicit integrators on the seed's 30 × 30 flag (seed 000 §4.1: the
// Garment PROTO's mass-spring constants, 0.1 kg particles, gravity, viscosity
// 0.2 N·s/m, two corners of the staff side pinned), released flat: one
// simulated second (30 frames) per iteration, from the start.
// Implicit Euler (Baraff–Witkin, one Newton step, PCG) at 1/30 s and 1/120 s;
// BDF (CVODE) at rtol 1e-3 and 1e-5, max order 2 and 5, KLU and GMRES.
// Run: build/tests/bench/vgd_bench --benchmark_filter=Implicit
#include <benchmark/benchmark.h>
#include <omp.h>

#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/integrator.hpp"

namespace {

using namespace vgd::sim;

constexpr int kSide = 30;
constexpr double kFps = 30.0, kSeconds = 1.0;

System flag() {
  Model m = make_grid(kSide, kSide, 1.0 / (kSide - 1), 1.0 / (kSide - 1), Vec3::Zero(), Vec3::UnitX(),
                      -Vec3::UnitY(), 0.1);
  MassSpringOptions opt;
  opt.fixed = {0, (kSide - 1) * kSide};
  std::vector<std::unique_ptr<Effect>> effects;
  effects.push_back(make_mass_spring(m, {MassSpringMaterial{}}, opt));
  effects.push_back(make_gravity({}));
  effects.push_back(make_viscosity({0.2, 0.0}));
  effects.push_back(make_pins(m, {opt.fixed}));
  return System(std::move(m), std::move(effects));
}

// Simulates kSeconds frame by frame; reports wall-clock steps per second and,
// per simulated second, steps, right-hand sides (force evaluations), Jacobians
// and convergence failures (implicit Euler: steps retried as two half steps,
// not counted as steps; BDF: CVODE's nonlinear convergence failures), and
// linear iterations per Newton iteration (PCG or GMRES; 0 for KLU).
void run_flag(benchmark::State& state, const IntegratorSettings& settings) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);  // the integrators are single-threaded; so are the forces here
  IntegratorStats total;
  double sag = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    System sys = flag();
    auto integ = make_integrator(settings);
    State s = initial_state(sys.model());
    state.ResumeTiming();
    integ->prepare(sys, s);
    for (int k = 1; k <= static_cast<int>(kFps * kSeconds); ++k) integ->advance(sys, s, k / kFps);
    benchmark::DoNotOptimize(s.x.data());
    const auto st = integ->stats();
    total.steps += st.steps;
    total.rhs_evaluations += st.rhs_evaluations;
    total.jacobian_evaluations += st.jacobian_evaluations;
    total.linear_iterations += st.linear_iterations;
    total.newton_iterations += st.newton_iterations;
    total.convergence_failures += st.convergence_failures;
    sag = -s.x.segment<3>(3 * (kSide * kSide - 1)).y();  // the free bottom corner, m below the staff
  }
  const double sim_s = kSeconds * static_cast<double>(state.iterations());
  state.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(total.steps), benchmark::Counter::kIsRate);
  state.counters["steps_per_sim_s"] = static_cast<double>(total.steps) / sim_s;
  state.counters["rhs_per_sim_s"] = static_cast<double>(total.rhs_evaluations) / sim_s;
  state.counters["jac_per_sim_s"] = static_cast<double>(total.jacobian_evaluations) / sim_s;
  state.counters["lin_iter_per_step"] =
      static_cast<double>(total.linear_iterations) / std::max(1.0, static_cast<double>(total.newton_iterations));
  state.counters["conv_fail_per_sim_s"] = static_cast<double>(total.convergence_failures) / sim_s;
  state.counters["corner_drop_m"] = sag;
  omp_set_num_threads(saved);
}

void BM_ImplicitEulerFlag(benchmark::State& state, double h) {
  IntegratorSettings st;
  st.method = Method::implicit_euler;
  st.step = h;
  run_flag(state, st);
}

void BM_ImplicitBdfFlag(benchmark::State& state, double rtol, int max_order, bool krylov) {
  IntegratorSettings st;
  st.method = Method::bdf;
  st.rtol = rtol;
  st.atol = rtol * 1e-2;  // 1 m flag: absolute errors of rtol cm (m, m/s)
  st.max_order = max_order;
  st.krylov = krylov;
  run_flag(state, st);
}

}  // namespace

BENCHMARK_CAPTURE(BM_ImplicitEulerFlag, h_1_30, 1.0 / 30)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_ImplicitEulerFlag, h_1_120, 1.0 / 120)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_ImplicitBdfFlag, rtol_1e3_order2_klu, 1e-3, 2, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ImplicitBdfFlag, rtol_1e5_order2_klu, 1e-5, 2, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ImplicitBdfFlag, rtol_1e3_order5_klu, 1e-3, 5, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ImplicitBdfFlag, rtol_1e5_order5_klu, 1e-5, 5, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ImplicitBdfFlag, rtol_1e3_order2_gmres, 1e-3, 2, true)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ImplicitBdfFlag, rtol_1e5_order2_gmres, 1e-5, 2, true)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ImplicitBdfFlag, rtol_1e3_order5_gmres, 1e-3, 5, true)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ImplicitBdfFlag, rtol_1e5_order5_gmres, 1e-5, 5, true)->Unit(benchmark::kMillisecond)->Iterations(1);
