// Trajectory files (.trj): what is written reads back bit for bit (float32
// positions, times, topology, merges), frames read in any order, a run
// records its frames and the merges its seams made, a crashed run's file
// reads up to its last whole frame with a warning, and bad input is named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "support/errors.hpp"
#include "sim/helpers.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/seam.hpp"
#include "vgd/sim/run.hpp"

using namespace vgd;
using io::trj::Merge;
using io::trj::Topology;
using io::trj::Trajectory;
using io::trj::TrjReader;
using io::trj::TrjWriter;
namespace fs = std::filesystem;

namespace {

// Bytes of the fixed header and of a chunk header (docs/formats/trj.md).
constexpr std::size_t kHeader = 32, kChunkHeader = 16;

// A small trajectory with every kind of content: two pieces, uv, merges at
// two frames, positions that are not round numbers (negative, tiny, large).
Trajectory sample(int frames = 12) {
  Trajectory t;
  Topology& topo = t.topology;
  topo.num_particles = 6;
  topo.triangles = {{0, 1, 2}, {1, 3, 2}, {3, 4, 5}};
  topo.triangle_piece = {0, 0, 1};
  topo.pieces = {"front", "back piece"};
  for (int i = 0; i < 6; ++i) topo.uv.push_back({0.1 * i, -0.05 * i * i});
  topo.merges = {{3, 4, 1}, {7, 5, 2}, {7, 3, 1}};
  for (int k = 0; k < frames; ++k) {
    t.times.push_back(k / 30.0);
    std::vector<float> x(18);
    for (int i = 0; i < 18; ++i) x[i] = static_cast<float>(std::sin(0.37 * i + 0.11 * k) * (i % 3 == 2 ? 1e-7 : 1.7) - 0.25 * k);
    t.frames.push_back(x);
  }
  return t;
}

using vgd::test::error_of;

bool has_warning(const TrjReader& r, const std::string& word) {
  for (const auto& d : r.warnings().items())
    if (d.severity == Severity::warning && d.message.find(word) != std::string::npos) return true;
  return false;
}

void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Where frame k's chunk starts in a file of sample() written without merges.
std::size_t frame_chunk(const Topology& topo, int k) {
  return kHeader + kChunkHeader + io::trj::topology_payload(topo).size() +
         k * (kChunkHeader + 16 + 12 * static_cast<std::size_t>(topo.num_particles));
}

}  // namespace

