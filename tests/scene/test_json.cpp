// Scene files: what they say arrives in the SceneDef (units converted), and
// every kind of mistake is an error naming the file, the JSON path and the problem.
#include <gtest/gtest.h>

#include "fixtures.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"

using namespace vgd;
using namespace vgd::scene;
using namespace vgd::scene::test;

TEST(SceneFile, ATinySceneReadsWithItsValues) {
  const SceneDef d = parse(tiny_scene());
  EXPECT_EQ(d.name, "tiny");
  ASSERT_EQ(d.cloth.size(), 1u);
  EXPECT_EQ(d.cloth[0].grid->nu, 5);
  EXPECT_DOUBLE_EQ(d.cloth[0].grid->width, 0.4);
  EXPECT_EQ(d.cloth[0].placement.v, Vec3(0, -1, 0));
  EXPECT_EQ(d.cloth[0].model, ClothModel::mass_spring);
  const auto& m = d.materials.at("cloth").values;
  EXPECT_DOUBLE_EQ(m.particle_mass, 0.01);
  ASSERT_TRUE(m.mass_spring);
  EXPECT_DOUBLE_EQ(m.mass_spring->warp, 100.0);
  ASSERT_TRUE(m.orthotropic);
  EXPECT_DOUBLE_EQ(m.orthotropic->E_warp, 120.0);
  ASSERT_TRUE(d.effects.gravity);
  EXPECT_DOUBLE_EQ(d.effects.gravity->g.y(), -9.81);
  EXPECT_FALSE(d.effects.wind);
  EXPECT_FALSE(d.effects.viscosity);
  ASSERT_EQ(d.effects.pins.size(), 1u);
  EXPECT_EQ(d.effects.pins[0].sets.size(), 2u);
  EXPECT_EQ(d.integrator.settings.method, sim::Method::symplectic_euler);
  EXPECT_DOUBLE_EQ(effective_step(d), 0.001);
  EXPECT_DOUBLE_EQ(d.run.fps, 25.0);
}

TEST(SceneFile, QuantitiesWithUnitsAreConvertedToSI) {
  json j = tiny_scene();
  j["integrator"]["step"] = "0.5 ms";
  j["frames"]["duration"] = "300 ms";
  j["cloth"][0]["grid"]["size"] = {"40 cm", "400 mm"};
  j["effects"]["wind"] = {{"velocity", {"36 km/h", 0, 0}}, {"turbulence", "10 %"}, {"gust_frequency", "2 Hz"}};
  j["effects"]["viscosity"] = {{"k", "0.2 N.s/m"}, {"alpha", "1 1/s"}};
  j["materials"]["cloth"]["spring.warp"] = "1.8 kN/m";
  j["materials"]["cloth"]["density"] = "150 g/m2";
  const SceneDef d = parse(j);
  EXPECT_DOUBLE_EQ(d.integrator.settings.step, 0.0005);
  EXPECT_DOUBLE_EQ(d.run.duration, 0.3);
  EXPECT_DOUBLE_EQ(d.cloth[0].grid->width, 0.4);
  EXPECT_DOUBLE_EQ(d.cloth[0].grid->height, 0.4);
  EXPECT_DOUBLE_EQ(d.effects.wind->velocity.x(), 10.0);
  EXPECT_DOUBLE_EQ(d.effects.wind->turbulence, 0.1);
  EXPECT_DOUBLE_EQ(d.effects.wind->gust_frequency, 2.0);
  EXPECT_DOUBLE_EQ(d.effects.viscosity->k, 0.2);
  EXPECT_DOUBLE_EQ(d.materials.at("cloth").values.mass_spring->warp, 1800.0);
  EXPECT_DOUBLE_EQ(d.materials.at("cloth").values.density, 0.15);
}

