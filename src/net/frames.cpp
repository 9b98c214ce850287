// Live frame messages (frames.hpp).
#include "vgd/net/frames.hpp"

#include <cstring>
#include <nlohmann/json.hpp>

#include "vgd/core/diagnostics.hpp"
#include "vgd/io/trj/binary.hpp"

namespace vgd::net {
namespace {

template <class T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // little-endian hosts (x86-64, aarch64), as .trj
  out.append(b, sizeof(T));
}

template <class T>
T get(const std::string& in, std::size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  return v;
}

}  // namespace

std::string topology_message(const io::trj::Topology& t) {
  nlohmann::json j = {{"type", "topology"}, {"particles", t.num_particles}, {"pieces", t.pieces},
                      {"triangle_piece", t.triangle_piece}};
  std::vector<int> tri;
  tri.reserve(t.triangles.size() * 3);
  for (const auto& f : t.triangles) tri.insert(tri.end(), f.begin(), f.end());
  j["triangles"] = tri;
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string frame_message(std::uint32_t seq, double t, const std::vector<float>& x) {
  std::string out = "VGDF";
  put<std::uint32_t>(out, seq);
  put<double>(out, t);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(x.size()));
  put<std::uint32_t>(out, io::binary::crc32(x.data(), x.size() * sizeof(float)));
  out.append(reinterpret_cast<const char*>(x.data()), x.size() * sizeof(float));
  return out;
}

FrameMessage parse_frame_message(const std::string& in) {
  constexpr std::size_t kHeader = 24;
  if (in.size() < kHeader || in.compare(0, 4, "VGDF") != 0) throw Error("frame", "", "not a VGDF frame message");
  FrameMessage m;
  m.seq = get<std::uint32_t>(in, 4);
  m.t = get<double>(in, 8);
  const auto count = get<std::uint32_t>(in, 16);
  const auto crc = get<std::uint32_t>(in, 20);
  if (in.size() != kHeader + std::size_t{count} * sizeof(float))
    throw Error("frame", "", "length " + std::to_string(in.size()) + " does not hold " + std::to_string(count) + " floats");
  m.positions.resize(count);
  std::memcpy(m.positions.data(), in.data() + kHeader, count * sizeof(float));
  m.checksum_ok = io::binary::crc32(m.positions.data(), count * sizeof(float)) == crc;
  return m;
}

}  // namespace vgd::net
