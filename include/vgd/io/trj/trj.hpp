#pragma once
// Trajectories (seed 002 §3.3.1): the .trj binary file of a simulation run —
// the cloth's topology once, then every frame's positions (float32, metres)
// and time, appended while the run goes so a crash loses at most the frame
// being written. Byte layout, versioning and crash behaviour:
// docs/formats/trj.md.
//
//   TrjReader r("skirt.trj");                 // throws vgd::Error for bad input
//   const Topology& topo = r.topology();      // particles, triangles, pieces, uv, merges
//   for (int i = 0; i < r.frame_count(); ++i) {
//     double t = r.time(i);                    // s
//     std::vector<float> x = r.positions(i);   // 3N: x0 y0 z0 x1 ... (m)
//   }
//   r.warnings();                              // e.g. "the last frame is truncated"
//
// Writing: TrjWriter is a sim::FrameSink (pass it to sim::run or
// dress::run_drape), or feed it frames yourself (begin(Topology), add_frame).
// It writes `file.partial` and renames it to `file` at end(): a crashed run
// leaves the .partial file, which TrjReader reads up to its last whole frame.
//
// This stage sees only what the engine hands a frame sink: the model's
// topology (triangles, pieces, material coordinates) and positions.
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <istream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/sim/run.hpp"

namespace vgd::io::trj {

// The format version this library writes. A reader accepts every file of the
// same major version (a newer minor version only adds chunk kinds, which are
// skipped) and refuses a newer major version with a named error.
inline constexpr int kVersionMajor = 1;
inline constexpr int kVersionMinor = 0;

// One seam merge (seed 002 §3.3): from frame `frame` on, `particle` is a copy
// of `representative` (same position). Indices are the model's original
// particles; `representative` is the lowest-numbered particle of its group.
struct Merge {
  int frame = 0;
  int particle = 0;
  int representative = 0;
  bool operator==(const Merge&) const = default;
};

// What does not change from frame to frame.
struct Topology {
  int num_particles = 0;
  std::vector<std::array<int, 3>> triangles;  // particle indices, counter-clockwise in material space
  std::vector<int> triangle_piece;            // piece index of each triangle (empty when the model has none)
  std::vector<std::string> pieces;            // piece names
  // Material (pattern) coordinates of each particle, m: u along the warp
  // (grain line), v along the weft. Empty when the model has none.
  std::vector<std::array<double, 2>> uv;
  // Seam merges in frame order (several per frame possible). A later entry
  // for the same particle supersedes an earlier one.
  std::vector<Merge> merges;

  // For every particle, the particle it is a copy of at `frame` (itself when
  // not merged): the merges with m.frame <= frame applied in order.
  std::vector<int> representatives(int frame) const;
  bool operator==(const Topology&) const = default;
};

// The topology of a model (no merges: those come while the run goes).
Topology topology_of(const sim::Model& model);

// The TOPO chunk payload of a topology (docs/formats/trj.md), merges left
// out; formats that embed a topology (.wvt) reuse it.
std::string topology_payload(const Topology& topology);
// Parses a TOPO payload for `num_particles` particles. Throws vgd::Error
// naming `file` when it is corrupt.
Topology parse_topology_payload(std::string_view payload, int num_particles, const std::string& file);

// A whole trajectory in memory (what the wavelet codec and `vgd decompress` use).
struct Trajectory {
  Topology topology;
  std::vector<double> times;               // s, one per frame
  std::vector<std::vector<float>> frames;  // 3N float32 positions (m) per frame
  int frame_count() const { return static_cast<int>(frames.size()); }
};

// ---------------------------------------------------------------------------
// Writing

struct WriterOptions {
  // fsync after every frame as well as at the end (survives a power loss, not
  // only a crash of vgd; costs a disk flush per frame). Every frame is always
  // flushed to the operating system before the next one is computed.
  bool sync_every_frame = false;
};

// Appends a trajectory chunk by chunk. As a sim::FrameSink: begin() creates
// `file.partial` (and missing parent folders) and writes the header and
// topology; merged() and frame() append one chunk each and flush it; end()
// writes the end marker and renames `file.partial` to `file`. When the run
// failed (`ok` false) the frames before the failure are valid but do not
// replace `file`: they go to failed_path() (`out.trj` -> `out.failed.trj`),
// and written() says which. One writer records one run. Throws vgd::Error naming the file when it cannot
// write.
class TrjWriter : public sim::FrameSink {
 public:
  explicit TrjWriter(std::filesystem::path file, WriterOptions options = {});
  ~TrjWriter() override;  // a writer never ended leaves `file.partial` (a crash looks the same)
  std::filesystem::path failed_path() const;
  const std::filesystem::path& written() const { return written_; }  // empty before end()
  TrjWriter(const TrjWriter&) = delete;
  TrjWriter& operator=(const TrjWriter&) = delete;

