// The .wvt codec (docs/formats/wvt.md). Encoding, in stages:
//   1. quantise   every coordinate on a uniform grid of step Δ = 2b/√3 from a
//                 per-axis origin: no vertex lands farther than b from where it was;
//   2. transform  each particle's integer signal along time with a reversible
//                 integer lifting wavelet (CDF 5/3 or Haar), Mallat layout, to
//                 the depth that codes smaller (full or none: measured per file);
//   3. predict    across particles: coefficients minus those of the particle's
//                 parent on a spanning tree of the mesh (merged copies: minus
//                 their representative's, which is 0 once they are one);
//   4. code       the residuals as zigzag varints, band by band, through zstd.
// Stages 2–4 are lossless on integers, so the error is the quantiser's alone;
// encode() still decodes its output and measures it, and tightens Δ if
// rounding to float32 ever pushed a vertex past the bound.
#include "vgd/io/wvt/wvt.hpp"

#include <zstd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/trj/binary.hpp"

namespace vgd::io::wvt {

namespace {

namespace bin = vgd::io::binary;
using trj::Topology;
using trj::Trajectory;

// ---- layout (docs/formats/wvt.md) ----
constexpr char kMagic[8] = {'\x89', 'W', 'V', 'T', '\r', '\n', '\x1a', '\n'};
constexpr std::uint32_t kHeaderSize = 128;
constexpr std::uint64_t kChunkHeader = 16;  // tag[4], crc32 u32, payload length u64
constexpr std::uint64_t kMaxValues = 1ull << 31;  // coordinates × frames a file may hold
constexpr double kMaxSteps = 1073741824.0;      // 2^30 grid steps per axis at most

[[noreturn]] void fail(const std::string& file, const std::string& what, const std::string& problem) {
  throw Error(file, what, problem);
}

// ---------------------------------------------------------------------------
// Reversible integer wavelets along time, in place on x[0, n), Mallat layout:
// approximation first, then details. C++20 >> on negative numbers is floor division.

// CDF 5/3 (LeGall, JPEG 2000 reversible) with whole-sample symmetric extension:
//   d[i] = x[2i+1] − ⌊(x[2i] + x[2i+2]) / 2⌋,   s[i] = x[2i] + ⌊(d[i−1] + d[i] + 2) / 4⌋
void cdf53_forward(std::int64_t* x, int n, std::vector<std::int64_t>& tmp) {
  if (n < 2) return;
  const int ns = (n + 1) / 2, nd = n / 2;
  tmp.resize(static_cast<std::size_t>(n));
  std::int64_t *s = tmp.data(), *d = tmp.data() + ns;
  for (int i = 0; i < nd; ++i) d[i] = x[2 * i + 1] - ((x[2 * i] + (2 * i + 2 < n ? x[2 * i + 2] : x[2 * i])) >> 1);
  for (int i = 0; i < ns; ++i) s[i] = x[2 * i] + ((d[i > 0 ? i - 1 : 0] + d[i < nd ? i : nd - 1] + 2) >> 2);
  std::copy(tmp.begin(), tmp.end(), x);
}

void cdf53_inverse(std::int64_t* x, int n, std::vector<std::int64_t>& tmp) {
  if (n < 2) return;
  const int ns = (n + 1) / 2, nd = n / 2;
  tmp.resize(static_cast<std::size_t>(n));
  const std::int64_t *s = x, *d = x + ns;
  for (int i = 0; i < ns; ++i) tmp[2 * i] = s[i] - ((d[i > 0 ? i - 1 : 0] + d[i < nd ? i : nd - 1] + 2) >> 2);
  for (int i = 0; i < nd; ++i)
    tmp[2 * i + 1] = d[i] + ((tmp[2 * i] + (2 * i + 2 < n ? tmp[2 * i + 2] : tmp[2 * i])) >> 1);
  std::copy(tmp.begin(), tmp.end(), x);
}

// Haar as the S-transform: d = x[2i+1] − x[2i], s = x[2i] + ⌊d / 2⌋; an odd
// last sample passes to the approximation.
void haar_forward(std::int64_t* x, int n, std::vector<std::int64_t>& tmp) {
  if (n < 2) return;
  const int ns = (n + 1) / 2, nd = n / 2;
  tmp.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < nd; ++i) {
    const std::int64_t d = x[2 * i + 1] - x[2 * i];
    tmp[ns + i] = d;
    tmp[i] = x[2 * i] + (d >> 1);
  }
  if (n % 2) tmp[ns - 1] = x[n - 1];
  std::copy(tmp.begin(), tmp.end(), x);
}

void haar_inverse(std::int64_t* x, int n, std::vector<std::int64_t>& tmp) {
  if (n < 2) return;
  const int ns = (n + 1) / 2, nd = n / 2;
  tmp.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < nd; ++i) {
    tmp[2 * i] = x[i] - (x[ns + i] >> 1);
    tmp[2 * i + 1] = x[ns + i] + tmp[2 * i];
  }
  if (n % 2) tmp[n - 1] = x[ns - 1];
  std::copy(tmp.begin(), tmp.end(), x);
}

