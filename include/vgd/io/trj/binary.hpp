#pragma once
// Little-endian byte packing and CRC-32 shared by the .trj and .wvt formats
// (docs/formats/trj.md, docs/formats/wvt.md). Every multi-byte number in both
// files is little-endian whatever the machine; floats are IEEE 754.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace vgd::io::binary {

// CRC-32 (ISO-HDLC, the zlib/PNG polynomial 0xEDB88320) of `data`,
// continuing from `crc` (0 to start).
std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc = 0);
inline std::uint32_t crc32(std::string_view s, std::uint32_t crc = 0) { return crc32(s.data(), s.size(), crc); }

// Appends numbers to a byte string.
inline void put_u16(std::string& out, std::uint16_t v) {
  out.push_back(static_cast<char>(v & 0xFF));
  out.push_back(static_cast<char>(v >> 8));
}
inline void put_u32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}
inline void put_u64(std::string& out, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}
inline void put_f32(std::string& out, float v) { put_u32(out, std::bit_cast<std::uint32_t>(v)); }
inline void put_f64(std::string& out, double v) { put_u64(out, std::bit_cast<std::uint64_t>(v)); }

// Reads numbers at a byte pointer (the caller checked the bounds).
inline std::uint16_t get_u16(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint16_t>(b[0] | (b[1] << 8));
}
inline std::uint32_t get_u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint32_t>(b[0]) | (static_cast<std::uint32_t>(b[1]) << 8) |
         (static_cast<std::uint32_t>(b[2]) << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
}
inline std::uint64_t get_u64(const char* p) {
  return static_cast<std::uint64_t>(get_u32(p)) | (static_cast<std::uint64_t>(get_u32(p + 4)) << 32);
}
inline float get_f32(const char* p) { return std::bit_cast<float>(get_u32(p)); }
inline double get_f64(const char* p) { return std::bit_cast<double>(get_u64(p)); }

// A bounds-checked cursor over a byte string: every get fails (returns false)
// instead of reading past the end, so a reader can name what was missing.
class Cursor {
 public:
  explicit Cursor(std::string_view bytes) : s_(bytes) {}
  std::size_t left() const { return s_.size() - pos_; }
  std::size_t pos() const { return pos_; }
  bool u32(std::uint32_t& v) { return take(4) ? (v = get_u32(p_), true) : false; }
  bool u64(std::uint64_t& v) { return take(8) ? (v = get_u64(p_), true) : false; }
  bool f64(double& v) { return take(8) ? (v = get_f64(p_), true) : false; }
  bool bytes(std::size_t n, std::string_view& v) { return take(n) ? (v = std::string_view(p_, n), true) : false; }

 private:
  bool take(std::size_t n) {
    if (left() < n) return false;
    p_ = s_.data() + pos_;
    pos_ += n;
    return true;
  }
  std::string_view s_;
  std::size_t pos_ = 0;
  const char* p_ = nullptr;
};

}  // namespace vgd::io::binary
