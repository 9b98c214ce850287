#pragma once
// Where tests find their inputs. Shared third-party data (../shared) is never
// copied into the repository: tests that need it call VGD_REQUIRE_SHARED() and
// are skipped, with a visible message, when it is absent.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace vgd::test {

inline std::filesystem::path source_dir() { return VGD_SOURCE_DIR; }
inline std::filesystem::path binary_dir() { return VGD_BINARY_DIR; }

inline std::filesystem::path shared_dir() {
  if (const char* env = std::getenv("VGD_SHARED_DIR")) return env;
  return VGD_SHARED_DIR;
}
inline std::filesystem::path shared_dxf(const std::string& name) {
  return shared_dir() / "data" / "dxf" / name;
}
inline bool have_shared() { return std::filesystem::is_directory(shared_dir() / "data" / "dxf"); }

// A fresh, empty directory for one test's outputs, under the build tree.
inline std::filesystem::path scratch_dir(const std::string& name) {
  auto d = binary_dir() / "test-scratch" / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace vgd::test

#define VGD_REQUIRE_SHARED()                                                          \
  do {                                                                                \
    if (!::vgd::test::have_shared())                                                  \
      GTEST_SKIP() << "SKIPPED: shared data not found at " << ::vgd::test::shared_dir() \
                   << " (set VGD_SHARED_DIR or check out ../shared)";                 \
  } while (0)
