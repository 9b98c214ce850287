// The output commands end to end: a simulated trajectory compressed
// under a bound and decoded back within it (measured here, not taken from the
// encoder's report), the same trajectory exported as VRML (three flavours),
// glTF and OBJ, and bad inputs named with exit 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/trj/trj.hpp"

using namespace vgd;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// One second of the seed's flag (900 particles, 26 frames) as a .trj.
fs::path flag_trajectory(const fs::path& dir) {
  const auto trj = dir / "flag.trj";
  const auto r = test::run_vgd({"-q", "simulate", (test::source_dir() / "data/scenes/flag.json").string(),
                                "--duration", "1", "--trj", trj.string(), "-o", (dir / "frames").string()});
  EXPECT_EQ(r.code, 0) << r.err;
  return trj;
}

std::string head(const fs::path& file, std::size_t n) { return read_file(file).substr(0, n); }

}  // namespace

TEST(CmdOutputs, CompressThenDecompressStaysWithinTheBound) {
  const auto dir = test::scratch_dir("cmd_outputs_wvt");
  const auto trj = flag_trajectory(dir), wvt = dir / "flag.wvt", back = dir / "back.trj";
  for (const double bound_mm : {1.0, 0.1}) {
    SCOPED_TRACE(bound_mm);
    const auto c = test::run_vgd({"-q", "compress", trj.string(), "-o", wvt.string(), "--max-error-mm",
                                  std::to_string(bound_mm), "--json"});
    ASSERT_EQ(c.code, 0) << c.err;
    const json j = json::parse(c.out);
    EXPECT_EQ(j.at("frames"), 26);
    EXPECT_EQ(j.at("particles"), 900);
    EXPECT_LT(fs::file_size(wvt), fs::file_size(trj));
    const auto d = test::run_vgd({"-q", "decompress", wvt.string(), "-o", back.string()});
    ASSERT_EQ(d.code, 0) << d.err;
    // The decoded positions, frame by frame, against the original.
    const io::trj::TrjReader a(trj), b(back);
    ASSERT_EQ(b.frame_count(), a.frame_count());
    ASSERT_EQ(b.num_particles(), a.num_particles());
    double worst = 0;
    for (int f = 0; f < a.frame_count(); ++f) {
      EXPECT_DOUBLE_EQ(b.time(f), a.time(f));
      const auto pa = a.positions(f), pb = b.positions(f);
      for (std::size_t i = 0; i < pa.size(); i += 3)
        worst = std::max(worst, std::hypot(double(pa[i]) - pb[i], double(pa[i + 1]) - pb[i + 1],
                                           double(pa[i + 2]) - pb[i + 2]));
    }
    EXPECT_LE(worst * 1000.0, bound_mm * (1 + 1e-6));
    EXPECT_GT(worst, 0.0);  // lossy: the bound is used, not ignored
    EXPECT_NEAR(j.at("max_error_measured_mm").get<double>(), worst * 1000.0, 1e-3);
  }
  // Not a trajectory: named, exit 1, nothing written.
  const auto bad = test::run_vgd({"-q", "compress", (dir / "frames" / "frame_0000.obj").string(), "-o",
                                  (dir / "bad.wvt").string()});
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("frame_0000.obj"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("not a vgd trajectory"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad.wvt"));
}

TEST(CmdOutputs, ExportWritesEveryFormatOfATrajectory) {
  const auto dir = test::scratch_dir("cmd_outputs_export");
  const auto trj = flag_trajectory(dir);
  for (const char* flavour : {"static", "animated", "live"}) {
    SCOPED_TRACE(flavour);
    const auto wrl = dir / (std::string(flavour) + ".wrl");
    const auto r = test::run_vgd({"-q", "export", trj.string(), "--vrml", flavour, "-o", wrl.string()});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string text = read_file(wrl);
    EXPECT_EQ(text.rfind("#VRML V2.0 utf8", 0), 0u);
    EXPECT_NE(text.find("IndexedFaceSet"), std::string::npos);
    if (std::string(flavour) == "animated") {
      EXPECT_NE(text.find("CoordinateInterpolator"), std::string::npos);
      EXPECT_NE(text.find("TimeSensor"), std::string::npos);
    }
    if (std::string(flavour) == "live") {
      EXPECT_NE(text.find("Script"), std::string::npos);
    }
  }
  const auto glb = dir / "flag.glb", obj = dir / "flag.obj";
  const auto r = test::run_vgd({"-q", "export", trj.string(), "--gltf", glb.string(), "--obj", obj.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(head(glb, 4), "glTF");  // the binary glTF magic
  const std::string o = read_file(obj);
  EXPECT_EQ(std::count(o.begin(), o.end(), '\n') > 900, true);
  EXPECT_NE(o.find("\nv "), std::string::npos);
  EXPECT_NE(o.find("\nf "), std::string::npos);
  // A missing input: named, exit 1.
  const auto missing = test::run_vgd({"-q", "export", (dir / "nope.trj").string(), "-o", (dir / "x.wrl").string()});
  EXPECT_NE(missing.code, 0);
  EXPECT_NE(missing.err.find("nope.trj"), std::string::npos) << missing.err;
}
