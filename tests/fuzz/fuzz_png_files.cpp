// libFuzzer target for PNG images (render::decode_png: vgd compare, textures):
// any byte string must decode to an image of the size its header states, or
// fail with vgd::Error — never crash, and never allocate for a header that
// claims more pixels than the limit (here 2^20, so the fuzzer runs fast).
// Seeds: tests/fuzz/corpus/png (tiny images of every colour type, a header
// claiming 10^10 pixels) plus data/textures.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_png_files tests/fuzz/corpus/png data/textures
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vgd/core/diagnostics.hpp"
#include "vgd/render/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  constexpr std::uint64_t kPixels = 1u << 20;
  try {
    const auto image = vgd::render::decode_png(std::string_view(reinterpret_cast<const char*>(data), size),
                                               "fuzz.png", kPixels);
    const auto pixels = static_cast<std::uint64_t>(image.width) * static_cast<std::uint64_t>(image.height);
    if (image.width <= 0 || image.height <= 0 || pixels > kPixels) __builtin_trap();
    if (image.rgba.size() != 4 * pixels) __builtin_trap();
  } catch (const vgd::Error&) {
    // Refused with a message: fine.
  }
  return 0;
}
