// Collision queries (docs/collisions.md): the signed distance grid against the
// exact BVH on a sphere of 5 000 and 20 000 triangles and a body-sized
// ellipsoid: build time, cost per query, error. And the effects' cost per
// step on the benchmark's cloth (71 × 71 = 5 041 particles).
// Target: well under 1 µs per particle per step.
// Run: build/tests/bench/vgd_bench --benchmark_filter=Collision
#include <benchmark/benchmark.h>

#include <random>

#include "sim/surfaces.hpp"
#include "vgd/sim/effects/body_collision.hpp"
#include "vgd/sim/effects/self_collision.hpp"
#include "vgd/sim/sdf.hpp"

namespace {

using namespace vgd::sim;

// 0: sphere r 0.3 m, 4 992 triangles; 1: the same, 19 968; 2: a body-sized
// ellipsoid (0.4 × 1.7 × 0.3 m), 19 968.
vgd::mesh::SurfaceMesh collider(int which) {
  if (which == 0) return test::uv_sphere(0.3, 64, 40);
  auto m = test::uv_sphere(0.3, 128, 79);
  if (which == 2)
    for (auto& v : m.vertices) v = Vec3(v.x() * 0.2 / 0.3, v.y() * 0.85 / 0.3, v.z() * 0.15 / 0.3);
  return m;
}

// n points within ±band of the surface (by the exact distance), seeded.
std::vector<Vec3> near_points(const vgd::mesh::SurfaceMesh& m, int n, double band) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> tri(0, m.num_triangles() - 1);
  std::uniform_real_distribution<double> u(0, 1), off(-band, band);
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    const auto& t = m.triangles[tri(rng)];
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Vec3 &p = m.vertices[t[0]], &q = m.vertices[t[1]], &r = m.vertices[t[2]];
    const Vec3 nrm = (q - p).cross(r - p).normalized();
    out.push_back(p + a * (q - p) + b * (r - p) + off(rng) * nrm);
  }
  return out;
}

void BM_CollisionSdfBuild(benchmark::State& state) {
  const auto m = collider(static_cast<int>(state.range(0)));
  const SdfOptions o{state.range(1) * 1e-4, state.range(2) * 1e-3};  // spacing in 0.1 mm, band in mm
  std::size_t bytes = 0;
  for (auto _ : state) {
    SignedDistanceGrid g(m, o);
    bytes = g.memory_bytes();
    benchmark::DoNotOptimize(&g);
  }
  // Accuracy against the exact distance (BVH) within ±1 cm of the surface.
  SignedDistanceGrid g(m, o);
  TriangleBvh bvh(m);
  double worst = 0.0;
  for (const Vec3& p : near_points(m, 20000, 0.01)) worst = std::max(worst, std::abs(g.distance(p) - bvh.closest(p).distance));
  state.counters["triangles"] = m.num_triangles();
  state.counters["MB"] = bytes / 1e6;
  state.counters["max_error_mm"] = worst * 1e3;
}
BENCHMARK(BM_CollisionSdfBuild)
    ->ArgNames({"mesh", "spacing_0.1mm", "band_mm"})
    ->Args({0, 50, 20})->Args({0, 50, 10})->Args({0, 25, 10})->Args({1, 50, 20})->Args({2, 50, 20})->Args({2, 50, 10})
    ->Unit(benchmark::kMillisecond);

void BM_CollisionBvhBuild(benchmark::State& state) {
  const auto m = collider(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    TriangleBvh b(m);
    benchmark::DoNotOptimize(&b);
  }
  state.counters["triangles"] = m.num_triangles();
}
BENCHMARK(BM_CollisionBvhBuild)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_CollisionSdfQuery(benchmark::State& state) {
  const auto m = collider(static_cast<int>(state.range(0)));
  const SignedDistanceGrid g(m, {0.005, 0.02});
  const auto pts = near_points(m, 5041, 0.01);
  for (auto _ : state) {
    double s = 0;
    Vec3 grad;
    for (const Vec3& p : pts) s += g.sample(p, grad);
    benchmark::DoNotOptimize(s);
  }
  state.counters["ns_per_query"] =
      benchmark::Counter(static_cast<double>(pts.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CollisionSdfQuery)->Arg(0)->Arg(1)->Arg(2);

void BM_CollisionBvhQuery(benchmark::State& state) {
  const auto m = collider(static_cast<int>(state.range(0)));
  const TriangleBvh b(m);
  const auto pts = near_points(m, 5041, 0.01);
  for (auto _ : state) {
    double s = 0;
    for (const Vec3& p : pts) s += b.closest(p).distance;
    benchmark::DoNotOptimize(s);
  }
  state.counters["ns_per_query"] =
      benchmark::Counter(static_cast<double>(pts.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CollisionBvhQuery)->Arg(0)->Arg(1)->Arg(2);

// The benchmark's cloth: 71 × 71 particles, 1 cm apart, laid over the top of
// the 0.3 m sphere (projected to 1 mm inside the clearance: every particle in
// contact), one after_step (detection and Provot response) per iteration.
Model draped_cloth(double r) {
  constexpr int n = 71;
  Model m = make_grid(n, n, 0.01, 0.01, Vec3(-0.35, 0, -0.35), Vec3::UnitX(), Vec3::UnitZ(), 1e-4);
  for (int i = 0; i < m.num_particles(); ++i) {
    Vec3 p = at(m.x0, i);
    p.y() = 1.0;
    at(m.x0, i) = (r + 0.002) * p.normalized();
  }
  return m;
}

void BM_CollisionBodyStep(benchmark::State& state) {
  const Model m = draped_cloth(0.3);
  BodyCollisionDef def;
  def.body = collider(0);
  def.query = state.range(0) == 0 ? BodyQuery::grid : BodyQuery::exact;
  auto e = make_body_collision(m, def);
  State s = initial_state(m);
  VecX v = VecX::Constant(m.num_dofs(), -0.01);
  for (auto _ : state) {
    s.x = m.x0;
    s.v = v;
    s.t += 0.001;
    e->after_step(m, s);
    benchmark::DoNotOptimize(s.x.data());
  }
  state.counters["ns_per_particle"] = benchmark::Counter(static_cast<double>(m.num_particles()),
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["in_contact"] = body_collision_stats(*e).in_contact;
}
BENCHMARK(BM_CollisionBodyStep)->ArgName("exact")->Arg(0)->Arg(1);

// Self-collision on the same cloth folded in two (the second half 3 mm over
// the first: every particle near a triangle): one force call and one after_step.
void BM_CollisionSelfStep(benchmark::State& state) {
  constexpr int n = 71;
  Model m = make_grid(n, n, 0.01, 0.01, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ(), 1e-4);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (i > n / 2) at(m.x0, j * n + i) = Vec3(0.7 - 0.01 * i, 0.003, 0.01 * j);  // folded back over
  SelfCollisionDef def;
  def.thickness = 0.004;
  auto e = make_self_collision(m, def);
  State s = initial_state(m);
  VecX f(m.num_dofs());
  for (auto _ : state) {
    s.x = m.x0;
    s.v.setZero();
    f.setZero();
    e->add_forces({m, 0.0, s.x, s.v}, f);
    e->after_step(m, s);
    benchmark::DoNotOptimize(s.x.data());
  }
  state.counters["ns_per_particle"] = benchmark::Counter(static_cast<double>(m.num_particles()),
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pairs"] = self_collision_stats(*e).pairs;
}
BENCHMARK(BM_CollisionSelfStep);

}  // namespace