// The seams' last stitch (docs/seams.md) reads with its unit and is checked.
TEST(SceneFile, TheSeamsLastStitchReads) {
  json j = tiny_scene();
  j["effects"]["seams"] = {{"last_stitch_distance", "5 cm"}, {"last_stitch_frames", 12}};
  const SceneDef d = parse(j);
  ASSERT_TRUE(d.effects.seams);
  EXPECT_DOUBLE_EQ(d.effects.seams->effect.last_stitch_distance, 0.05);
  EXPECT_EQ(d.effects.seams->effect.last_stitch_frames, 12);
  expect_scene_error([](json& k) { k["effects"]["seams"] = {{"last_stitch_frames", 0}}; },
                     "effects.seams.last_stitch_frames", ">= 1");
  expect_scene_error([](json& k) { k["effects"]["seams"] = {{"last_stitch_distance", -0.01}}; },
                     "effects.seams.last_stitch_distance", ">= 0");
}

// The self-collision's repulsion damping (docs/collisions.md, "Damped
// repulsion"): a fraction of critical, none by default, never negative.
TEST(SceneFile, TheRepulsionsDampingReads) {
  json j = tiny_scene();
  j["effects"]["self_collision"] = json::object();
  const SceneDef none = parse(j);
  ASSERT_TRUE(none.effects.self_collision);
  EXPECT_EQ(none.effects.self_collision->damping, 0.0);
  j["effects"]["self_collision"]["damping"] = 0.5;
  EXPECT_EQ(parse(j).effects.self_collision->damping, 0.5);
  expect_scene_error([](json& k) { k["effects"]["self_collision"] = {{"damping", -0.5}}; },
                     "effects.self_collision.damping", ">= 0");
}

TEST(SceneFile, HeldContactsAreAnIntegratorFlagOffByDefault) {
  json j = tiny_scene();
  EXPECT_FALSE(parse(j).integrator.settings.hold_contacts);
  j["integrator"]["hold_contacts"] = true;
  EXPECT_TRUE(parse(j).integrator.settings.hold_contacts);
  expect_scene_error([](json& k) { k["integrator"]["hold_contacts"] = "yes"; }, "integrator.hold_contacts",
                     "expected true or false");
}

TEST(SceneFile, IterationsPerFrameSetTheStepAsInTheSeed) {
  json j = tiny_scene();
  j["integrator"].erase("step");
  j["integrator"]["iterations_per_frame"] = 16;
  EXPECT_DOUBLE_EQ(effective_step(parse(j)), 1.0 / (25.0 * 16));  // 2.5 ms
}

TEST(SceneFile, AnEffectSwitchedOffIsNotInTheDef) {
  json j = tiny_scene();
  j["effects"]["wind"] = {{"velocity", {1, 0, 0}}, {"enabled", false}};
  j["effects"]["pins"][0]["enabled"] = false;
  const SceneDef d = parse(j);
  EXPECT_FALSE(d.effects.wind);
  EXPECT_TRUE(d.effects.pins.empty());
}

TEST(SceneFile, InlineMaterialsAndOutputsRead) {
  json j = tiny_scene();
  j["cloth"][0]["material"] = j["materials"]["cloth"];
  j["materials"].erase("cloth");
  j["output"] = json::array({{{"type", "obj"}, {"directory", "frames"}}, {{"type", "memory"}}});
  const SceneDef d = parse(j);
  EXPECT_EQ(d.cloth[0].material, "cloth[0].material");
  EXPECT_TRUE(d.materials.count("cloth[0].material"));
  ASSERT_EQ(d.outputs.size(), 2u);
  EXPECT_EQ(d.outputs[0].directory, "frames");
  EXPECT_EQ(d.outputs[1].kind, OutputDef::Kind::memory);
}

// ---- errors: file, JSON path, problem ------------------------------------------------

TEST(SceneFileErrors, AMissingFieldIsNamed) {
  expect_scene_error([](json& j) { j.erase("cloth"); }, "cloth", "missing");
  expect_scene_error([](json& j) { j["cloth"][0].erase("material"); }, "cloth[0].material", "missing");
  expect_scene_error([](json& j) { j["cloth"][0]["grid"].erase("particles"); }, "cloth[0].grid.particles", "missing");
  expect_scene_error([](json& j) { j["cloth"][0].erase("grid"); }, "cloth[0]", "grid, xvc or garment");
}

