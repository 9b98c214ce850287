// libFuzzer target for the fabric lab's measurement CSV (docs/fabric-lab.md,
// lab::parse_measurements): any byte string must give measurements with
// finite values, angles of 0 to 90 degrees and at most the row limit, or fail
// with vgd::Error naming the line — never crash.
// Seeds: tests/fuzz/corpus/lab.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_lab_csv tests/fuzz/corpus/lab
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vgd/core/diagnostics.hpp"
#include "vgd/lab/fit.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  constexpr std::size_t kRows = 200;
  try {
    const auto ms = vgd::lab::parse_measurements(std::string_view(reinterpret_cast<const char*>(data), size),
                                                 "fuzz.csv", kRows);
    if (ms.empty() || ms.size() > kRows) __builtin_trap();
    for (const auto& m : ms) {
      if (!std::isfinite(m.value) || m.value < 0.0 || !std::isfinite(m.x) || m.x < 0.0) __builtin_trap();
      if (!(m.angle_deg >= 0.0 && m.angle_deg <= 90.0) && !std::isnan(m.angle_deg)) __builtin_trap();
      if (m.line < 1) __builtin_trap();
    }
  } catch (const vgd::Error&) {
    // Refused with a message: fine.
  }
  return 0;
}