// Levels a signal of n samples can take (until the approximation is one sample).
int max_levels(int n) {
  int l = 0;
  for (int m = n; m > 1; m = (m + 1) / 2) ++l;
  return l;
}

// Band edges of the Mallat layout, coarse to fine: band b is [edges[b], edges[b+1]).
std::vector<int> band_edges(int n, int levels) {
  std::vector<int> lengths{n};
  for (int l = 0; l < levels; ++l) lengths.push_back((lengths.back() + 1) / 2);
  std::vector<int> edges{0};
  for (int l = levels; l >= 0; --l) edges.push_back(lengths[l]);
  return edges;
}

void transform_signal(std::int64_t* x, int n, int levels, int transform, bool inverse, std::vector<std::int64_t>& tmp) {
  auto step = [&](int len) {
    if (transform == 1)
      inverse ? haar_inverse(x, len, tmp) : haar_forward(x, len, tmp);
    else
      inverse ? cdf53_inverse(x, len, tmp) : cdf53_forward(x, len, tmp);
  };
  std::vector<int> lengths{n};
  for (int l = 1; l < levels; ++l) lengths.push_back((lengths.back() + 1) / 2);
  if (!inverse) {
    for (int l = 0; l < levels; ++l) step(lengths[l]);
  } else {
    for (int l = levels - 1; l >= 0; --l) step(lengths[l]);
  }
}

// ---------------------------------------------------------------------------
// Prediction across particles

// Each particle's parent (−1: none) and the coding order (parents first).
// Merged copies (final representative another particle that is its own
// representative) hang from their representative; the others form a BFS
// spanning forest of the mesh edges between representatives.
struct Tree {
  std::vector<int> parent, order;
};

Tree spanning_tree(const Topology& topo, int frames) {
  const int n = topo.num_particles;
  Tree t;
  t.parent.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> rep = topo.representatives(std::max(0, frames - 1));
  std::vector<bool> copy(static_cast<std::size_t>(n), false);
  for (int i = 0; i < n; ++i) copy[i] = rep[i] != i && rep[rep[i]] == rep[i];
  auto root = [&](int i) { return copy[i] ? rep[i] : i; };
  // Adjacency (CSR) between representatives.
  std::vector<int> degree(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& f : topo.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = root(f[k]), b = root(f[(k + 1) % 3]);
      if (a != b) ++degree[a + 1], ++degree[b + 1];
    }
  for (int i = 0; i < n; ++i) degree[i + 1] += degree[i];
  std::vector<int> adj(static_cast<std::size_t>(degree[n])), fill(degree.begin(), degree.end() - 1);
  for (const auto& f : topo.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = root(f[k]), b = root(f[(k + 1) % 3]);
      if (a != b) adj[fill[a]++] = b, adj[fill[b]++] = a;
    }
  std::vector<bool> seen(static_cast<std::size_t>(n), false);
  t.order.reserve(static_cast<std::size_t>(n));
  for (int s = 0; s < n; ++s) {
    if (copy[s] || seen[s]) continue;
    seen[s] = true;
    std::size_t q = t.order.size();
    t.order.push_back(s);
    while (q < t.order.size()) {
      const int u = t.order[q++];
      for (int e = degree[u]; e < degree[u + 1]; ++e)
        if (!seen[adj[e]]) {
          seen[adj[e]] = true;
          t.parent[adj[e]] = u;
          t.order.push_back(adj[e]);
        }
    }
  }
  for (int i = 0; i < n; ++i)
    if (copy[i]) {
      t.parent[i] = rep[i];
      t.order.push_back(i);
    }
  return t;
}

