#pragma once
// Wavelet-compressed trajectories (seed 002 §3.3.1, the .wvt file): the
// positions of a .trj quantised on a uniform grid fine enough that no vertex
// moves by more than the user's bound, transformed along time with a
// reversible integer wavelet and entropy coded with zstd. The topology, the
// seam merges and the frame times are kept exactly. Byte layout and the
// measured ratio against the bound: docs/formats/wvt.md.
//
//   trj::Trajectory t = trj::TrjReader("skirt.trj").read_all();
//   wvt::EncodeStats stats;
//   wvt::write_wvt("skirt.wvt", t, {.max_error_m = 0.001}, &stats);
//   trj::Trajectory back = wvt::read_wvt("skirt.wvt");   // same topology and times
//
// The bound is guaranteed, not assumed: encode() decodes what it produced and
// measures the largest vertex distance; stats.max_error_m is that measurement.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "vgd/io/trj/trj.hpp"

namespace vgd::io::wvt {

inline constexpr int kVersionMajor = 1;
inline constexpr int kVersionMinor = 0;

struct EncodeOptions {
  // Largest allowed distance (m) between a decoded vertex and the original
  // float32 one, over every particle and frame. Typical 0.001 (1 mm); at
  // least 1e-7.
  double max_error_m = 0.001;
  // Wavelet levels along time; -1 chooses by measurement: encodes with as
  // many levels as the frame count allows and with none (prediction across
  // the mesh alone), and keeps the smaller.
  int levels = -1;
  // zstd level (1 fast … 19 small).
  int zstd_level = 19;
  // The reversible integer wavelet along time (docs/formats/wvt.md compares them).
  enum class Transform { haar = 1, cdf53 = 2 };
  Transform transform = Transform::cdf53;
  // Prediction across particles: each particle's coefficients minus those of
  // its neighbour on a spanning tree of the mesh (a merged copy: minus its
  // representative's), in no band, the coarsest band only, or every band.
  enum class Spatial { none = 0, coarse = 1, all = 2 };
  Spatial spatial = Spatial::all;
  // What the trajectory is called in messages (the file it was read from).
  std::string source = "the trajectory";
};

// What an encoding did (sizes in bytes, times in seconds).
struct EncodeStats {
  std::uint64_t position_bytes = 0;         // the .trj position payload: frames × particles × 3 × 4
  std::uint64_t position_stream_bytes = 0;  // the compressed positions in the .wvt
  std::uint64_t output_bytes = 0;           // the whole .wvt (header, topology, times, positions)
  double step_m = 0.0;                      // quantisation step per coordinate
  int levels = 0;                           // wavelet levels along time used
  double max_error_m = 0.0;                 // measured on the decoded result
  int attempts = 0;                         // encodings until the bound held (1 normally)
  double seconds = 0.0;                     // encode + verification
};

// Encodes a trajectory. Throws vgd::Error (file options.source) for a
// non-finite position or a bound too small for the trajectory's extent.
std::string encode(const trj::Trajectory& trajectory, const EncodeOptions& options, EncodeStats* stats = nullptr);

// Decodes a .wvt held in memory. Throws vgd::Error naming `name` for bad
// magic, a newer major version or a corrupt section.
trj::Trajectory decode(std::string_view bytes, const std::string& name = "<memory>");

// encode() + vgd::write_file_atomic.
void write_wvt(const std::filesystem::path& file, const trj::Trajectory& trajectory, const EncodeOptions& options,
               EncodeStats* stats = nullptr);
trj::Trajectory read_wvt(const std::filesystem::path& file);

// What the header of a .wvt says (no decoding of positions).
struct Info {
  int version_major = 0, version_minor = 0;
  int num_particles = 0, num_triangles = 0, num_pieces = 0, num_merges = 0;
  int frame_count = 0;
  double first_time = 0.0, last_time = 0.0;  // s
  double max_error_m = 0.0;                  // the bound it was encoded with (m)
  double measured_error_m = 0.0;             // the error measured when it was encoded (m)
  double step_m = 0.0;                       // quantisation step (m)
  int levels = 0;                            // wavelet levels along time
  std::uint64_t file_size = 0;
  std::uint64_t position_stream_bytes = 0;
};
Info read_info(std::string_view bytes, const std::string& name = "<memory>");

// The largest distance (m) between corresponding vertices of two
// trajectories with the same particle and frame counts.
double max_vertex_error(const trj::Trajectory& a, const trj::Trajectory& b);

// True when `bytes` begin with the .wvt magic.
bool looks_like_wvt(std::string_view bytes);
// True when the file begins with the .wvt magic (false when it cannot be
// read: the reader that opens it next says why).
bool is_wvt_file(const std::filesystem::path& file);

// A .trj or a .wvt (told apart by content), whole, in memory.
trj::Trajectory read_trajectory(const std::filesystem::path& file);

}  // namespace vgd::io::wvt
