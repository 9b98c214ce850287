// The mannequin's surface kept between runs (mannequin_cache.hpp,
// docs/avatar.md "The cache").
//
// A file holds one surface: a text header (format, key) and then the vertex
// and triangle counts, the coordinates as IEEE doubles and the corners as
// 32-bit integers, little-endian as the machine writes them, and an FNV-1a
// checksum of everything before it. It is read back only when the header's
// key is the one asked for, the counts fit the file's size and the checksum
// matches: anything else is a file to replace.
#include "mannequin_cache.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

#include "vgd/core/file.hpp"

namespace vgd::body {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kMagic = "vgd mannequin surface 1\n";
constexpr std::size_t kMaxFiles = 64;  // surfaces kept at most (about 15 MB at 10 000 triangles)

std::atomic<long> meshings{0};

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 14695981039346656037ull) {
  for (const unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
bool get(std::string_view& in, T& v) {
  if (in.size() < sizeof v) return false;
  std::memcpy(&v, in.data(), sizeof v);
  in.remove_prefix(sizeof v);
  return true;
}

fs::path file_for(const std::string& key) {
  const fs::path dir = mannequin_cache_dir();
  if (dir.empty()) return {};
  char name[40];
  std::snprintf(name, sizeof name, "mannequin-%016llx.bin", static_cast<unsigned long long>(fnv1a(key)));
  return dir / name;
}

// A file the cache wrote: "mannequin-" and 16 hex digits ".bin", beginning
// with the format's first line.
bool is_cache_file(const fs::path& p) {
  const std::string name = p.filename().string();
  constexpr std::string_view prefix = "mannequin-", suffix = ".bin";
  if (name.size() != prefix.size() + 16 + suffix.size() || name.rfind(prefix, 0) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0 ||
      name.find_first_not_of("0123456789abcdef", prefix.size()) != prefix.size() + 16)
    return false;
  std::ifstream in(p, std::ios::binary);
  std::string head(kMagic.size(), '\0');
  return in.read(head.data(), static_cast<std::streamsize>(head.size())) && head == kMagic;
}

}  // namespace

fs::path mannequin_cache_dir() {
  if (const char* d = std::getenv("VGD_CACHE_DIR"); d && *d) {
    if (std::string_view(d) == "off") return {};
    return fs::path(d);
  }
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "vgd";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "vgd";
  return {};
}

long mannequin_meshings() { return meshings.load(); }

std::string mannequin_cache_file(const mesh::SurfaceMesh& surface, std::string_view key) {
  std::string out(kMagic);
  out += key;
  put(out, static_cast<std::uint64_t>(surface.vertices.size()));
  put(out, static_cast<std::uint64_t>(surface.triangles.size()));
  for (const auto& v : surface.vertices)
    for (int i = 0; i < 3; ++i) put(out, v[i]);
  for (const auto& t : surface.triangles)
    for (int i = 0; i < 3; ++i) put(out, static_cast<std::int32_t>(t[i]));
  put(out, fnv1a(out));
  return out;
}

std::optional<mesh::SurfaceMesh> read_mannequin_cache_file(std::string_view bytes, std::string_view key) {
  const std::string header = std::string(kMagic) + std::string(key);
  if (bytes.size() < header.size() + sizeof(std::uint64_t) || bytes.substr(0, header.size()) != header)
    return std::nullopt;
  const std::string_view body = bytes.substr(0, bytes.size() - sizeof(std::uint64_t));
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes.data() + body.size(), sizeof sum);
  if (sum != fnv1a(body)) return std::nullopt;
  std::string_view rest = body.substr(header.size());
  std::uint64_t nv = 0, nt = 0;
  constexpr std::uint64_t kVertex = 3 * sizeof(double), kTriangle = 3 * sizeof(std::int32_t);
  if (!get(rest, nv) || !get(rest, nt) || nv > rest.size() / kVertex || nt > rest.size() / kTriangle ||
      rest.size() != nv * kVertex + nt * kTriangle)
    return std::nullopt;
  mesh::SurfaceMesh s;
  s.vertices.resize(nv);
  for (auto& v : s.vertices)
    for (int i = 0; i < 3; ++i) {
      get(rest, v[i]);
      if (!std::isfinite(v[i])) return std::nullopt;
    }
  s.triangles.resize(nt);
  for (auto& t : s.triangles)
    for (int i = 0; i < 3; ++i) {
      std::int32_t c = 0;
      get(rest, c);
      if (c < 0 || static_cast<std::uint64_t>(c) >= nv) return std::nullopt;
      t[i] = c;
    }
  return s;
}

namespace detail {

void count_meshing() { ++meshings; }

std::string mannequin_cache_key(const BodyMeasurements& m, const MannequinOptions& o) {
  std::string k = "sex " + m.sex + "\n";
  for (const double v : {m.height, m.bust, m.under_bust, m.waist, m.hip, m.shoulder_width, m.neck, m.arm_length,
                         m.inseam})
    k += number(v) + " ";
  k += "\noptions " + std::to_string(o.target_triangles) + " " + number(o.facet_size) + " " +
       number(o.facet_distance) + " " + number(o.arm_angle_deg) + " " + number(o.arm_forward_deg) + " " +
       (o.calibrate ? "calibrated" : "estimated") + "\n";
  // The executable that meshes: another build may mesh otherwise.
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  struct stat st {};
  if (ec || ::stat(exe.c_str(), &st) != 0) return {};  // no identity: no cache
  k += "exe " + exe.string() + " " + std::to_string(st.st_size) + " " + std::to_string(st.st_mtim.tv_sec) + "." +
       std::to_string(st.st_mtim.tv_nsec) + "\n";
  return k;
}

std::optional<mesh::SurfaceMesh> read_cached_surface(const std::string& key) {
  if (key.empty()) return std::nullopt;
  const fs::path file = file_for(key);
  if (file.empty()) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return read_mannequin_cache_file(bytes, key);
}

void write_cached_surface(const std::string& key, const mesh::SurfaceMesh& surface) {
  if (key.empty()) return;
  const fs::path file = file_for(key);
  if (file.empty()) return;
  try {
    write_file_atomic(file, mannequin_cache_file(surface, key));
  } catch (const std::exception&) {
    // A cache that cannot be written (read-only home, disk full) costs the next run its meshing only.
    return;
  }
  // At most kMaxFiles surfaces: each build of vgd keys its own, so the
  // oldest written go (another process may be removing them too: errors are
  // ignored). Only the cache's own files: named as file_for names them and
  // beginning with kMagic; anything else in the folder is never touched.
  std::error_code ec;
  std::vector<std::pair<fs::file_time_type, fs::path>> kept;
  for (fs::directory_iterator it(file.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    if (!is_cache_file(it->path())) continue;
    std::error_code te;
    const auto t = fs::last_write_time(it->path(), te);
    if (!te) kept.emplace_back(t, it->path());
  }
  if (kept.size() <= kMaxFiles) return;
  std::sort(kept.begin(), kept.end());
  for (std::size_t i = 0; i + kMaxFiles < kept.size(); ++i)
    if (kept[i].second != file) fs::remove(kept[i].second, ec);
}

}  // namespace detail
}  // namespace vgd::body