// ---------------------------------------------------------------------------
// Varints and zstd

void put_varint(std::string& out, std::int64_t v) {
  std::uint64_t z = (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
  while (z >= 0x80) {
    out.push_back(static_cast<char>((z & 0x7F) | 0x80));
    z >>= 7;
  }
  out.push_back(static_cast<char>(z));
}

bool get_varint(const char*& p, const char* end, std::int64_t& v) {
  std::uint64_t z = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    if (p == end) return false;
    const auto b = static_cast<unsigned char>(*p++);
    z |= static_cast<std::uint64_t>(b & 0x7F) << shift;
    if (!(b & 0x80)) {
      v = static_cast<std::int64_t>(z >> 1) ^ -static_cast<std::int64_t>(z & 1);
      return true;
    }
  }
  return false;
}

std::string zstd_compress(std::string_view in, int level) {
  std::string out(ZSTD_compressBound(in.size()), '\0');
  const std::size_t n = ZSTD_compress(out.data(), out.size(), in.data(), in.size(), level);
  VGD_ASSERT(!ZSTD_isError(n), "zstd compression failed");
  out.resize(n);
  return out;
}

// Decompresses a section whose size the format bounds (`limit` bytes).
std::string zstd_decompress(std::string_view in, std::uint64_t limit, const std::string& file, const std::string& what) {
  const unsigned long long size = ZSTD_getFrameContentSize(in.data(), in.size());
  if (size == ZSTD_CONTENTSIZE_ERROR || size == ZSTD_CONTENTSIZE_UNKNOWN)
    fail(file, what, "not a zstd frame (corrupt section)");
  if (size > limit)
    fail(file, what, "declares " + std::to_string(size) + " bytes; at most " + std::to_string(limit) +
                         " fit the header's counts (corrupt section)");
  std::string out(static_cast<std::size_t>(size), '\0');
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n) || n != size) fail(file, what, std::string("zstd: ") + (ZSTD_isError(n) ? ZSTD_getErrorName(n) : "short section") + " (corrupt section)");
  return out;
}

std::string section(const char tag[4], std::string_view payload) {
  std::string out(tag, 4);
  bin::put_u32(out, bin::crc32(payload));
  bin::put_u64(out, payload.size());
  out += payload;
  return out;
}

// ---------------------------------------------------------------------------
// The coded positions: what the header and the POSN section hold.

struct Grid {
  int n = 0, frames = 0, transform = 2, levels = 0, spatial = 2;
  double step = 0.0;
  double origin[3] = {0, 0, 0};
};

// signal index of (axis, particle): the F samples of one coordinate are contiguous.
inline std::size_t signal(const Grid& g, int axis, int p) {
  return (static_cast<std::size_t>(axis) * g.n + p) * static_cast<std::size_t>(g.frames);
}

bool band_predicted(const Grid& g, int band) { return g.spatial == 2 || (g.spatial == 1 && band == 0); }

