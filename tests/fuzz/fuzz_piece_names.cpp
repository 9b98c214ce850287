// libFuzzer target for the piece-role reader (pattern/roles.hpp): any byte
// string as a piece name, category, annotation and style — valid UTF-8 or not,
// Cyrillic, accents, truncated sequences — gives a role and never crashes,
// hangs or reads out of bounds. The input is split at its first three 0x1F bytes.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_piece_names tests/fuzz/corpus/names
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "vgd/pattern/roles.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  std::string_view part[4];
  std::size_t start = 0;
  for (int k = 0; k < 4; ++k) {
    const std::size_t end = k < 3 ? all.find('\x1f', start) : std::string_view::npos;
    part[k] = all.substr(std::min(start, all.size()),
                         end == std::string_view::npos ? std::string_view::npos : end - start);
    start = end == std::string_view::npos ? all.size() : end + 1;
  }
  const vgd::pattern::RoleGuess g = vgd::pattern::piece_role(part[0], part[1], part[2], part[3]);
  (void)vgd::pattern::role_name(g.role);
  (void)vgd::pattern::fold_name(all);
  return 0;
}
