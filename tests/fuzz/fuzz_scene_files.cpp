// libFuzzer target for vgd's own text formats read by the dressing stage: scene
// files (JSON, docs/scene.md) and seam files (JSON, docs/xvc.md). Any byte
// string must parse or fail with vgd::Error — never crash or hang. The first
// byte picks the parser (even: scene, odd: seam file), so one corpus covers both.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_scene_files tests/fuzz/corpus/scene
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vgd/core/diagnostics.hpp"
#include "vgd/scene/json.hpp"
#include "vgd/xvc/seams.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    if (data[0] % 2 == 0) {
      const auto def = vgd::scene::parse_scene(text, "fuzz.json");
      if (def.cloth.empty()) __builtin_trap();  // validate() refuses a scene without cloth
    } else {
      for (const auto& plan : vgd::xvc::parse_seam_plans(text, "fuzz.seams.json"))
        if (plan.hems.size() < 2) __builtin_trap();  // a seam sews at least two hems
    }
  } catch (const vgd::Error&) {
    // Rejected with a message: fine.
  }
  return 0;
}