// Quantised, transformed, predicted, varint-coded positions.
std::string code_positions(const Trajectory& t, const Grid& g, const Tree& tree) {
  const std::size_t f = static_cast<std::size_t>(g.frames);
  std::vector<std::int64_t> c(3 * static_cast<std::size_t>(g.n) * f);
  for (std::size_t k = 0; k < f; ++k)
    for (int p = 0; p < g.n; ++p)
      for (int a = 0; a < 3; ++a)
        c[signal(g, a, p) + k] = std::llround((static_cast<double>(t.frames[k][3 * p + a]) - g.origin[a]) / g.step);
  std::vector<std::int64_t> tmp;
  for (int a = 0; a < 3; ++a)
    for (int p = 0; p < g.n; ++p) transform_signal(c.data() + signal(g, a, p), g.frames, g.levels, g.transform, false, tmp);
  const std::vector<int> edges = band_edges(g.frames, g.levels);
  std::string out;
  out.reserve(c.size());
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    const bool predicted = band_predicted(g, static_cast<int>(b));
    for (int a = 0; a < 3; ++a)
      for (int p : tree.order) {
        const std::int64_t* x = c.data() + signal(g, a, p);
        const std::int64_t* y = predicted && tree.parent[p] >= 0 ? c.data() + signal(g, a, tree.parent[p]) : nullptr;
        for (int k = edges[b]; k < edges[b + 1]; ++k) put_varint(out, y ? x[k] - y[k] : x[k]);
      }
  }
  return out;
}

// The inverse of code_positions: positions of every frame.
std::vector<std::vector<float>> decode_positions(std::string_view coded, const Grid& g, const Tree& tree,
                                                 const std::string& file) {
  const std::size_t f = static_cast<std::size_t>(g.frames);
  std::vector<std::int64_t> c(3 * static_cast<std::size_t>(g.n) * f);
  const std::vector<int> edges = band_edges(g.frames, g.levels);
  const char *p0 = coded.data(), *end = coded.data() + coded.size();
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    const bool predicted = band_predicted(g, static_cast<int>(b));
    for (int a = 0; a < 3; ++a)
      for (int p : tree.order) {
        std::int64_t* x = c.data() + signal(g, a, p);
        const std::int64_t* y = predicted && tree.parent[p] >= 0 ? c.data() + signal(g, a, tree.parent[p]) : nullptr;
        for (int k = edges[b]; k < edges[b + 1]; ++k) {
          std::int64_t v = 0;
          if (!get_varint(p0, end, v)) fail(file, "positions", "the coefficient stream ends early (corrupt section)");
          // Wrapping arithmetic: corrupt input must not be undefined behaviour.
          x[k] = y ? static_cast<std::int64_t>(static_cast<std::uint64_t>(v) + static_cast<std::uint64_t>(y[k])) : v;
          if (x[k] > (1ll << 40) || x[k] < -(1ll << 40))
            fail(file, "positions", "a coefficient out of range (corrupt section)");
        }
      }
  }
  if (p0 != end) fail(file, "positions", std::to_string(end - p0) + " bytes left after the coefficients (corrupt section)");
  std::vector<std::int64_t> tmp;
  for (int a = 0; a < 3; ++a)
    for (int p = 0; p < g.n; ++p) transform_signal(c.data() + signal(g, a, p), g.frames, g.levels, g.transform, true, tmp);
  std::vector<std::vector<float>> frames(f, std::vector<float>(3 * static_cast<std::size_t>(g.n)));
  for (std::size_t k = 0; k < f; ++k)
    for (int p = 0; p < g.n; ++p)
      for (int a = 0; a < 3; ++a)
        frames[k][3 * p + a] = static_cast<float>(g.origin[a] + static_cast<double>(c[signal(g, a, p) + k]) * g.step);
  return frames;
}

std::string merges_payload(const Topology& t) {
  std::string p;
  bin::put_u32(p, static_cast<std::uint32_t>(t.merges.size()));
  for (const auto& m : t.merges) {
    bin::put_u32(p, static_cast<std::uint32_t>(m.frame));
    bin::put_u32(p, static_cast<std::uint32_t>(m.particle));
    bin::put_u32(p, static_cast<std::uint32_t>(m.representative));
  }
  return p;
}

// The fixed header.
struct Header {
  int major = 0, minor = 0;
  Grid grid;
  int triangles = 0, pieces = 0, merges = 0;  // counts that bound the sections' sizes
  double bound = 0.0, measured = 0.0;
};

