// Import speed on the largest shared file (mirrored.DXF: 255 blocks, 706 kB).
// Run: build/tests/bench/vgd_bench --benchmark_filter=Import
#include <benchmark/benchmark.h>

#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/dxf/import.hpp"

namespace {

void BM_ImportFile(benchmark::State& state, const char* name) {
  const auto path = vgd::test::shared_dxf(name);
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("shared data absent");
    return;
  }
  for (auto _ : state) {
    auto r = vgd::dxf::import_file(path);
    benchmark::DoNotOptimize(r);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
}

void BM_ImportFromMemory(benchmark::State& state) {
  const auto path = vgd::test::shared_dxf("mirrored.DXF");
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("shared data absent");
    return;
  }
  const std::string text = vgd::read_file(path);
  for (auto _ : state) {
    auto r = vgd::dxf::import_string(text, "mirrored.DXF");
    benchmark::DoNotOptimize(r);
  }
}

}  // namespace

BENCHMARK_CAPTURE(BM_ImportFile, mirrored, "mirrored.DXF")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ImportFile, GLX4802S19_ASTM, "GLX4802S19_ASTM.DXF")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ImportFromMemory)->Unit(benchmark::kMillisecond);
