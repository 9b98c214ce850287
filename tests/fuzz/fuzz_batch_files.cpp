// libFuzzer target for the catalogue runs' files (docs/batch.md): a
// catalogue.json and an item's manifest.json. Any byte string must be read or
// refused with vgd::Error — never crash or hang. The first byte picks the
// reader (even: catalogue, odd: manifest). The catalogue is written into a
// folder holding a style (s.xvc), a fabric (f.xvc) and a body (b.obj), so
// inputs naming them get past the file checks to the expansion.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_batch_files tests/fuzz/corpus/batch
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "vgd/batch/catalogue.hpp"
#include "vgd/batch/item.hpp"
#include "vgd/core/diagnostics.hpp"

namespace {

std::filesystem::path folder() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("vgd-fuzz-batch-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::ofstream(d / "s.xvc") << "<XVC/>\n";
    std::ofstream(d / "f.xvc") << "<XVC/>\n";
    std::ofstream(d / "b.obj") << "v 0 0 0\n";
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    if (data[0] % 2 == 0) {
      const auto file = folder() / "catalogue.json";
      std::ofstream(file, std::ios::binary | std::ios::trunc).write(text.data(), static_cast<std::streamsize>(text.size()));
      const auto c = vgd::batch::load_catalogue(file);
      std::size_t expected = 0;
      for (const auto& s : c.styles) expected += s.sizes.size() * c.fabrics.size() * c.avatars.size();
      if (c.items.size() != expected) __builtin_trap();  // every style x size x fabric x body, once
      for (std::size_t i = 0; i < c.items.size(); ++i)
        if (c.items[i].index != static_cast<int>(i) || c.items[i].id.size() != 16) __builtin_trap();
    } else {
      const auto m = vgd::batch::manifest_from_json(std::string(text), "fuzz.manifest.json");
      if (m.state != "passed" && m.state != "failed") __builtin_trap();
      (void)vgd::batch::to_json(m);
    }
  } catch (const vgd::Error&) {
    // Refused with a message: fine.
  }
  return 0;
}