std::string header_bytes(const Header& h) {
  std::string out(kMagic, 8);
  bin::put_u16(out, kVersionMajor);
  bin::put_u16(out, kVersionMinor);
  bin::put_u32(out, kHeaderSize);
  bin::put_u32(out, static_cast<std::uint32_t>(h.grid.n));
  bin::put_u32(out, static_cast<std::uint32_t>(h.grid.frames));
  bin::put_u32(out, static_cast<std::uint32_t>(h.grid.transform));
  bin::put_u32(out, static_cast<std::uint32_t>(h.grid.levels));
  bin::put_u32(out, static_cast<std::uint32_t>(h.grid.spatial));
  bin::put_u32(out, static_cast<std::uint32_t>(h.triangles));
  bin::put_f64(out, h.bound);
  bin::put_f64(out, h.measured);
  bin::put_f64(out, h.grid.step);
  for (double o : h.grid.origin) bin::put_f64(out, o);
  bin::put_u32(out, static_cast<std::uint32_t>(h.pieces));
  bin::put_u32(out, static_cast<std::uint32_t>(h.merges));
  out.resize(kHeaderSize, '\0');
  return out;
}

Header parse_header(std::string_view bytes, const std::string& file) {
  if (!looks_like_wvt(bytes))
    fail(file, "header", "not a vgd compressed trajectory: the file does not start with the .wvt signature (bad magic)");
  if (bytes.size() < kHeaderSize)
    fail(file, "header", "the file ends inside the " + std::to_string(kHeaderSize) + "-byte header (" +
                             std::to_string(bytes.size()) + " bytes)");
  const char* p = bytes.data();
  Header h;
  h.major = bin::get_u16(p + 8);
  h.minor = bin::get_u16(p + 10);
  if (h.major != kVersionMajor)
    fail(file, "header",
         "format version " + std::to_string(h.major) + "." + std::to_string(h.minor) +
             (h.major > kVersionMajor ? " was written by a newer vgd; " : " is not supported; ") + "this vgd reads " +
             std::to_string(kVersionMajor) + ".x (unsupported version)");
  const std::uint32_t header_size = bin::get_u32(p + 12);
  if (header_size < kHeaderSize || header_size > bytes.size())
    fail(file, "header", "header size " + std::to_string(header_size) + " is impossible (corrupt header)");
  Grid& g = h.grid;
  const std::uint32_t n = bin::get_u32(p + 16), frames = bin::get_u32(p + 20);
  const std::uint32_t transform = bin::get_u32(p + 24), levels = bin::get_u32(p + 28), spatial = bin::get_u32(p + 32);
  if (3ull * n * frames > kMaxValues || n > (1u << 28) || frames > (1u << 28))
    fail(file, "header", std::to_string(n) + " particles × " + std::to_string(frames) +
                             " frames is more than a .wvt holds (corrupt header)");
  if (transform != 1 && transform != 2)
    fail(file, "header", "unknown wavelet " + std::to_string(transform) + " (corrupt header, or a newer vgd)");
  if (static_cast<int>(levels) > max_levels(static_cast<int>(frames)))
    fail(file, "header", std::to_string(levels) + " wavelet levels for " + std::to_string(frames) + " frames (corrupt header)");
  if (spatial > 2) fail(file, "header", "unknown prediction mode " + std::to_string(spatial) + " (corrupt header)");
  g.n = static_cast<int>(n);
  g.frames = static_cast<int>(frames);
  g.transform = static_cast<int>(transform);
  g.levels = static_cast<int>(levels);
  g.spatial = static_cast<int>(spatial);
  const std::uint32_t triangles = bin::get_u32(p + 36), pieces = bin::get_u32(p + 88), merges = bin::get_u32(p + 92);
  if (triangles > (1u << 28) || pieces > (1u << 20) || merges > (1u << 28))
    fail(file, "header", "impossible triangle, piece or merge count (corrupt header)");
  h.triangles = static_cast<int>(triangles);
  h.pieces = static_cast<int>(pieces);
  h.merges = static_cast<int>(merges);
  h.bound = bin::get_f64(p + 40);
  h.measured = bin::get_f64(p + 48);
  g.step = bin::get_f64(p + 56);
  for (int a = 0; a < 3; ++a) g.origin[a] = bin::get_f64(p + 64 + 8 * a);
  if (!(g.step > 0.0) || !std::isfinite(g.step) || !std::isfinite(g.origin[0]) || !std::isfinite(g.origin[1]) ||
      !std::isfinite(g.origin[2]))
    fail(file, "header", "the quantisation grid is not finite and positive (corrupt header)");
  return h;
}