  // ---- sim::FrameSink ----
  void begin(const sim::Model& model) override;
  void merged(int frame, const std::vector<int>& representative) override;
  void frame(int index, double t, const sim::VecX& x) override;
  void end(bool ok) override;

  // ---- without the engine ----
  void begin(const Topology& topology);  // topology.merges are written as merge chunks before frame 0
  // Merges taking effect at `frame` (usually the next frame to be added).
  void add_merges(int frame, const std::vector<Merge>& merges);
  void add_frame(double t, const float* positions);  // 3N floats (m)
  void add_frame(double t, const std::vector<float>& positions);
  void finish() { end(true); }

  const std::filesystem::path& path() const { return file_; }
  std::filesystem::path partial_path() const;
  int frames_written() const { return frames_; }
  std::uint64_t bytes_written() const { return bytes_; }

 private:
  void write_chunk(const char tag[4], const std::string& payload);
  void flush_chunk();

  std::filesystem::path file_, written_;
  WriterOptions options_;
  std::FILE* out_ = nullptr;
  int num_particles_ = 0;
  int frames_ = 0;
  std::uint64_t bytes_ = 0;
  std::vector<int> rep_;  // representatives written so far (merges are written as changes)
  std::vector<float> scratch_;
};

// Writes a whole trajectory (through TrjWriter: `file.partial`, then rename).
void write_trj(const std::filesystem::path& file, const Trajectory& trajectory);

// ---------------------------------------------------------------------------
// Reading

// Opens a .trj: reads the header and topology and scans the chunk headers
// to index the frames (random access by frame index afterwards). Throws
// vgd::Error naming the file, what and the problem for a file that is not a
// trajectory, a newer major version, or a corrupt chunk. A truncated last
// frame (a run that crashed while writing it) is dropped with a warning; a
// file without the end marker (a run that never finished) reads with a
// warning.
class TrjReader {
 public:
  explicit TrjReader(const std::filesystem::path& file);
  // From bytes in memory; `name` stands for the file in messages.
  static TrjReader from_bytes(std::string bytes, std::string name = "<memory>");
  ~TrjReader();
  TrjReader(TrjReader&&) noexcept;
  TrjReader& operator=(TrjReader&&) noexcept;

  const Topology& topology() const { return topology_; }
  int num_particles() const { return topology_.num_particles; }
  int frame_count() const { return static_cast<int>(frames_.size()); }
  double time(int i) const;                  // s
  std::vector<float> positions(int i) const;  // 3N float32 (m); throws vgd::Error if the frame's checksum fails
  void positions(int i, std::vector<float>& out) const;
  // Seconds from the first frame to the last (0 for fewer than two frames).
  double duration() const;
  // True when the writer ended the file (end marker present).
  bool complete() const { return complete_; }
  // The end marker's verdict: false when the run that wrote the file failed.
  bool run_ok() const { return run_ok_; }
  int version_major() const { return major_; }
  int version_minor() const { return minor_; }
  std::uint64_t file_size() const { return size_; }
  // Bytes of per-frame positions (frame_count × 3N × 4): what compression ratios are measured against.
  std::uint64_t position_bytes() const;
  const Diagnostics& warnings() const { return warnings_; }
  const std::string& name() const { return name_; }

  // Every frame in memory.
  Trajectory read_all() const;

 private:
  TrjReader() = default;
  void open();

  struct FrameRef {
    std::uint64_t offset = 0;  // of the positions in the file
    double t = 0.0;
    std::uint32_t crc = 0;
  };
  std::string name_;
  std::unique_ptr<std::istream> in_;
  Topology topology_;
  std::vector<FrameRef> frames_;
  Diagnostics warnings_;
  std::uint64_t size_ = 0;
  int major_ = 0, minor_ = 0;
  bool complete_ = false, run_ok_ = false;
};

// True when `bytes` begin with the .trj magic (a quick content check).
bool looks_like_trj(std::string_view bytes);

}  // namespace vgd::io::trj
