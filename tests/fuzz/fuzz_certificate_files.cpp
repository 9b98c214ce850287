// libFuzzer target for certificate.json as vgd reads it back
// (dress::certificate_from_json: the studio reads the server's) and for
// contact-pressure.json (dress::contact_pressure_from_json: vgd render --map
// pressure). Any byte
// string must give a certificate that writes back to JSON, or fail with
// vgd::Error — never crash.
// Seeds: tests/fuzz/corpus/certificate (a catalogue item's certificate, a
// contact-pressure map).
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_certificate_files tests/fuzz/corpus/certificate
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vgd/core/diagnostics.hpp"
#include "vgd/dress/certificate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const auto c = vgd::dress::certificate_from_json(std::string_view(reinterpret_cast<const char*>(data), size),
                                                     "fuzz.json");
    if (vgd::dress::to_json(c).empty()) __builtin_trap();
  } catch (const vgd::Error&) {
    // Refused with a message: fine.
  }
  try {
    for (double p : vgd::dress::contact_pressure_from_json(
             std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json"))
      if (!(p >= 0.0)) __builtin_trap();
  } catch (const vgd::Error&) {
  }
  return 0;
}