// The sections of a .wvt after its header, by tag.
struct Sections {
  std::string_view topo, merges, times, positions;
  bool end = false;
};

Sections split_sections(std::string_view bytes, const std::string& file) {
  Sections s;
  std::uint64_t pos = bin::get_u32(bytes.data() + 12);
  while (pos < bytes.size()) {
    const std::string what = "section at byte " + std::to_string(pos);
    if (bytes.size() - pos < kChunkHeader) fail(file, what, "the file ends inside a section header (truncated)");
    const char* h = bytes.data() + pos;
    const std::uint32_t crc = bin::get_u32(h + 4);
    const std::uint64_t len = bin::get_u64(h + 8);
    if (len > bytes.size() - pos - kChunkHeader) fail(file, what, "the section runs past the end of the file (truncated)");
    const std::string_view payload = bytes.substr(pos + kChunkHeader, len);
    const std::string tag(h, 4);
    if (bin::crc32(payload) != crc) fail(file, what, "'" + tag + "' checksum mismatch (corrupt section)");
    if (tag == "TOPO") s.topo = payload;
    else if (tag == "MERG") s.merges = payload;
    else if (tag == "TIME") s.times = payload;
    else if (tag == "POSN") s.positions = payload;
    else if (tag == "END ") s.end = true;
    pos += kChunkHeader + len;
    if (s.end) break;
  }
  if (!s.end) fail(file, "", "no end marker: the file is truncated");
  if (s.topo.data() == nullptr || s.times.data() == nullptr || s.positions.data() == nullptr ||
      s.merges.data() == nullptr)
    fail(file, "", "a section is missing (TOPO, MERG, TIME and POSN are required; corrupt file)");
  return s;
}

// The .trj TOPO payload, its size bounded by the header's counts (piece names: 1 MiB at most).
Topology decode_topology(const Header& h, const Sections& s, const std::string& name) {
  const std::uint64_t limit = 12 + 16ull * h.triangles + 16ull * h.grid.n + 4ull * h.pieces + (1u << 20);
  Topology t = trj::parse_topology_payload(zstd_decompress(s.topo, limit, name, "topology"), h.grid.n, name);
  if (t.triangles.size() != static_cast<std::size_t>(h.triangles) || t.pieces.size() != static_cast<std::size_t>(h.pieces))
    fail(name, "topology", "the topology's counts differ from the header's (corrupt section)");
  return t;
}

}  // namespace

bool looks_like_wvt(std::string_view bytes) { return bytes.size() >= 8 && std::memcmp(bytes.data(), kMagic, 8) == 0; }

double max_vertex_error(const Trajectory& a, const Trajectory& b) {
  VGD_ASSERT(a.frames.size() == b.frames.size(), "max_vertex_error: frame counts differ");
  double worst = 0.0;
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    VGD_ASSERT(a.frames[k].size() == b.frames[k].size(), "max_vertex_error: particle counts differ");
    for (std::size_t i = 0; i + 2 < a.frames[k].size(); i += 3) {
      double d2 = 0.0;
      for (int j = 0; j < 3; ++j) {
        const double d = static_cast<double>(a.frames[k][i + j]) - static_cast<double>(b.frames[k][i + j]);
        d2 += d * d;
      }
      worst = std::max(worst, d2);
    }
  }
  return std::sqrt(worst);
}

