// Speed of the strain-rosette membrane and the bending model on the seed's
// 30 × 30 flag (make_grid: 900 particles, 1682 triangles, 2 523 hinges):
// particle-steps per second for symplectic Euler, midpoint and RK4 on 1 and 2
// threads (target: ≥ 5e6 particle-steps/s for symplectic Euler on one
// core), and the cost of one force evaluation of each effect.
// Run: build/tests/bench/vgd_bench --benchmark_filter='Rosette|Bending|Flag'
#include <benchmark/benchmark.h>
#include <omp.h>

#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/bending.hpp"
#include "vgd/sim/effects/strain_rosette.hpp"
#include "vgd/sim/integrator.hpp"

namespace {

using namespace vgd::sim;

// The seed's flag: 30 × 30 particles 2 cm apart, hanging in the x–y plane
// (+Y up) from its two upper corners, 200 g/m² (mechanics.md's worked fabric).
Model flag() {
  Model m = make_grid(30, 30, 0.02, 0.02, Vec3(0, 0.58, 0), Vec3::UnitX(), -Vec3::UnitY(), 1.0);
  const OrthotropicMaterial fabric;
  m.mass = lump_masses(m.uv, m.triangles, fabric.density);
  return m;
}

std::vector<std::unique_ptr<Effect>> flag_effects(const Model& m) {
  const OrthotropicMaterial fabric;
  std::vector<std::unique_ptr<Effect>> e;
  e.push_back(make_gravity({}));
  e.push_back(make_viscosity({0.0, 0.5}));
  e.push_back(make_pins(m, {{0, 29}}));
  e.push_back(make_strain_rosette(m, {fabric}));
  e.push_back(make_bending(m, {fabric}));
  return e;
}

// Restores the OpenMP thread count when the benchmark ends.
struct Threads {
  int before;
  explicit Threads(int n) : before(omp_get_max_threads()) { omp_set_num_threads(n); }
  ~Threads() { omp_set_num_threads(before); }
};

// state.range(0): method; state.range(1): threads. Each iteration advances 200
// steps of 0.9 × the method's stability limit, from the hanging flag onwards.
void BM_FlagRosetteBending(benchmark::State& state) {
  const Method method = static_cast<Method>(state.range(0));
  Threads threads(static_cast<int>(state.range(1)));
  System sys(flag(), flag_effects(flag()));
  IntegratorSettings st;
  st.method = method;
  st.step = 0.9 * stability_limit(method, sys.stiffness());
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  const int steps = 200;
  long total = 0;
  for (auto _ : state) {
    integ->advance(sys, s, s.t + steps * st.step);
    total += steps;
  }
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(static_cast<double>(total) * sys.model().num_particles(), benchmark::Counter::kIsRate);
  state.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(total), benchmark::Counter::kIsRate);
  state.counters["step_us"] = st.step * 1e6;
  state.SetLabel(std::string(to_string(method)) + ", " + std::to_string(state.range(1)) + " thread(s)");
}
BENCHMARK(BM_FlagRosetteBending)
    ->ArgsProduct({{static_cast<long>(Method::symplectic_euler), static_cast<long>(Method::midpoint),
                    static_cast<long>(Method::rk4)},
                   {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// One force evaluation of one effect on the flag, deformed; state.range(0): threads.
template <class Make>
void force_bench(benchmark::State& state, Make make) {
  Threads threads(static_cast<int>(state.range(0)));
  const Model m = flag();
  auto effect = make(m);
  VecX x = m.x0;
  for (int i = 0; i < m.num_particles(); ++i) x[3 * i + 2] = 0.01 * std::sin(7.0 * m.uv[i].x() + 3.0 * m.uv[i].y());
  VecX f = VecX::Zero(m.num_dofs());
  for (auto _ : state) {
    f.setZero();
    effect->add_forces({m, 0.0, x, m.v0}, f);
    benchmark::DoNotOptimize(f.data());
  }
  state.counters["elements_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(m.triangles.size()), benchmark::Counter::kIsRate);
}
void BM_RosetteForces(benchmark::State& state) {
  force_bench(state, [](const Model& m) { return make_strain_rosette(m, {OrthotropicMaterial{}}); });
}
void BM_BendingForces(benchmark::State& state) {
  force_bench(state, [](const Model& m) { return make_bending(m, {OrthotropicMaterial{}}); });
}
BENCHMARK(BM_RosetteForces)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BendingForces)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

// The exact Jacobians (implicit integrators assemble them once per step).
void BM_FlagJacobian(benchmark::State& state) {
  const Model m = flag();
  auto rosette = make_strain_rosette(m, {OrthotropicMaterial{}});
  auto bending = make_bending(m, {OrthotropicMaterial{}});
  VecX x = m.x0;
  for (int i = 0; i < m.num_particles(); ++i) x[3 * i + 2] = 0.01 * std::sin(7.0 * m.uv[i].x() + 3.0 * m.uv[i].y());
  Triplets jx, jv;
  for (auto _ : state) {
    jx.clear();
    rosette->add_jacobian({m, 0.0, x, m.v0}, jx, jv);
    bending->add_jacobian({m, 0.0, x, m.v0}, jx, jv);
    benchmark::DoNotOptimize(jx.data());
  }
  state.counters["triplets"] = static_cast<double>(jx.size());
}
BENCHMARK(BM_FlagJacobian)->Unit(benchmark::kMillisecond);

}  // namespace
