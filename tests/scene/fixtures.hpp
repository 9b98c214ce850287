#pragma once
// Tiny scenes built inside the tests (style guide: build tiny scenes in the
// test), and a check that an error names the file, the JSON path and the problem.
#include <gtest/gtest.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "vgd/core/diagnostics.hpp"
#include "vgd/scene/build.hpp"
#include "vgd/scene/json.hpp"

namespace vgd::scene::test {

using nlohmann::json;

// A 5 x 5 mass-spring sheet, 0.4 m square, hanging flat (in x-y) from its two
// top corners, with gravity; Euler at 1 ms, 25 fps, 0.2 s.
inline json tiny_scene() {
  return json::parse(R"({
    "version": 1,
    "name": "tiny",
    "materials": {
      "cloth": { "particle_mass": 0.01, "density": 0.1, "spring.warp": 100, "spring.weft": 100, "spring.shear": 20,
                 "spring.bend_warp": 5, "spring.bend_weft": 5, "spring.damping": 0.01,
                 "E_warp": 120, "E_weft": 120, "G": 20, "nu_warp_weft": 0.2, "B_warp": 1e-5, "B_weft": 1e-5 }
    },
    "cloth": [ { "name": "sheet", "grid": { "particles": [5, 5], "size": [0.4, 0.4] },
                 "placement": { "origin": [0, 1, 0], "u": [1, 0, 0], "v": [0, -1, 0] },
                 "model": "mass-spring", "material": "cloth" } ],
    "effects": {
      "gravity": {},
      "pins": [ { "piece": "sheet", "sets": ["corner-u0v0", "corner-u1v0"] } ]
    },
    "integrator": { "method": "euler", "step": 0.001 },
    "frames": { "fps": 25, "duration": 0.2 }
  })");
}

inline SceneDef parse(const json& j, const std::string& name = "tiny.json") { return parse_scene(j.dump(2), name); }

// Runs `f`, which must throw vgd::Error naming `file`, entity `path` and a
// message holding `needle`.
inline void expect_error(const std::function<void()>& f, const std::string& file, const std::string& path,
                         const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no error; expected " << path << ": ..." << needle;
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().file, file) << e.what();
    EXPECT_EQ(e.diagnostic().entity, path) << e.what();
    EXPECT_NE(e.diagnostic().message.find(needle), std::string::npos) << e.what();
  }
}

// expect_error on parse (and build) of a changed tiny scene.
inline void expect_scene_error(const std::function<void(json&)>& change, const std::string& path,
                               const std::string& needle) {
  json j = tiny_scene();
  change(j);
  expect_error([&] { build(parse(j)); }, "tiny.json", path, needle);
}

}  // namespace vgd::scene::test
