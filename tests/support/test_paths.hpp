#pragma once
// Where tests find their inputs. Shared third-party data (../shared) is never
// copied into the repository: tests that need it call VGD_REQUIRE_SHARED() and
// are skipped, with a visible message, when it is absent.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <cctype>
#include <string>
#include <vector>

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

// The real DXF exports in ../shared/data/dxf (Gerber AAMA/ASTM, CLO, Valentina).
inline std::vector<std::string> shared_dxf_files() {
  return {"simple.DXF",          "MEN_CLASSIC_TEE.DXF", "WM_SLIM_TANK.DXF",
          "GLX4802S19_AAMA.DXF", "GLX4802S19_ASTM.DXF", "ORILEGWB_AAMA.DXF",
          "GMH1006F18_AAMA.DXF", "drill-holes.DXF",     "mirrored.DXF",
          "clo-box.dxf",         "clo-pattern.dxf",     "Valentina_MaleShirt_AAMA_R12.dxf",
          "Valentina_Trousers_ASTM_R12.dxf"};
}

// A file name as a gtest parameter name ("clo-box.dxf" -> "clo_box_dxf").
struct FileParamName {
  template <class Info>
  std::string operator()(const Info& param_info) const {
    std::string n = param_info.param;
    for (auto& c : n)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return n;
  }
};

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
