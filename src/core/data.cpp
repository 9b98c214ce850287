// Where the shipped data (scenes, materials, body tables, garments) is.
#include "vgd/core/data.hpp"

#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"

namespace vgd {

namespace fs = std::filesystem;

fs::path data_file(std::string_view relative) {
  std::vector<fs::path> tried;
  auto consider = [&](const fs::path& dir) -> std::optional<fs::path> {
    if (dir.empty()) return std::nullopt;
    const fs::path p = dir / relative;
    tried.push_back(p);
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) return p;
    return std::nullopt;
  };
  // The user's choice first, then this build's source tree, then the installed copy.
  if (const char* env = std::getenv("VGD_DATA_DIR"); env && *env)
    if (auto p = consider(env)) return *p;
  if (auto p = consider(VGD_SOURCE_DATA_DIR)) return *p;
  if (auto p = consider(VGD_INSTALL_DATA_DIR)) return *p;
  std::string list;
  for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t.string();
  throw Error("", std::string(relative),
              "cannot find " + std::string(relative) + " (tried " + list + "); set VGD_DATA_DIR to vgd's data folder");
}

fs::path shipped_scene(std::string_view name) { return data_file("scenes/" + std::string(name) + ".json"); }

}  // namespace vgd
