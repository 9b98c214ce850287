#pragma once
// Scene files (JSON, docs/scene.md). Reading checks types, units and names and
// then validate()s the result; every problem is a vgd::Error naming the file,
// the JSON path of the field (e.g. `effects.wind.velocity`, `cloth[0].grid`)
// and what is wrong. Quantities may be written as numbers in SI units or as
// strings with a unit ("4 ms", "2 cm", "0.2 N.s/m"); a unit of the wrong kind
// is refused. Unknown fields are refused too (a typo must not be ignored).
#include <filesystem>
#include <string>
#include <string_view>

#include "vgd/scene/scene.hpp"

namespace vgd::scene {

// Reads and checks a scene file. Throws vgd::Error (file, JSON path, problem).
SceneDef load_scene(const std::filesystem::path& file);

// The same from text; `source` names the file in messages and is the base of
// relative paths (XVC files).
SceneDef parse_scene(std::string_view json_text, const std::filesystem::path& source);

}  // namespace vgd::scene
