// libFuzzer target for the trajectory readers: .trj (docs/formats/trj.md) and
// .wvt (docs/formats/wvt.md). Any byte string must read or fail with
// vgd::Error — never crash, hang or read out of bounds. The first byte picks
// the reader (bit 0: .trj or .wvt), so one corpus covers both; bit 1 has the
// chunk checksums recomputed first, so mutations reach the parsers behind them.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_trj_files tests/fuzz/corpus/trj
#include <cstddef>
#include <cstdint>
#include <string>

#include "vgd/core/diagnostics.hpp"
#include "vgd/io/trj/binary.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/io/wvt/wvt.hpp"

namespace {

// Inputs declaring more than this many coordinates × frames are only checked
// up to their header: a compressed file may legitimately declare gigabytes.
constexpr long long kMaxValues = 1 << 22;

// Both formats: a header whose u32 at byte 12 is its size, then chunks of
// tag[4], crc32, u64 length, payload. Rewrites every whole chunk's CRC.
void fix_checksums(std::string& bytes) {
  namespace bin = vgd::io::binary;
  if (bytes.size() < 16) return;
  std::uint64_t pos = bin::get_u32(bytes.data() + 12);
  while (pos + 16 <= bytes.size()) {
    const std::uint64_t len = bin::get_u64(bytes.data() + pos + 8);
    if (len > bytes.size() - pos - 16) return;
    const std::uint32_t crc = bin::crc32(bytes.data() + pos + 16, len);
    for (int k = 0; k < 4; ++k) bytes[pos + 4 + k] = static_cast<char>((crc >> (8 * k)) & 0xFF);
    pos += 16 + len;
  }
}

void read_trj(std::string bytes) {
  const auto r = vgd::io::trj::TrjReader::from_bytes(std::move(bytes), "fuzz.trj");
  const int n = r.num_particles();
  for (const auto& t : r.topology().triangles)
    for (int c : t)
      if (c < 0 || c >= n) __builtin_trap();  // the reader checks every corner
  if (n <= kMaxValues) r.topology().representatives(r.frame_count());
  for (int k = 0; k < r.frame_count(); ++k) {
    try {
      if (r.positions(k).size() != 3 * static_cast<std::size_t>(n)) __builtin_trap();
    } catch (const vgd::Error&) {
      // A frame that fails its checksum: named, and the others still read.
    }
  }
}

void read_wvt(const std::string& bytes) {
  const auto info = vgd::io::wvt::read_info(bytes, "fuzz.wvt");
  if (3ll * info.num_particles * info.frame_count > kMaxValues || info.num_particles > kMaxValues) return;
  const auto t = vgd::io::wvt::decode(bytes, "fuzz.wvt");
  if (t.frame_count() != info.frame_count || t.times.size() != t.frames.size()) __builtin_trap();
  for (const auto& f : t.frames)
    if (f.size() != 3 * static_cast<std::size_t>(info.num_particles)) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] & 2) fix_checksums(bytes);
  try {
    if (data[0] % 2 == 0)
      read_trj(std::move(bytes));
    else
      read_wvt(bytes);
  } catch (const vgd::Error&) {
    // Rejected with a message: fine.
  }
  return 0;
}
