// `vgd simulate` and `vgd bench engine` end to end: a tiny scene runs and
// writes its frames; a bad scene exits 1 naming the JSON path; --profile lists
// exactly the scene's effects; a run stopped early exits 1 and keeps its frames.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/obj/obj.hpp"

using namespace vgd;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A 5 x 5 sheet hanging from two corners, both cloth models' values, 0.2 s at 25 fps.
json tiny_scene() {
  return json::parse(R"({
    "name": "tiny",
    "materials": {
      "cloth": { "particle_mass": 0.01, "density": 0.1, "spring.warp": 100, "spring.weft": 100, "spring.shear": 20,
                 "spring.bend_warp": 5, "spring.bend_weft": 5,
                 "E_warp": 120, "E_weft": 120, "G": 20, "nu_warp_weft": 0.2, "B_warp": 1e-5, "B_weft": 1e-5 }
    },
    "cloth": [ { "name": "sheet", "grid": { "particles": [5, 5], "size": [0.4, 0.4] },
                 "placement": { "origin": [0, 1, 0], "u": [1, 0, 0], "v": [0, -1, 0] }, "material": "cloth" } ],
    "effects": {
      "gravity": {},
      "viscosity": { "k": 0.001 },
      "pins": [ { "piece": "sheet", "sets": ["corner-u0v0", "corner-u1v0"] } ]
    },
    "integrator": { "method": "euler", "step": "1 ms" },
    "frames": { "fps": 25, "duration": 0.2 }
  })");
}

fs::path write_scene(const std::string& test, const json& j) {
  const auto dir = test::scratch_dir(test);
  write_file_atomic(dir / "scene.json", j.dump(2));
  return dir / "scene.json";
}

test::CliResult vgd_run(const std::string& args) { return test::run_vgd(args); }

}  // namespace

