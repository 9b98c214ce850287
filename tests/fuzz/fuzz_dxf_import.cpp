// libFuzzer target for the DXF importer: any byte string must either import or
// fail with vgd::Error — never crash, hang or touch memory it does not own.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_dxf_import tests/fuzz/corpus/dxf
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vgd/io/dxf/import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    vgd::dxf::ImportOptions opts;
    opts.unfold_mirrored = size % 2 == 1;  // exercise unfolding on half of the inputs
    opts.join_per_side = size % 4 >= 2;    // and joining pieces written per side on half, across both
    const auto result = vgd::dxf::import_string(text, "fuzz.dxf", opts);
    // Invariants of a successful import.
    for (const auto& p : result.style.pieces)
      if (p.boundary.size() < 3) __builtin_trap();
  } catch (const vgd::Error&) {
    // Rejected with a message: fine.
  }
  return 0;
}
