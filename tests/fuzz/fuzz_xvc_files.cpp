// libFuzzer target for XVC documents (docs/xvc.md): any byte string must load
// (libxml2 deciding what is well-formed, tinyxml2 building the tree), pass
// vgd's rules and become a style, or fail with vgd::Error — never crash, hang
// or expand an entity. Every diagnostic it yields is printable text.
// Seeds: tests/fuzz/corpus/xvc (regressions, broken documents) plus the
// shipped garments and materials (data/garments, data/materials).
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_xvc_files tests/fuzz/corpus/xvc data/garments data/materials
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"
#include "vgd/xvc/validate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const vgd::xvc::Document doc = vgd::xvc::load_string(text, "fuzz.xvc");
    const vgd::Diagnostics found = vgd::xvc::check(doc);
    for (const auto& d : found.items())
      if (!vgd::is_utf8(d.message) || !vgd::is_utf8(d.entity)) __builtin_trap();  // printable, always
    const vgd::pattern::Style style = vgd::xvc::to_style(doc);
    for (const auto& piece : style.pieces)
      for (const auto& p : piece.boundary)
        if (!p.p.allFinite()) __builtin_trap();  // a coordinate that is not finite is refused, never passed on
    (void)vgd::xvc::save_string(doc);
  } catch (const vgd::Error& e) {
    if (!vgd::is_utf8(e.what())) __builtin_trap();
  }
  return 0;
}
