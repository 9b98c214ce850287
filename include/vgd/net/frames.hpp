#pragma once
// Live frames of a running job (docs/server.md, "Live frames"): what the
// WebSocket at /v1/jobs/{id}/frames sends. The worker writes the job's
// trajectory (.trj) as it runs; each viewer reads it on its own, so a slow
// viewer never slows the simulation and never changes the stored result.
//
// Messages, in order:
//   text    {"type": "topology", "particles": N, "triangles": [i0, j0, k0, i1, ...], "pieces": [...],
//            "triangle_piece": [...]}
//   binary  a frame: "VGDF", u32 seq (the frame's index in the trajectory), f64 t (s), u32 count
//           (3N), u32 crc32 (of the positions' bytes, as .trj chunks), then count float32
//           positions (m; x0 y0 z0 x1 ...); little-endian. A viewer that joins late gets the
//           latest frame first, then the live ones.
//   text    {"type": "progress", "progress": {"stage", "simulated_s", "seams_closed", "seam_pairs",
//            "kinetic_energy_j", "wall_s"}}: when it changes, while the job runs
//   text    {"type": "dropped", "count": k, "total": K}: frames this viewer skipped because it
//           read slower than they came (the trajectory keeps them all)
//   text    {"type": "end", "state": "passed", "frames": F, "sent": S, "dropped": K}
#include <cstdint>
#include <string>
#include <vector>

#include "vgd/io/trj/trj.hpp"

namespace vgd::net {

std::string topology_message(const io::trj::Topology& topology);
std::string frame_message(std::uint32_t seq, double t, const std::vector<float>& positions);

struct FrameMessage {
  std::uint32_t seq = 0;
  double t = 0.0;
  std::vector<float> positions;
  bool checksum_ok = false;
};
// Parses a binary frame message; throws vgd::Error when it is not one.
FrameMessage parse_frame_message(const std::string& bytes);

}  // namespace vgd::net
