// Start-up: the heavy libraries are opened by the commands that use them, not
// by every command. OSMesa (which brings LLVM) is opened when the first
// off-screen context is made, assimp (in the vgd_assimp module) when the
// first body file is read; `vgd --version` and `vgd import` open neither.
// (The time itself is measured by tests/bench/startup.sh, not here.)
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"

namespace vgd::test {
namespace {

// The shared objects the dynamic loader opens for `vgd ARGS` (LD_DEBUG=files
// prints one "file=<name> [0];  needed by ..." or "... dynamically loaded by"
// line per object on stderr).
std::string loaded_by(const std::vector<std::string>& args) {
  ::setenv("LD_DEBUG", "files", 1);
  const CliResult r = run_vgd(args);
  ::unsetenv("LD_DEBUG");
  EXPECT_EQ(r.code, 0) << r.err.substr(r.err.size() > 2000 ? r.err.size() - 2000 : 0);
  return r.err;
}

bool opened(const std::string& log, const std::string& name) { return log.find("file=" + name) != std::string::npos; }

TEST(Startup, VersionOpensNeitherOSMesaNorAssimp) {
  const std::string log = loaded_by({"--version"});
  ASSERT_TRUE(opened(log, "libstdc++")) << "LD_DEBUG gave no list of files";
  EXPECT_FALSE(opened(log, "libOSMesa"));
  EXPECT_FALSE(opened(log, "libLLVM"));
  EXPECT_FALSE(opened(log, "libassimp"));
  EXPECT_FALSE(opened(log, "libvgd_assimp"));
}

TEST(Startup, ImportOpensNeitherOSMesaNorAssimp) {
  const auto dir = scratch_dir("startup-import");
  const std::string log = loaded_by({"import", (source_dir() / "data/garments/a-line-skirt.dxf").string(), "-o",
                                     (dir / "skirt.xvc").string(), "-q"});
  EXPECT_FALSE(opened(log, "libOSMesa"));
  EXPECT_FALSE(opened(log, "libassimp"));
}

// The other side: the commands that need them open them, and work.
TEST(Startup, ABodyFileOpensTheAssimpModule) {
  const auto dir = scratch_dir("startup-avatar");
  ASSERT_EQ(run_vgd({"mannequin", "--size", "38", "--triangles", "5000", "-o", (dir / "body.obj").string(), "-q"}).code, 0);
  const std::string log = loaded_by({"avatar", "report", (dir / "body.obj").string()});
  EXPECT_TRUE(opened(log, std::string(VGD_BINARY_DIR) + "/src/body/libvgd_assimp.so") ||
              log.find("libvgd_assimp.so") != std::string::npos);
  EXPECT_TRUE(opened(log, "libassimp"));
  EXPECT_FALSE(opened(log, "libOSMesa"));
}

}  // namespace
}  // namespace vgd::test