TEST(SceneFileErrors, AWrongTypeIsNamed) {
  expect_scene_error([](json& j) { j["effects"]["wind"] = {{"velocity", "fast"}}; }, "effects.wind.velocity",
                     "expected a list of 3 numbers");
  expect_scene_error([](json& j) { j["effects"]["wind"] = {{"velocity", {1, "x", 0}}}; }, "effects.wind.velocity[1]",
                     "is not a number with a unit");
  expect_scene_error([](json& j) { j["cloth"][0]["grid"]["particles"] = {5.5, 5}; }, "cloth[0].grid.particles[0]",
                     "whole number");
  expect_scene_error([](json& j) { j["cloth"] = json::object(); }, "cloth", "expected a list");
  expect_scene_error([](json& j) { j["effects"]["gravity"] = 9.81; }, "effects.gravity", "expected an object");
  expect_scene_error([](json& j) { j["integrator"]["auto_substep"] = "yes"; }, "integrator.auto_substep",
                     "true or false");
}

TEST(SceneFileErrors, AnUnknownEffectOrFieldIsNamed) {
  expect_scene_error([](json& j) { j["effects"]["tornado"] = json::object(); }, "effects.tornado",
                     "unknown field 'tornado'");
  expect_scene_error([](json& j) { j["effects"]["wind"] = {{"speed", 3}}; }, "effects.wind.speed", "known here:");
  expect_scene_error([](json& j) { j["integrator"]["method"] = "leapfrog"; }, "integrator.method",
                     "unknown integrator 'leapfrog'");
  expect_scene_error([](json& j) { j["cloth"][0]["model"] = "finite-elements"; }, "cloth[0].model",
                     "unknown cloth model");
  expect_scene_error([](json& j) { j["materials"]["cloth"]["stiffness"] = 3; }, "materials.cloth.stiffness",
                     "unknown field 'stiffness'");
}

TEST(SceneFileErrors, ANegativeStepOrRateIsRefused) {
  expect_scene_error([](json& j) { j["integrator"]["step"] = -0.004; }, "integrator.step", "positive");
  expect_scene_error([](json& j) { j["integrator"]["step"] = 0; }, "integrator.step", "positive");
  expect_scene_error([](json& j) { j["frames"]["fps"] = 0; }, "frames.fps", "positive");
  expect_scene_error([](json& j) { j["frames"]["duration"] = -1; }, "frames.duration", ">= 0");
  expect_scene_error([](json& j) { j["effects"]["wind"] = {{"turbulence", -0.1}}; }, "effects.wind.turbulence",
                     ">= 0");
  expect_scene_error([](json& j) { j["materials"]["cloth"]["spring.warp"] = -1; }, "materials.cloth.spring.warp",
                     ">= 0");
  expect_scene_error([](json& j) { j["cloth"][0]["grid"]["particles"] = {1, 5}; }, "cloth[0].grid.particles",
                     "at least 2 x 2");
}

TEST(SceneFileErrors, StepAndIterationsTogetherAreRefused) {
  expect_scene_error([](json& j) { j["integrator"]["iterations_per_frame"] = 10; }, "integrator.iterations_per_frame",
                     "either step or iterations_per_frame");
}

TEST(SceneFileErrors, AnUnknownMaterialIsNamed) {
  expect_scene_error([](json& j) { j["cloth"][0]["material"] = "silk"; }, "cloth[0].material",
                     "unknown material 'silk' (known: cloth)");
}

TEST(SceneFileErrors, AMaterialWithoutTheModelsValuesIsRefused) {
  expect_scene_error(
      [](json& j) {
        for (const char* k : {"spring.warp", "spring.weft", "spring.shear", "spring.bend_warp", "spring.bend_weft",
                              "spring.damping"})
          j["materials"]["cloth"].erase(k);
      },
      "materials.cloth", "no mass-spring values");
  expect_scene_error(
      [](json& j) {
        j["cloth"][0]["model"] = "strain-rosette";
        j["materials"]["cloth"]["nu_warp_weft"] = 1.5;
      },
      "materials.cloth", "nu");
}

