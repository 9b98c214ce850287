// Meshing speed: the sample size of real files at 1 cm spacing, 25° minimum angle.
// Run: build/tests/bench/vgd_bench --benchmark_filter=Mesh
#include <benchmark/benchmark.h>

#include "support/test_paths.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/mesh/mesh.hpp"

namespace {

void BM_MeshSampleSize(benchmark::State& state, const char* name) {
  const auto path = vgd::test::shared_dxf(name);
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("shared data absent");
    return;
  }
  const auto style = vgd::dxf::import_file(path).style;
  vgd::mesh::MeshOptions o;  // 1 cm spacing, 25°
  std::size_t nodes = 0, triangles = 0, pieces = 0;
  for (auto _ : state) {
    vgd::Diagnostics d;
    auto meshes = vgd::mesh::mesh_style(style, "", o, d);
    nodes = triangles = 0;
    pieces = meshes.size();
    for (const auto& m : meshes) {
      nodes += m.nodes.size();
      triangles += m.triangles.size();
    }
    benchmark::DoNotOptimize(meshes.data());
  }
  state.counters["pieces"] = static_cast<double>(pieces);
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["triangles"] = static_cast<double>(triangles);
}

}  // namespace

BENCHMARK_CAPTURE(BM_MeshSampleSize, mirrored, "mirrored.DXF")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MeshSampleSize, MEN_CLASSIC_TEE, "MEN_CLASSIC_TEE.DXF")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MeshSampleSize, Valentina_Trousers, "Valentina_Trousers_ASTM_R12.dxf")->Unit(benchmark::kMillisecond);