TEST(CmdSimulate, RunsATinySceneAndWritesItsFrames) {
  const auto scene = write_scene("cmd_simulate_tiny", tiny_scene());
  const auto out = scene.parent_path() / "frames";
  const auto r = vgd_run("simulate " + scene.string() + " -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  // The summary: frames, steps, evaluations, wall time, particle-steps/s.
  EXPECT_NE(r.out.find("6 frames"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("200 steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("200 RHS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("particle-steps/s"), std::string::npos) << r.out;
  // Progress on stderr, one line per ~10 % when it is not a terminal, ending at the last frame.
  EXPECT_NE(r.err.find("frame 5/5"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ETA"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
  // Frames 0..5 as OBJ files with 25 vertices and 32 triangles.
  for (int k = 0; k <= 5; ++k) {
    const auto m = io::obj::read_obj(out / io::obj::frame_file_name(k));
    EXPECT_EQ(m.vertices.size(), 25u);
    EXPECT_EQ(m.faces.size(), 32u);
  }
  EXPECT_FALSE(fs::exists(out / "frame_0006.obj"));
}

TEST(CmdSimulate, JsonSummaryAndOverrides) {
  const auto scene = write_scene("cmd_simulate_json", tiny_scene());
  const auto r = vgd_run("-q simulate " + scene.string() + " --json --integrator rk4 --step 2ms --duration 0.08");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // -q and --json: no progress
  const auto j = json::parse(r.out);
  EXPECT_TRUE(j.at("ok").get<bool>());
  EXPECT_EQ(j.at("integrator"), "rk4");
  EXPECT_EQ(j.at("frames"), 3);  // 0, 0.04, 0.08 s
  EXPECT_EQ(j.at("steps"), 40);
  EXPECT_EQ(j.at("rhs_evaluations"), 160);  // four per RK4 step
  EXPECT_EQ(j.at("particles"), 25);
  EXPECT_GT(j.at("particle_steps_per_s").get<double>(), 0.0);
}

// --quality replaces the scene's integrator by a preset (docs/accuracy-vs-time.md):
// precise is RK4 at 1/8 of its limit, half standard's step (1/4), twice its steps.
TEST(CmdSimulate, QualityPresetsReplaceTheIntegrator) {
  const auto scene = write_scene("cmd_simulate_quality", tiny_scene());
  long steps[2] = {0, 0};
  double step[2] = {0, 0};
  int k = 0;
  for (const char* q : {"standard", "precise"}) {
    const auto r = vgd_run("-q simulate " + scene.string() + " --json --quality " + q + " --duration 0.08");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = json::parse(r.out);
    EXPECT_EQ(j.at("integrator"), "rk4") << q;
    steps[k] = j.at("steps").get<long>();
    step[k++] = j.at("step_s").get<double>();
  }
  EXPECT_NEAR(step[1], 0.5 * step[0], 1e-12);
  EXPECT_NEAR(static_cast<double>(steps[1]) / steps[0], 2.0, 0.1);
  EXPECT_EQ(vgd_run("-q simulate " + scene.string() + " --quality ultra").code, 2);
}

TEST(CmdSimulate, ProfileListsExactlyTheScenesEffects) {
  const auto scene = write_scene("cmd_simulate_profile", tiny_scene());
  const auto r = vgd_run("-q simulate " + scene.string() + " --profile");
  ASSERT_EQ(r.code, 0) << r.err;
  // The table: a header, then one row per effect, in build order.
  const auto at = r.out.find("effect ");
  ASSERT_NE(at, std::string::npos) << r.out;
  std::istringstream rows(r.out.substr(at));
  std::string line;
  std::getline(rows, line);
  std::vector<std::string> names;
  while (std::getline(rows, line) && !line.empty()) {
    std::istringstream cells(line);
    std::string name;
    long calls = 0;
    cells >> name >> calls;
    names.push_back(name);
    EXPECT_EQ(calls, 200) << line;  // one force call per Euler step
  }
  EXPECT_EQ(names, (std::vector<std::string>{"mass-spring", "gravity", "viscosity", "pins"})) << r.out;

  // The same through --json, with wind switched on and viscosity off.
  json j = tiny_scene();
  j["effects"]["wind"] = {{"velocity", {0, 0, 1}}};
  j["effects"]["viscosity"]["enabled"] = false;
  const auto r2 = vgd_run("-q simulate " + write_scene("cmd_simulate_profile2", j).string() + " --json");
  ASSERT_EQ(r2.code, 0) << r2.err;
  std::vector<std::string> listed;
  const auto summary = json::parse(r2.out);
  for (const auto& p : summary.at("profile")) listed.push_back(p.at("effect"));
  EXPECT_EQ(listed, (std::vector<std::string>{"mass-spring", "gravity", "wind", "pins"}));
}

TEST(CmdSimulate, ABadSceneExits1NamingTheJsonPath) {
  json j = tiny_scene();
  j["effects"]["wind"] = {{"velocity", {0, "fast", 0}}};
  const auto r = vgd_run("simulate " + write_scene("cmd_simulate_bad", j).string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("scene.json: effects.wind.velocity[1]:"), std::string::npos) << r.err;

  j = tiny_scene();
  j["integrator"]["step"] = -0.001;
  const auto r2 = vgd_run("simulate " + write_scene("cmd_simulate_bad2", j).string());
  EXPECT_EQ(r2.code, 1);
  EXPECT_NE(r2.err.find("integrator.step: must be a positive number"), std::string::npos) << r2.err;

  EXPECT_EQ(vgd_run("simulate /nonexistent/scene.json").code, 1);
  EXPECT_EQ(vgd_run("simulate " + write_scene("cmd_simulate_bad3", tiny_scene()).string() + " --step fast").code, 2);
}

TEST(CmdSimulate, ARunStoppedEarlyExits1AndKeepsItsFrames) {
  // Free fall may not exceed 1 m/s: reached at t = 0.102 s, so frames 0..10 of 0.01 s are written.
  json j = tiny_scene();
  j["effects"].erase("pins");
  j["integrator"]["max_speed"] = "1 m/s";
  j["frames"] = {{"fps", 100}, {"duration", 1}};
  const auto scene = write_scene("cmd_simulate_stop", j);
  const auto out = scene.parent_path() / "frames";
  const auto r = vgd_run("simulate " + scene.string() + " -o " + out.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("the run stopped after 11 frames"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("m/s"), std::string::npos) << r.err;  // the engine's message
  for (int k = 0; k <= 10; ++k) EXPECT_EQ(io::obj::read_obj(out / io::obj::frame_file_name(k)).vertices.size(), 25u);
  EXPECT_FALSE(fs::exists(out / "frame_0011.obj"));
}

TEST(CmdSimulate, AnUnstableStepIsRefusedWithWhatWouldWork) {
  json j = tiny_scene();
  j["integrator"]["step"] = 0.05;
  const auto r = vgd_run("simulate " + write_scene("cmd_simulate_unstable", j).string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("stability limit"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("What would work"), std::string::npos) << r.err;
}

TEST(CmdBench, EngineRecordsEveryModelAndIntegrator) {
  const auto scene = write_scene("cmd_bench", tiny_scene());
  const auto r = vgd_run("-q bench engine --quick --json --scene " + scene.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto list = json::parse(r.out);
  ASSERT_TRUE(list.is_array());
  int main_records = 0;
  for (const auto& rec : list) {
    for (const char* k : {"scene", "model", "integrator", "threads", "particles", "steps", "wall_s",
                          "particle_steps_per_s", "status"})
      EXPECT_TRUE(rec.contains(k)) << k << " in " << rec.dump();
    if (rec.contains("variant")) continue;
    ++main_records;
    const std::string integ = rec.at("integrator");
    if (rec.at("status") == "ok" && (integ == "implicit-euler" || integ == "bdf")) {
      EXPECT_TRUE(rec.contains("rhs_per_simulated_s")) << rec.dump();
      EXPECT_TRUE(rec.contains("jacobians_per_simulated_s")) << rec.dump();
    }
    if (rec.at("status") == "ok") {
      EXPECT_EQ(rec.at("particles"), 25);
    }
  }
  // 2 models x 5 integrators x (1 thread and every core).
  EXPECT_TRUE(main_records == 10 || main_records == 20) << main_records;
}