TEST(SceneFileErrors, PinsOutOfRangeAreNamed) {
  expect_scene_error([](json& j) { j["effects"]["pins"][0]["particles"] = {0, 25}; }, "effects.pins[0].particles[1]",
                     "particle 25 is out of range: piece 'sheet' has 25 particles (0..24)");
  expect_scene_error([](json& j) { j["effects"]["pins"][0]["particles"] = {-1}; }, "effects.pins[0].particles[0]",
                     "start at 0");
  expect_scene_error([](json& j) { j["effects"]["pins"][0]["sets"] = {"row-5"}; }, "effects.pins[0].sets[0]",
                     "unknown particle set 'row-5'");
  expect_scene_error([](json& j) { j["effects"]["pins"][0]["piece"] = "sail"; }, "effects.pins[0].piece",
                     "no cloth piece is called 'sail'");
  expect_scene_error(
      [](json& j) {
        j["effects"]["pins"][0].erase("sets");
        j["effects"]["pins"][0]["region"] = {{"min", {5, 5, 5}}, {"max", {6, 6, 6}}};
      },
      "effects.pins[0].region", "holds no particle");
}

TEST(SceneFileErrors, AUnitMismatchIsNamed) {
  expect_scene_error([](json& j) { j["integrator"]["step"] = "4 m"; }, "integrator.step",
                     "unit mismatch: \"4 m\" is in m, but this field needs s");
  expect_scene_error([](json& j) { j["effects"]["gravity"] = {{"g", {0, "-9.81 N", 0}}}; }, "effects.gravity.g[1]",
                     "needs m/s2");
  expect_scene_error([](json& j) { j["materials"]["cloth"]["spring.warp"] = "1800 N"; },
                     "materials.cloth.spring.warp", "needs N/m");
}

TEST(SceneFileErrors, OneModelPerScene) {
  expect_scene_error(
      [](json& j) {
        json second = j["cloth"][0];
        second["name"] = "other";
        second["model"] = "strain-rosette";
        j["cloth"].push_back(second);
      },
      "cloth[1].model", "one cloth model for all its pieces");
}

TEST(SceneFileErrors, InvalidJsonNamesTheLine) {
  try {
    parse_scene("{\n  \"name\": \"x\",\n  \"cloth\": [,]\n}\n", "broken.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().file, "broken.json");
    EXPECT_EQ(e.diagnostic().line, 3) << e.what();
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos);
  }
}

TEST(SceneFileErrors, AMissingFileIsNamed) {
  try {
    load_scene("/nonexistent/scene.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos) << e.what();
  }
}

TEST(SceneFile, TheExamplesInTheDocsRead) {
  // Every ```json block of docs/scene.md holding a whole scene ("cloth") parses and validates.
  const std::string doc = read_file(vgd::test::source_dir() / "docs" / "scene.md");
  int scenes = 0;
  for (std::size_t at = doc.find("```json\n"); at != std::string::npos; at = doc.find("```json\n", at + 1)) {
    const std::size_t begin = at + 8, end = doc.find("```", begin);
    const std::string text = doc.substr(begin, end - begin);
    if (text.find("\"cloth\"") == std::string::npos) continue;
    EXPECT_NO_THROW(parse_scene(text, vgd::test::source_dir() / "data" / "scenes" / "example.json")) << text;
    ++scenes;
  }
  EXPECT_EQ(scenes, 2);
}

namespace vgd::scene {
namespace {

// A number no double holds is bad JSON with a message, not a crash (fuzzing found it).
TEST(SceneFileErrors, ANumberTooLargeForADoubleIsNamed) {
  try {
    parse_scene(R"({"cloth": [{"grid": {"particles": [2, 2], "size": [1e999, 1]}}]})", "huge.json");
    FAIL() << "accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("huge.json"), std::string::npos) << m;
    EXPECT_NE(m.find("not valid JSON"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace vgd::scene
