// libFuzzer target for the mannequin cache's file reader
// (body::read_mannequin_cache_file, docs/avatar.md "The cache"). Any byte
// string must read back as a surface or as nothing: never crash, hang or read
// out of bounds. Bit 0 of the first byte chooses how the rest is used: as the
// file's bytes as they stand, or as a surface (counts, coordinates, corners)
// written whole by the writer and then changed at one byte the input names,
// so that mutations reach what lies behind the header and the checksum.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_mannequin_cache tests/fuzz/corpus/mannequin
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "vgd/body/mannequin.hpp"

namespace {

constexpr std::string_view kKey = "fuzz\n";

void check(const std::string& bytes) {
  const auto s = vgd::body::read_mannequin_cache_file(bytes, kKey);
  if (!s) return;
  // What reads back is a surface whose every corner is one of its vertices.
  for (const auto& t : s->triangles)
    for (const int c : t)
      if (c < 0 || c >= s->num_vertices()) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string rest(reinterpret_cast<const char*>(data + 1), size - 1);
  if ((data[0] & 1) == 0) {
    check(rest);
    return 0;
  }
  // A surface from the bytes: a vertex count (0-63), then coordinates and corners.
  std::string_view in(rest);
  vgd::mesh::SurfaceMesh s;
  const int nv = in.empty() ? 0 : static_cast<unsigned char>(in[0]) % 64;
  if (!in.empty()) in.remove_prefix(1);
  for (int i = 0; i < nv && in.size() >= 24; ++i) {
    double v[3];
    std::memcpy(v, in.data(), sizeof v);
    in.remove_prefix(sizeof v);
    s.vertices.push_back({v[0], v[1], v[2]});
  }
  while (in.size() >= 4 && !s.vertices.empty()) {
    const int n = static_cast<int>(s.vertices.size());
    s.triangles.push_back({static_cast<unsigned char>(in[0]) % n, static_cast<unsigned char>(in[1]) % n,
                           static_cast<unsigned char>(in[2]) % n});
    in.remove_prefix(3);
  }
  std::string bytes = vgd::body::mannequin_cache_file(s, kKey);
  check(bytes);
  if (!bytes.empty()) {
    const std::size_t at = (static_cast<std::size_t>(data[0]) * 131u + size) % bytes.size();
    bytes[at] = static_cast<char>(bytes[at] ^ (data[0] | 1));
    check(bytes);
  }
  return 0;
}
