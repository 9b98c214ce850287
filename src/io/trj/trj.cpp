// The .trj trajectory file (docs/formats/trj.md): a fixed header, then
// self-delimiting chunks — TOPO once, MERG when seams merge, FRAM per frame,
// END when the writer finished. Each chunk carries its length and a CRC-32 of
// its payload, so a reader can index frames by scanning chunk headers and
// tell a torn last write (a crash) from corruption.
#include "vgd/io/trj/trj.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "vgd/io/trj/binary.hpp"

namespace vgd::io::trj {

namespace {

namespace bin = vgd::io::binary;

// ---- layout (docs/formats/trj.md) ----
constexpr char kMagic[8] = {'\x89', 'T', 'R', 'J', '\r', '\n', '\x1a', '\n'};
constexpr std::uint32_t kHeaderSize = 32;
constexpr std::uint64_t kChunkHeader = 16;  // tag[4], crc32 u32, payload length u64
constexpr std::uint64_t kFrameFixed = 16;   // frame index u32, reserved u32, time f64
constexpr std::uint32_t kMaxParticles = 1u << 28;
constexpr std::uint32_t kTopoHasUv = 1u, kTopoHasPieces = 2u;

// Error text helpers: every message names the file and what.
[[noreturn]] void fail(const std::string& file, const std::string& what, const std::string& problem) {
  throw Error(file, what, problem);
}

std::string offset_text(std::uint64_t off) { return "at byte " + std::to_string(off); }

std::string chunk(const char tag[4], std::string_view payload) {
  std::string out(tag, 4);
  bin::put_u32(out, bin::crc32(payload));
  bin::put_u64(out, payload.size());
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------
// Topology

std::vector<int> Topology::representatives(int frame) const {
  std::vector<int> rep(static_cast<std::size_t>(std::max(0, num_particles)));
  for (std::size_t i = 0; i < rep.size(); ++i) rep[i] = static_cast<int>(i);
  for (const Merge& m : merges)
    if (m.frame <= frame && m.particle >= 0 && m.particle < num_particles) rep[m.particle] = m.representative;
  return rep;
}

Topology topology_of(const sim::Model& model) {
  Topology t;
  t.num_particles = model.num_particles();
  if (t.num_particles == 0) t.num_particles = static_cast<int>(model.x0.size() / 3);
  t.triangles = model.triangles;
  if (model.triangle_piece.size() == model.triangles.size()) t.triangle_piece = model.triangle_piece;
  t.pieces = model.pieces;
  if (static_cast<int>(model.uv.size()) == t.num_particles) {
    t.uv.reserve(model.uv.size());
    for (const auto& p : model.uv) t.uv.push_back({p.x(), p.y()});
  }
  return t;
}

std::string topology_payload(const Topology& topology) {
  // Counts, flags, piece names, triangles, piece ids, uv.
  const int n = topology.num_particles;
  const bool has_pieces = topology.triangle_piece.size() == topology.triangles.size() && !topology.triangles.empty();
  const bool has_uv = static_cast<int>(topology.uv.size()) == n && n > 0;
  std::string p;
  bin::put_u32(p, static_cast<std::uint32_t>(topology.triangles.size()));
  bin::put_u32(p, static_cast<std::uint32_t>(topology.pieces.size()));
  bin::put_u32(p, (has_uv ? kTopoHasUv : 0u) | (has_pieces ? kTopoHasPieces : 0u));
  for (const auto& name : topology.pieces) {
    bin::put_u32(p, static_cast<std::uint32_t>(name.size()));
    p += name;
  }
  for (const auto& tri : topology.triangles) {
    for (int c : tri) {
      VGD_ASSERT(c >= 0 && c < n, "trj: a triangle indexes a particle out of range");
      bin::put_u32(p, static_cast<std::uint32_t>(c));
    }
  }
  if (has_pieces)
    for (int piece : topology.triangle_piece) {
      VGD_ASSERT(piece >= 0 && piece < static_cast<int>(topology.pieces.size()), "trj: a triangle's piece does not exist");
      bin::put_u32(p, static_cast<std::uint32_t>(piece));
    }
  if (has_uv)
    for (const auto& q : topology.uv) {
      bin::put_f64(p, q[0]);
      bin::put_f64(p, q[1]);
    }
  return p;
}

// ---------------------------------------------------------------------------
// Writer

TrjWriter::TrjWriter(std::filesystem::path file, WriterOptions options)
    : file_(std::move(file)), options_(options) {}

TrjWriter::~TrjWriter() {
  if (out_) std::fclose(out_);
}

std::filesystem::path TrjWriter::partial_path() const { return std::filesystem::path(file_.string() + ".partial"); }

void TrjWriter::begin(const sim::Model& model) { begin(topology_of(model)); }

void TrjWriter::begin(const Topology& topology) {
  VGD_ASSERT(out_ == nullptr, "TrjWriter::begin called twice");
  VGD_ASSERT(topology.num_particles >= 0 && static_cast<std::uint32_t>(topology.num_particles) <= kMaxParticles,
             "TrjWriter: particle count out of range");
  const auto partial = partial_path();
  std::error_code ec;
  if (partial.has_parent_path()) std::filesystem::create_directories(partial.parent_path(), ec);
  out_ = std::fopen(partial.c_str(), "wb");
  if (!out_) fail(partial.string(), "", std::string("cannot create the trajectory file: ") + std::strerror(errno));
  num_particles_ = topology.num_particles;
  frames_ = 0;
  bytes_ = 0;

  // Header: magic, version, header size, particle count, flags, reserved.
  std::string head(kMagic, 8);
  bin::put_u16(head, kVersionMajor);
  bin::put_u16(head, kVersionMinor);
  bin::put_u32(head, kHeaderSize);
  bin::put_u32(head, static_cast<std::uint32_t>(num_particles_));
  bin::put_u32(head, 0);
  bin::put_u64(head, 0);
  if (std::fwrite(head.data(), 1, head.size(), out_) != head.size())
    fail(partial.string(), "header", std::string("cannot write: ") + std::strerror(errno));
  bytes_ += head.size();

  write_chunk("TOPO", topology_payload(topology));

  rep_.resize(static_cast<std::size_t>(num_particles_));
  for (int i = 0; i < num_particles_; ++i) rep_[i] = i;
  // Merges a topology already carries, one chunk per frame, in file order.
  std::vector<Merge> group;
  for (std::size_t k = 0; k < topology.merges.size(); ++k) {
    group.push_back(topology.merges[k]);
    if (k + 1 == topology.merges.size() || topology.merges[k + 1].frame != group.front().frame) {
      add_merges(group.front().frame, group);
      group.clear();
    }
  }
  flush_chunk();
}

void TrjWriter::merged(int frame, const std::vector<int>& representative) {
  VGD_ASSERT(out_ != nullptr, "TrjWriter::merged before begin");
  VGD_ASSERT(static_cast<int>(representative.size()) == num_particles_,
             "TrjWriter::merged takes one representative per original particle");
  std::vector<Merge> changes;
  for (int i = 0; i < num_particles_; ++i)
    if (representative[i] != rep_[i]) changes.push_back({frame, i, representative[i]});
  add_merges(frame, changes);
}

void TrjWriter::add_merges(int frame, const std::vector<Merge>& merges) {
  VGD_ASSERT(out_ != nullptr, "TrjWriter::add_merges before begin");
  if (merges.empty()) return;
  std::string p;
  bin::put_u32(p, static_cast<std::uint32_t>(frame));
  bin::put_u32(p, static_cast<std::uint32_t>(merges.size()));
  for (const Merge& m : merges) {
    VGD_ASSERT(m.particle >= 0 && m.particle < num_particles_ && m.representative >= 0 &&
                   m.representative < num_particles_,
               "TrjWriter: a merge names a particle out of range");
    bin::put_u32(p, static_cast<std::uint32_t>(m.particle));
    bin::put_u32(p, static_cast<std::uint32_t>(m.representative));
    rep_[m.particle] = m.representative;
  }
  write_chunk("MERG", p);
  flush_chunk();
}

void TrjWriter::frame(int index, double t, const sim::VecX& x) {
  VGD_ASSERT(x.size() == 3 * static_cast<Eigen::Index>(num_particles_), "TrjWriter::frame takes 3N positions");
  scratch_.resize(static_cast<std::size_t>(x.size()));
  for (Eigen::Index i = 0; i < x.size(); ++i) scratch_[i] = static_cast<float>(x[i]);
  add_frame(t, scratch_.data());
}

void TrjWriter::add_frame(double t, const std::vector<float>& positions) {
  VGD_ASSERT(positions.size() == 3 * static_cast<std::size_t>(num_particles_), "TrjWriter::add_frame takes 3N positions");
  add_frame(t, positions.data());
}

void TrjWriter::add_frame(double t, const float* positions) {
  VGD_ASSERT(out_ != nullptr, "TrjWriter::add_frame before begin (or after end)");
  const std::size_t n = 3 * static_cast<std::size_t>(num_particles_);
  std::string p;
  p.reserve(kFrameFixed + 4 * n);
  bin::put_u32(p, static_cast<std::uint32_t>(frames_));
  bin::put_u32(p, 0);
  bin::put_f64(p, t);
  if constexpr (std::endian::native == std::endian::little) {
    p.append(reinterpret_cast<const char*>(positions), 4 * n);
  } else {
    for (std::size_t i = 0; i < n; ++i) bin::put_f32(p, positions[i]);
  }
  write_chunk("FRAM", p);
  ++frames_;
  flush_chunk();
}

void TrjWriter::end(bool ok) {
  if (!out_) return;
  std::string p;
  bin::put_u32(p, static_cast<std::uint32_t>(frames_));
  bin::put_u32(p, ok ? 1u : 0u);
  write_chunk("END ", p);
  const auto partial = partial_path();
  const bool flushed = std::fflush(out_) == 0 && ::fsync(fileno(out_)) == 0;
  const int closed = std::fclose(out_);
  out_ = nullptr;
  if (!flushed || closed != 0) fail(partial.string(), "", std::string("cannot finish the file: ") + std::strerror(errno));
  // A failed run's frames never replace a complete file: they go beside it.
  written_ = ok ? file_ : failed_path();
  std::error_code ec;
  std::filesystem::rename(partial, written_, ec);
  if (ec) fail(written_.string(), "", "cannot rename " + partial.string() + " into place: " + ec.message());
}

std::filesystem::path TrjWriter::failed_path() const {
  auto p = file_;
  const auto ext = p.extension().string();
  p.replace_filename(p.stem().string() + ".failed" + (ext.empty() ? ".trj" : ext));
  return p;
}

void TrjWriter::write_chunk(const char tag[4], const std::string& payload) {
  const std::string head = chunk(tag, payload);
  if (std::fwrite(head.data(), 1, head.size(), out_) != head.size() ||
      std::fwrite(payload.data(), 1, payload.size(), out_) != payload.size())
    fail(partial_path().string(), std::string(tag, 4) + " chunk", std::string("cannot write: ") + std::strerror(errno));
  bytes_ += head.size() + payload.size();
}

void TrjWriter::flush_chunk() {
  if (std::fflush(out_) != 0)
    fail(partial_path().string(), "", std::string("cannot write: ") + std::strerror(errno));
  if (options_.sync_every_frame) ::fsync(fileno(out_));
}

void write_trj(const std::filesystem::path& file, const Trajectory& trajectory) {
  TrjWriter w(file);
  w.begin(trajectory.topology);
  VGD_ASSERT(trajectory.times.size() == trajectory.frames.size(), "write_trj: one time per frame");
  for (std::size_t k = 0; k < trajectory.frames.size(); ++k) w.add_frame(trajectory.times[k], trajectory.frames[k]);
  w.finish();
}

// ---------------------------------------------------------------------------
// Reader

bool looks_like_trj(std::string_view bytes) {
  return bytes.size() >= 8 && std::memcmp(bytes.data(), kMagic, 8) == 0;
}

TrjReader::TrjReader(const std::filesystem::path& file) : name_(file.string()) {
  auto in = std::make_unique<std::ifstream>(file, std::ios::binary);
  if (!*in) fail(name_, "", std::string("cannot open the trajectory: ") + std::strerror(errno));
  in_ = std::move(in);
  open();
}

TrjReader TrjReader::from_bytes(std::string bytes, std::string name) {
  TrjReader r;
  r.name_ = std::move(name);
  r.in_ = std::make_unique<std::istringstream>(std::move(bytes), std::ios::binary);
  r.open();
  return r;
}

TrjReader::~TrjReader() = default;
TrjReader::TrjReader(TrjReader&&) noexcept = default;
TrjReader& TrjReader::operator=(TrjReader&&) noexcept = default;

namespace {

// Reads n bytes at `offset`; false when the stream ends first.
bool read_at(std::istream& in, std::uint64_t offset, std::size_t n, std::string& out) {
  out.resize(n);
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  if (!in) return false;
  in.read(out.data(), static_cast<std::streamsize>(n));
  return static_cast<std::size_t>(in.gcount()) == n;
}

// True when every byte from `offset` to the end is zero (a file system's
// zero-filled tail after a crash).
bool zero_tail(std::istream& in, std::uint64_t offset, std::uint64_t size) {
  std::string buf;
  for (std::uint64_t at = offset; at < size; at += buf.size()) {
    if (!read_at(in, at, static_cast<std::size_t>(std::min<std::uint64_t>(size - at, 1 << 16)), buf)) return false;
    if (std::any_of(buf.begin(), buf.end(), [](char c) { return c != 0; })) return false;
  }
  return true;
}

bool printable_tag(const char* p) {
  return std::all_of(p, p + 4, [](char c) { return c >= 0x20 && c <= 0x7E; });
}

// Parses a TOPO payload into `t` (num_particles already set).
void parse_topology(const std::string& name, std::string_view payload, bool newer_minor, Topology& t) {
  bin::Cursor c(payload);
  std::uint32_t ntri = 0, npieces = 0, flags = 0;
  auto short_payload = [&] { fail(name, "topology", "the topology chunk is shorter than its counts say (corrupt chunk)"); };
  if (!c.u32(ntri) || !c.u32(npieces) || !c.u32(flags)) short_payload();
  if ((flags & ~(kTopoHasUv | kTopoHasPieces)) != 0 && !newer_minor)
    fail(name, "topology", "unknown topology flags " + std::to_string(flags) + " (corrupt chunk)");
  const std::uint64_t n = static_cast<std::uint64_t>(t.num_particles);
  // Counts against the payload size before any allocation.
  const std::uint64_t need = 4ull * npieces + 12ull * ntri + ((flags & kTopoHasPieces) ? 4ull * ntri : 0) +
                             ((flags & kTopoHasUv) ? 16ull * n : 0);
  if (need > c.left()) short_payload();
  t.pieces.resize(npieces);
  for (auto& piece : t.pieces) {
    std::uint32_t len = 0;
    std::string_view s;
    if (!c.u32(len) || !c.bytes(len, s)) short_payload();
    piece.assign(s);
  }
  t.triangles.resize(ntri);
  for (std::uint32_t k = 0; k < ntri; ++k) {
    for (int j = 0; j < 3; ++j) {
      std::uint32_t v = 0;
      if (!c.u32(v)) short_payload();
      if (v >= n)
        fail(name, "triangle " + std::to_string(k),
             "corner " + std::to_string(v) + " is not a particle (" + std::to_string(n) + " particles; corrupt chunk)");
      t.triangles[k][j] = static_cast<int>(v);
    }
  }
  if (flags & kTopoHasPieces) {
    t.triangle_piece.resize(ntri);
    for (std::uint32_t k = 0; k < ntri; ++k) {
      std::uint32_t v = 0;
      if (!c.u32(v)) short_payload();
      if (v >= npieces)
        fail(name, "triangle " + std::to_string(k),
             "piece " + std::to_string(v) + " does not exist (" + std::to_string(npieces) + " pieces; corrupt chunk)");
      t.triangle_piece[k] = static_cast<int>(v);
    }
  }
  if (flags & kTopoHasUv) {
    t.uv.resize(n);
    for (auto& q : t.uv) {
      if (!c.f64(q[0]) || !c.f64(q[1])) short_payload();
      if (!std::isfinite(q[0]) || !std::isfinite(q[1]))
        fail(name, "topology", "a material coordinate is not a finite number (corrupt chunk)");
    }
  }
  if (c.left() != 0 && !newer_minor)
    fail(name, "topology", std::to_string(c.left()) + " bytes left over after the topology (corrupt chunk)");
}

}  // namespace

Topology parse_topology_payload(std::string_view payload, int num_particles, const std::string& file) {
  Topology t;
  t.num_particles = num_particles;
  parse_topology(file, payload, false, t);
  return t;
}

void TrjReader::open() {
  std::istream& in = *in_;
  in.seekg(0, std::ios::end);
  size_ = static_cast<std::uint64_t>(std::max<std::streamoff>(0, in.tellg()));
  std::string buf;

  // ---- header ----
  if (!read_at(in, 0, 8, buf) || !looks_like_trj(buf)) {
    // A .wvt (docs/formats/wvt.md) begins "\x89WVT".
    if (buf.size() >= 4 && buf.compare(0, 4, "\x89WVT") == 0)
      fail(name_, "header", "a compressed trajectory (.wvt), not a .trj: vgd decompress turns it into one");
    fail(name_, "header", "not a vgd trajectory: the file does not start with the .trj signature (bad magic)");
  }
  if (!read_at(in, 0, kHeaderSize, buf))
    fail(name_, "header", "the file ends inside the " + std::to_string(kHeaderSize) + "-byte header (" +
                              std::to_string(size_) + " bytes)");
  major_ = bin::get_u16(buf.data() + 8);
  minor_ = bin::get_u16(buf.data() + 10);
  if (major_ != kVersionMajor)
    fail(name_, "header",
         "format version " + std::to_string(major_) + "." + std::to_string(minor_) +
             (major_ > kVersionMajor ? " was written by a newer vgd; " : " is not supported; ") + "this vgd reads " +
             std::to_string(kVersionMajor) + ".x (unsupported version)");
  const bool newer_minor = minor_ > kVersionMinor;
  const std::uint32_t header_size = bin::get_u32(buf.data() + 12);
  const std::uint32_t n = bin::get_u32(buf.data() + 16);
  if (header_size < kHeaderSize || header_size > size_)
    fail(name_, "header", "header size " + std::to_string(header_size) + " is impossible (corrupt header)");
  if (n > kMaxParticles)
    fail(name_, "header", std::to_string(n) + " particles is more than a trajectory can hold (corrupt header)");
  topology_ = Topology{};
  topology_.num_particles = static_cast<int>(n);
  frames_.clear();
  warnings_ = Diagnostics{};
  complete_ = run_ok_ = false;

  const std::uint64_t frame_len = kFrameFixed + 12ull * n;
  std::uint64_t pos = header_size;
  bool have_topology = false;
  while (pos < size_) {
    const std::uint64_t left = size_ - pos;
    // A chunk header cut short, or a zero-filled tail: a write the crash tore.
    if (left < kChunkHeader) {
      if (!have_topology) fail(name_, "topology", "the file ends before the topology (truncated)");
      warnings_.warn(name_, "", "the file ends with " + std::to_string(left) +
                                    " bytes of an unfinished chunk; they were being written when the run stopped "
                                    "and are ignored (truncated)");
      break;
    }
    if (!read_at(in, pos, kChunkHeader, buf)) fail(name_, "", "cannot read " + offset_text(pos));
    char tag[4];
    std::memcpy(tag, buf.data(), 4);
    const std::uint32_t crc = bin::get_u32(buf.data() + 4);
    const std::uint64_t len = bin::get_u64(buf.data() + 8);
    const std::string what = "chunk " + offset_text(pos);
    if (!printable_tag(tag)) {
      if (have_topology && zero_tail(in, pos, size_)) {
        warnings_.warn(name_, "", "the file ends with " + std::to_string(left) +
                                      " zero bytes (a write torn by a crash); they are ignored (truncated)");
        break;
      }
      fail(name_, what, "not a chunk header (corrupt chunk)");
    }
    const std::string kind(tag, 4);
    if (!have_topology && kind != "TOPO") fail(name_, what, "the first chunk is '" + kind + "', not the topology (corrupt chunk)");
    if (complete_) {
      warnings_.warn(name_, what, std::to_string(left) + " bytes after the end marker are ignored");
      break;
    }
    // A chunk running past the end of the file: the last write, cut short.
    if (len > left - kChunkHeader) {
      if (!have_topology) fail(name_, "topology", "the topology chunk is truncated");
      if (kind == "FRAM" && len != frame_len)
        fail(name_, what, "a frame chunk of " + std::to_string(len) + " bytes; " + std::to_string(n) +
                              " particles need " + std::to_string(frame_len) + " (corrupt chunk)");
      warnings_.warn(name_, kind == "FRAM" ? "frame " + std::to_string(frames_.size()) : what,
                     "the last " + std::string(kind == "FRAM" ? "frame" : "chunk") + " is truncated (" +
                         std::to_string(left - kChunkHeader) + " of " + std::to_string(len) +
                         " bytes): it was being written when the run stopped and is dropped; " +
                         std::to_string(frames_.size()) + " frames are readable");
      break;
    }
    const std::uint64_t payload_at = pos + kChunkHeader;
    // Small chunks are read whole and checked now; frames only at their header (checked when read).
    auto read_payload = [&](std::string& p) {
      if (!read_at(in, payload_at, static_cast<std::size_t>(len), p)) fail(name_, what, "cannot read the chunk");
      if (bin::crc32(p) != crc) fail(name_, what, "'" + kind + "' chunk checksum mismatch (corrupt chunk)");
    };
    if (kind == "TOPO") {
      if (have_topology) fail(name_, what, "a second topology chunk (corrupt chunk)");
      std::string p;
      read_payload(p);
      parse_topology(name_, p, newer_minor, topology_);
      have_topology = true;
    } else if (kind == "FRAM") {
      if (len != frame_len)
        fail(name_, what, "a frame chunk of " + std::to_string(len) + " bytes; " + std::to_string(n) +
                              " particles need " + std::to_string(frame_len) + " (corrupt chunk)");
      if (!read_at(in, payload_at, kFrameFixed, buf)) fail(name_, what, "cannot read the chunk");
      const std::uint32_t index = bin::get_u32(buf.data());
      const double t = bin::get_f64(buf.data() + 8);
      if (index != frames_.size())
        fail(name_, what, "frame chunk numbered " + std::to_string(index) + " where frame " +
                              std::to_string(frames_.size()) + " belongs (corrupt chunk)");
      if (!std::isfinite(t)) fail(name_, "frame " + std::to_string(index), "the time is not a finite number (corrupt chunk)");
      frames_.push_back({payload_at, t, crc});
    } else if (kind == "MERG") {
      std::string p;
      read_payload(p);
      bin::Cursor c(p);
      std::uint32_t frame = 0, count = 0;
      if (!c.u32(frame) || !c.u32(count) || c.left() != 8ull * count || frame > 0x7FFFFFFFu)
        fail(name_, what, "a merge chunk whose size does not match its count (corrupt chunk)");
      for (std::uint32_t k = 0; k < count; ++k) {
        std::uint32_t a = 0, b = 0;
        c.u32(a);
        c.u32(b);
        if (a >= n || b >= n)
          fail(name_, what, "merge of particle " + std::to_string(a) + " into " + std::to_string(b) + ": only " +
                                std::to_string(n) + " particles (corrupt chunk)");
        topology_.merges.push_back({static_cast<int>(frame), static_cast<int>(a), static_cast<int>(b)});
      }
    } else if (kind == "END ") {
      std::string p;
      read_payload(p);
      if (p.size() < 8) fail(name_, what, "an end marker of " + std::to_string(p.size()) + " bytes (corrupt chunk)");
      if (bin::get_u32(p.data()) != frames_.size())
        fail(name_, what, "the end marker counts " + std::to_string(bin::get_u32(p.data())) + " frames; the file holds " +
                              std::to_string(frames_.size()) + " (corrupt chunk)");
      complete_ = true;
      run_ok_ = bin::get_u32(p.data() + 4) != 0;
    } else if (!newer_minor) {
      warnings_.warn(name_, what, "unknown chunk kind '" + kind + "' skipped");
    }
    pos = payload_at + len;
  }
  if (!have_topology) fail(name_, "topology", "the file ends before the topology (truncated)");
  // A run that never finished: its last frame may be a torn write of the right size.
  if (!complete_ && !frames_.empty()) {
    std::string p;
    const FrameRef& last = frames_.back();
    if (!read_at(in, last.offset, static_cast<std::size_t>(frame_len), p) || bin::crc32(p) != last.crc) {
      frames_.pop_back();
      warnings_.warn(name_, "frame " + std::to_string(frames_.size()),
                     "the last frame fails its checksum: it was being written when the run stopped and is dropped "
                     "(truncated)");
    }
  }
  if (!complete_)
    warnings_.warn(name_, "", "no end marker: the run that wrote this trajectory did not finish (it stopped, or is "
                              "still running); " + std::to_string(frames_.size()) + " whole frames are readable");
}

double TrjReader::time(int i) const {
  VGD_ASSERT(i >= 0 && i < frame_count(), "TrjReader::time: frame index out of range");
  return frames_[i].t;
}

double TrjReader::duration() const { return frames_.size() < 2 ? 0.0 : frames_.back().t - frames_.front().t; }

std::uint64_t TrjReader::position_bytes() const {
  return static_cast<std::uint64_t>(frames_.size()) * 12ull * static_cast<std::uint64_t>(topology_.num_particles);
}

std::vector<float> TrjReader::positions(int i) const {
  std::vector<float> out;
  positions(i, out);
  return out;
}

void TrjReader::positions(int i, std::vector<float>& out) const {
  VGD_ASSERT(i >= 0 && i < frame_count(), "TrjReader::positions: frame index out of range");
  const std::size_t n = 3 * static_cast<std::size_t>(topology_.num_particles);
  std::string p;
  if (!read_at(*in_, frames_[i].offset, kFrameFixed + 4 * n, p))
    fail(name_, "frame " + std::to_string(i), "cannot read the frame (the file shrank?)");
  if (bin::crc32(p) != frames_[i].crc) fail(name_, "frame " + std::to_string(i), "checksum mismatch (corrupt chunk)");
  out.resize(n);
  const char* src = p.data() + kFrameFixed;
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(out.data(), src, 4 * n);
  } else {
    for (std::size_t k = 0; k < n; ++k) out[k] = bin::get_f32(src + 4 * k);
  }
}

Trajectory TrjReader::read_all() const {
  Trajectory t;
  t.topology = topology_;
  t.times.reserve(frames_.size());
  t.frames.resize(frames_.size());
  for (int i = 0; i < frame_count(); ++i) {
    t.times.push_back(frames_[i].t);
    positions(i, t.frames[i]);
  }
  return t;
}

}  // namespace vgd::io::trj
