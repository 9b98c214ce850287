#pragma once
// The project's shipped data (data/scenes, data/materials), found the way the
// XVC schema is: $VGD_DATA_DIR, else the source tree this build came from,
// else the installed share directory (<prefix>/share/vgd/data).
#include <filesystem>
#include <string_view>

namespace vgd {

// data/<relative>, e.g. data_file("scenes/flag.json"). Throws vgd::Error
// naming the places tried when it is in none of them.
std::filesystem::path data_file(std::string_view relative);

// data/scenes/<name>.json, e.g. shipped_scene("flag").
std::filesystem::path shipped_scene(std::string_view name);

}  // namespace vgd