std::string encode(const Trajectory& t, const EncodeOptions& options, EncodeStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  const std::string& name = options.source;
  const int n = t.topology.num_particles, frames = t.frame_count();
  VGD_ASSERT(t.times.size() == t.frames.size(), "wvt::encode: one time per frame");
  VGD_ASSERT(options.max_error_m > 0.0, "wvt::encode: the error bound must be positive");
  if (!(options.max_error_m >= 1e-7))
    fail(name, "", "an error bound of " + format_double(options.max_error_m * 1000) +
                       " mm is below float32 resolution; use at least 0.0001 mm");
  if (3ull * static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(frames) > kMaxValues)
    fail(name, "", "too large for one .wvt (more than 2^31 coordinates)");

  // Extent per axis, and every coordinate finite.
  Grid g;
  g.n = n;
  g.frames = frames;
  g.transform = static_cast<int>(options.transform);
  g.spatial = static_cast<int>(options.spatial);
  g.levels = options.levels < 0 ? max_levels(frames) : std::min(options.levels, max_levels(frames));
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, biggest = 0.0;
  for (int k = 0; k < frames; ++k) {
    VGD_ASSERT(t.frames[k].size() == 3 * static_cast<std::size_t>(n), "wvt::encode: a frame without 3N positions");
    for (int p = 0; p < n; ++p)
      for (int a = 0; a < 3; ++a) {
        const double x = t.frames[k][3 * p + a];
        if (!std::isfinite(x))
          fail(name, "frame " + std::to_string(k) + ", particle " + std::to_string(p), "a position is not finite");
        lo[a] = (k == 0 && p == 0) ? x : std::min(lo[a], x);
        hi[a] = (k == 0 && p == 0) ? x : std::max(hi[a], x);
        biggest = std::max(biggest, std::abs(x));
      }
  }
  for (int a = 0; a < 3; ++a) g.origin[a] = lo[a];
  // Δ = 2b/√3 keeps every vertex within b (each axis within Δ/2); a margin of
  // a few float32 ulps covers the rounding of the decoded value to float.
  const double margin = 4.0 * biggest * std::numeric_limits<float>::epsilon();
  g.step = 2.0 * std::max(options.max_error_m - margin, 0.5 * options.max_error_m) / std::sqrt(3.0);
  for (int a = 0; a < 3; ++a)
    if ((hi[a] - lo[a]) / g.step > kMaxSteps)
      fail(name, "", "an error bound of " + format_double(options.max_error_m * 1000) +
                         " mm is too fine for a trajectory " + format_double(hi[a] - lo[a]) + " m across");

  const Tree tree = spanning_tree(t.topology, frames);
  std::string times;
  for (double x : t.times) bin::put_f64(times, x);
  std::string fixed_sections = section("TOPO", zstd_compress(trj::topology_payload(t.topology), options.zstd_level)) +
                               section("MERG", zstd_compress(merges_payload(t.topology), options.zstd_level)) +
                               section("TIME", zstd_compress(times, options.zstd_level));

  // Encode, decode, measure; tighten the step if the bound did not hold.
  Header h;
  h.grid = g;
  h.triangles = static_cast<int>(t.topology.triangles.size());
  h.pieces = static_cast<int>(t.topology.pieces.size());
  h.merges = static_cast<int>(t.topology.merges.size());
  h.bound = options.max_error_m;
  // Levels: as asked, or by measurement — the full depth and none (prediction
  // across the mesh alone) both encoded, the smaller kept (docs/formats/wvt.md:
  // short drapes favour none, long motion the full depth).
  std::vector<int> depths{std::min(options.levels, max_levels(frames))};
  if (options.levels < 0) depths = {max_levels(frames), 0};
  for (int attempt = 1;; ++attempt) {
    std::string positions;
    for (int depth : depths) {
      Grid trial = h.grid;
      trial.levels = depth;
      std::string p = zstd_compress(code_positions(t, trial, tree), options.zstd_level);
      if (positions.empty() || p.size() < positions.size()) {
        positions = std::move(p);
        h.grid.levels = depth;
      }
    }
    std::string out = header_bytes(h) + fixed_sections + section("POSN", positions) + section("END ", "");
    const Trajectory back = decode(out, name);
    h.measured = max_vertex_error(t, back);
    if (h.measured <= options.max_error_m) {
      out.replace(0, kHeaderSize, header_bytes(h));
      if (stats) {
        stats->position_bytes = 12ull * static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(frames);
        stats->position_stream_bytes = positions.size();
        stats->output_bytes = out.size();
        stats->step_m = h.grid.step;
        stats->levels = h.grid.levels;
        stats->max_error_m = h.measured;
        stats->attempts = attempt;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
      return out;
    }
    VGD_ASSERT(attempt < 20, "wvt::encode: the error bound could not be met");
    h.grid.step *= 0.9 * options.max_error_m / h.measured;
  }
}

Trajectory decode(std::string_view bytes, const std::string& name) {
  const Header h = parse_header(bytes, name);
  const Grid& g = h.grid;
  const Sections s = split_sections(bytes, name);
  Trajectory t;
  t.topology = decode_topology(h, s, name);
  // Merges.
  {
    const std::string p = zstd_decompress(s.merges, 4 + 12ull * h.merges, name, "merges");
    bin::Cursor c(p);
    std::uint32_t count = 0;
    if (!c.u32(count) || count != static_cast<std::uint32_t>(h.merges) || c.left() != 12ull * count)
      fail(name, "merges", "the merge list's size does not match its count (corrupt section)");
    t.topology.merges.reserve(count);
    for (std::uint32_t k = 0; k < count; ++k) {
      std::uint32_t f = 0, a = 0, b = 0;
      c.u32(f), c.u32(a), c.u32(b);
      if (a >= static_cast<std::uint32_t>(g.n) || b >= static_cast<std::uint32_t>(g.n) || f > 0x7FFFFFFFu)
        fail(name, "merges", "a merge names a particle that does not exist (corrupt section)");
      t.topology.merges.push_back({static_cast<int>(f), static_cast<int>(a), static_cast<int>(b)});
    }
  }
  // Times.
  {
    const std::string p = zstd_decompress(s.times, 8ull * g.frames, name, "times");
    if (p.size() != 8ull * g.frames)
      fail(name, "times", std::to_string(p.size() / 8) + " frame times for " + std::to_string(g.frames) + " frames (corrupt section)");
    t.times.resize(static_cast<std::size_t>(g.frames));
    for (int k = 0; k < g.frames; ++k) t.times[k] = bin::get_f64(p.data() + 8 * k);
  }
  // Positions: at most 10 bytes per coefficient.
  const std::uint64_t values = 3ull * g.n * g.frames;
  const std::string coded = zstd_decompress(s.positions, 10 * values, name, "positions");
  if (coded.size() < values) fail(name, "positions", "fewer coded bytes than coordinates (corrupt section)");
  if (g.frames > 0) t.frames = decode_positions(coded, g, spanning_tree(t.topology, g.frames), name);
  return t;
}

void write_wvt(const std::filesystem::path& file, const Trajectory& trajectory, const EncodeOptions& options,
               EncodeStats* stats) {
  write_file_atomic(file, encode(trajectory, options, stats));
}

Trajectory read_wvt(const std::filesystem::path& file) { return decode(read_file(file), file.string()); }

Info read_info(std::string_view bytes, const std::string& name) {
  const Header h = parse_header(bytes, name);
  const Sections s = split_sections(bytes, name);
  Info info;
  info.version_major = h.major;
  info.version_minor = h.minor;
  info.num_particles = h.grid.n;
  info.frame_count = h.grid.frames;
  info.max_error_m = h.bound;
  info.measured_error_m = h.measured;
  info.step_m = h.grid.step;
  info.levels = h.grid.levels;
  info.file_size = bytes.size();
  info.position_stream_bytes = s.positions.size();
  decode_topology(h, s, name);  // checks it
  info.num_triangles = h.triangles;
  info.num_pieces = h.pieces;
  info.num_merges = h.merges;
  const std::string times = zstd_decompress(s.times, 8ull * h.grid.frames, name, "times");
  if (times.size() >= 8) {
    info.first_time = bin::get_f64(times.data());
    info.last_time = bin::get_f64(times.data() + times.size() - 8);
  }
  return info;
}

bool is_wvt_file(const std::filesystem::path& file) {
  std::string head(8, '\0');
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (!f) return false;
  head.resize(std::fread(head.data(), 1, head.size(), f));
  std::fclose(f);
  return looks_like_wvt(head);
}

Trajectory read_trajectory(const std::filesystem::path& file) {
  if (is_wvt_file(file)) return read_wvt(file);
  return trj::TrjReader(file).read_all();  // says when the file cannot be opened
}

}  // namespace vgd::io::wvt