TEST(TrjFile, RoundTripIsExactForPositionsTimesTopologyAndMerges) {
  const auto dir = test::scratch_dir("trj_roundtrip");
  const Trajectory t = sample();
  io::trj::write_trj(dir / "a.trj", t);
  EXPECT_FALSE(fs::exists(dir / "a.trj.partial"));
  const TrjReader r(dir / "a.trj");
  EXPECT_TRUE(r.warnings().empty());
  EXPECT_TRUE(r.complete());
  EXPECT_TRUE(r.run_ok());
  EXPECT_EQ(r.version_major(), io::trj::kVersionMajor);
  EXPECT_EQ(r.topology(), t.topology);
  ASSERT_EQ(r.frame_count(), t.frame_count());
  for (int k = 0; k < r.frame_count(); ++k) {
    EXPECT_EQ(r.time(k), t.times[k]);  // bit for bit
    const auto x = r.positions(k);
    ASSERT_EQ(x.size(), t.frames[k].size());
    EXPECT_EQ(std::memcmp(x.data(), t.frames[k].data(), 4 * x.size()), 0) << "frame " << k;
  }
  EXPECT_EQ(r.position_bytes(), 12u * 6u * 12u);
  EXPECT_DOUBLE_EQ(r.duration(), 11 / 30.0);
  EXPECT_EQ(r.file_size(), fs::file_size(dir / "a.trj"));
  // Merges in force at a frame: none before 3, particle 4 from 3, the rest from 7.
  EXPECT_EQ(r.topology().representatives(2), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(r.topology().representatives(3), (std::vector<int>{0, 1, 2, 3, 1, 5}));
  EXPECT_EQ(r.topology().representatives(7), (std::vector<int>{0, 1, 2, 1, 1, 2}));
}

TEST(TrjFile, FramesReadInAnyOrder) {
  const auto dir = test::scratch_dir("trj_random");
  const Trajectory t = sample(40);
  io::trj::write_trj(dir / "r.trj", t);
  const TrjReader r(dir / "r.trj");
  for (int k : {37, 2, 19, 0, 39, 19}) {
    EXPECT_EQ(r.positions(k), t.frames[k]) << "frame " << k;
    EXPECT_EQ(r.time(k), t.times[k]);
  }
  // From bytes in memory as from a file.
  const TrjReader m = TrjReader::from_bytes(read_file(dir / "r.trj"), "mem.trj");
  EXPECT_EQ(m.positions(33), t.frames[33]);
  EXPECT_EQ(m.read_all().frames, t.frames);
}

TEST(TrjFile, ARunRecordsItsFramesAndTheMergesItsSeamsMade) {
  // Two 3 × 4 grids 3 cm apart, sewn along the gap: the seam pulls the pairs
  // together and merges them during the run.
  const int nu = 3, nv = 4;
  const sim::Model m = sim::test::two_grids(nu, nv, 0.03);
  sim::SeamDef def;
  sim::SeamPairs side{"side", {}};
  for (int j = 0; j < nv; ++j) side.pairs.push_back({j * nu + nu - 1, nu * nv + j * nu});
  def.seams = {side};
  def.max_force = 0.5;
  sim::MassSpringMaterial mat;
  mat.warp = mat.weft = 50.0;
  mat.shear = mat.bend_warp = mat.bend_weft = 10.0;
  mat.damping = 0.05;
  sim::System sys(m, sim::test::effects(sim::make_mass_spring(m, {mat}), sim::make_seam(m, def)));
  auto integrator = sim::make_integrator({});
  sim::State s = sim::initial_state(m);
  const auto dir = test::scratch_dir("trj_run");
  TrjWriter writer(dir / "run.trj");
  sim::MemorySink memory;
  const auto summary = sim::run(sys, *integrator, s, {30.0, 2.0}, {&writer, &memory});
  ASSERT_TRUE(summary.ok) << summary.error;
  ASSERT_TRUE(sys.merged()) << "the seam should have closed within 2 s";

  const TrjReader r(dir / "run.trj");
  EXPECT_TRUE(r.warnings().empty());
  EXPECT_EQ(r.topology().triangles, m.triangles);
  EXPECT_EQ(r.topology().pieces, m.pieces);
  ASSERT_EQ(r.topology().uv.size(), m.uv.size());
  EXPECT_EQ(r.topology().uv[7][0], m.uv[7].x());
  // Every frame the run emitted, rounded to float32 and nothing else.
  ASSERT_EQ(r.frame_count(), static_cast<int>(memory.frames.size()));
  for (int k = 0; k < r.frame_count(); ++k) {
    EXPECT_EQ(r.time(k), memory.times[k]);
    const auto x = r.positions(k);
    for (int i = 0; i < m.num_dofs(); ++i) ASSERT_EQ(x[i], static_cast<float>(memory.frames[k][i])) << k << " " << i;
  }
  // One merge per seam pair: B's left column became copies of A's right column,
  // and from its merge frame on a copy sits exactly where its representative is.
  ASSERT_EQ(r.topology().merges.size(), static_cast<std::size_t>(nv));
  for (const Merge& mg : r.topology().merges) {
    EXPECT_GT(mg.frame, 0);
    EXPECT_LT(mg.representative, mg.particle);
    for (int k = mg.frame; k < r.frame_count(); ++k) {
      const auto x = r.positions(k);
      for (int a = 0; a < 3; ++a) EXPECT_EQ(x[3 * mg.particle + a], x[3 * mg.representative + a]);
    }
    // The frame before: still apart.
    const auto before = r.positions(mg.frame - 1);
    EXPECT_NE(before[3 * mg.particle], before[3 * mg.representative]);
  }
  const auto rep = r.topology().representatives(r.frame_count() - 1);
  for (const auto& pair : side.pairs) EXPECT_EQ(rep[pair[1]], pair[0]);
}

TEST(TrjFile, ACrashedRunLeavesAPartialFileThatReadsWithAWarning) {
  const auto dir = test::scratch_dir("trj_crash");
  const Trajectory t = sample();
  {
    TrjWriter w(dir / "c.trj");
    w.begin(t.topology);
    for (int k = 0; k < 5; ++k) w.add_frame(t.times[k], t.frames[k]);
    // Destroyed without end(): what a crash leaves.
  }
  EXPECT_FALSE(fs::exists(dir / "c.trj"));
  ASSERT_TRUE(fs::exists(dir / "c.trj.partial"));
  const TrjReader r(dir / "c.trj.partial");
  EXPECT_FALSE(r.complete());
  EXPECT_EQ(r.frame_count(), 5);
  EXPECT_EQ(r.positions(4), t.frames[4]);
  EXPECT_TRUE(has_warning(r, "no end marker")) << r.warnings().items().size();
  EXPECT_EQ(r.warnings().count(Severity::error), 0u);
}

TEST(TrjFile, ATruncatedLastFrameIsDroppedWithAWarning) {
  const auto dir = test::scratch_dir("trj_truncated");
  Trajectory t = sample();
  t.topology.merges.clear();
  io::trj::write_trj(dir / "full.trj", t);
  const std::string bytes = read_file(dir / "full.trj");
  // Cut inside frame 9 (of 12): frames 0–8 stay.
  const std::size_t cut = frame_chunk(t.topology, 9) + 40;
  write_bytes(dir / "cut.trj", bytes.substr(0, cut));
  const TrjReader r(dir / "cut.trj");
  EXPECT_EQ(r.frame_count(), 9);
  EXPECT_TRUE(has_warning(r, "truncated"));
  EXPECT_EQ(r.positions(8), t.frames[8]);
  // Cut inside a chunk header.
  write_bytes(dir / "cut2.trj", bytes.substr(0, frame_chunk(t.topology, 4) + 5));
  const TrjReader r2(dir / "cut2.trj");
  EXPECT_EQ(r2.frame_count(), 4);
  EXPECT_TRUE(has_warning(r2, "truncated"));
  // A zero-filled tail (a file system's torn write after a crash).
  write_bytes(dir / "zeros.trj", bytes.substr(0, frame_chunk(t.topology, 6)) + std::string(300, '\0'));
  const TrjReader r3(dir / "zeros.trj");
  EXPECT_EQ(r3.frame_count(), 6);
  EXPECT_TRUE(has_warning(r3, "torn"));
  // A last frame of the right size whose bytes never all arrived: its checksum fails.
  std::string torn = bytes.substr(0, frame_chunk(t.topology, 10));
  torn[frame_chunk(t.topology, 9) + kChunkHeader + 20] ^= 0x5A;
  write_bytes(dir / "torn.trj", torn);
  const TrjReader r4(dir / "torn.trj");
  EXPECT_EQ(r4.frame_count(), 9);
  EXPECT_TRUE(has_warning(r4, "checksum"));
}

TEST(TrjFile, AFailedRunEndsItsFileBesideTheCompleteOneAndSaysSo) {
  const auto dir = test::scratch_dir("trj_failed");
  const Trajectory t = sample();
  {  // a complete trajectory from an earlier run
    TrjWriter w(dir / "f.trj");
    w.begin(t.topology);
    for (const auto& f : t.frames) w.add_frame(0.0, f);
    w.end(true);
    EXPECT_EQ(w.written(), dir / "f.trj");
  }
  TrjWriter w(dir / "f.trj");
  w.begin(t.topology);
  w.add_frame(0.0, t.frames[0]);
  w.end(false);
  EXPECT_EQ(w.written(), dir / "f.failed.trj");
  EXPECT_FALSE(std::filesystem::exists(dir / "f.trj.partial"));
  const TrjReader kept(dir / "f.trj");
  EXPECT_TRUE(kept.run_ok());
  EXPECT_EQ(kept.frame_count(), static_cast<int>(t.frames.size()));
  const TrjReader r(dir / "f.failed.trj");
  EXPECT_TRUE(r.complete());
  EXPECT_FALSE(r.run_ok());
  EXPECT_EQ(r.frame_count(), 1);
}

TEST(TrjFile, NotATrajectoryIsNamedAsBadMagic) {
  const auto dir = test::scratch_dir("trj_magic");
  write_bytes(dir / "x.trj", "solid cube\nfacet normal 0 0 1\n");
  const auto d = error_of([&] { TrjReader r(dir / "x.trj"); });
  EXPECT_EQ(d.file, (dir / "x.trj").string());
  EXPECT_EQ(d.entity, "header");
  EXPECT_NE(d.message.find("bad magic"), std::string::npos) << d.message;
  write_bytes(dir / "empty.trj", "");
  EXPECT_NE(error_of([&] { TrjReader r(dir / "empty.trj"); }).message.find("bad magic"), std::string::npos);
  EXPECT_NE(error_of([&] { TrjReader r(dir / "missing.trj"); }).message.find("cannot open"), std::string::npos);
}

TEST(TrjFile, ANewerMajorVersionIsRefusedNamingIt) {
  const auto dir = test::scratch_dir("trj_version");
  io::trj::write_trj(dir / "a.trj", sample());
  std::string bytes = read_file(dir / "a.trj");
  bytes[8] = 2;  // major version 2
  write_bytes(dir / "v2.trj", bytes);
  const auto d = error_of([&] { TrjReader r(dir / "v2.trj"); });
  EXPECT_NE(d.message.find("version 2.0"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("newer"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("unsupported version"), std::string::npos) << d.message;
  // A newer minor version reads (it only adds chunk kinds).
  bytes[8] = 1;
  bytes[10] = 7;
  write_bytes(dir / "v1_7.trj", bytes);
  EXPECT_EQ(TrjReader(dir / "v1_7.trj").frame_count(), 12);
}

TEST(TrjFile, CorruptChunksAreNamed) {
  const auto dir = test::scratch_dir("trj_corrupt");
  Trajectory t = sample();
  t.topology.merges.clear();
  io::trj::write_trj(dir / "a.trj", t);
  const std::string bytes = read_file(dir / "a.trj");

  // A flipped byte in the topology: refused on open.
  std::string topo = bytes;
  topo[kHeader + kChunkHeader + 30] ^= 0x01;
  write_bytes(dir / "topo.trj", topo);
  const auto d1 = error_of([&] { TrjReader r(dir / "topo.trj"); });
  EXPECT_NE(d1.message.find("corrupt chunk"), std::string::npos) << d1.message;
  EXPECT_NE(d1.entity.find("chunk at byte 32"), std::string::npos) << d1.entity;

  // A flipped byte in frame 3's positions: the frame refuses to read, the others read.
  std::string frame = bytes;
  frame[frame_chunk(t.topology, 3) + kChunkHeader + 16 + 5] ^= 0x20;
  write_bytes(dir / "frame.trj", frame);
  const TrjReader r(dir / "frame.trj");
  EXPECT_EQ(r.positions(2), t.frames[2]);
  const auto d2 = error_of([&] { r.positions(3); });
  EXPECT_EQ(d2.entity, "frame 3");
  EXPECT_NE(d2.message.find("checksum"), std::string::npos) << d2.message;

  // A frame chunk claiming another length in mid-file.
  std::string length = bytes;
  length[frame_chunk(t.topology, 2) + 8] ^= 0x04;
  write_bytes(dir / "length.trj", length);
  const auto d3 = error_of([&] { TrjReader x(dir / "length.trj"); });
  EXPECT_NE(d3.message.find("corrupt chunk"), std::string::npos) << d3.message;

  // Garbage where a chunk header belongs.
  std::string garbage = bytes;
  garbage[frame_chunk(t.topology, 5)] = '\x01';
  write_bytes(dir / "garbage.trj", garbage);
  const auto d4 = error_of([&] { TrjReader x(dir / "garbage.trj"); });
  EXPECT_NE(d4.message.find("not a chunk header"), std::string::npos) << d4.message;

  // A header cut short.
  write_bytes(dir / "short.trj", bytes.substr(0, 20));
  EXPECT_NE(error_of([&] { TrjReader x(dir / "short.trj"); }).message.find("header"), std::string::npos);
}
