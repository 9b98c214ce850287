// Quality presets (scene/quality.hpp): what a scene's integrator.preset and
// --quality set, what overrides them, and that the presets order by error
// and by cost on the seed's flag as docs/accuracy-vs-time.md says.
#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.hpp"
#include "vgd/core/data.hpp"
#include "vgd/scene/material.hpp"
#include "vgd/scene/quality.hpp"
#include "vgd/sim/integrator.hpp"

using namespace vgd;
using namespace vgd::scene;
using namespace vgd::scene::test;

TEST(QualityPreset, WithoutContactTheyAreExplicitMethodsAtFractionsOfTheLimit) {
  json j = tiny_scene();
  j["integrator"] = {{"preset", "standard"}};
  SceneDef d = parse(j);
  ASSERT_TRUE(d.integrator.preset);
  EXPECT_EQ(*d.integrator.preset, Quality::standard);
  EXPECT_EQ(d.integrator.settings.method, sim::Method::rk4);
  EXPECT_TRUE(d.integrator.settings.auto_substep);
  EXPECT_DOUBLE_EQ(d.integrator.settings.safety, 0.25);
  EXPECT_DOUBLE_EQ(effective_step(d), 1.0 / 25);  // one frame asked, shrunk to the limit by auto_substep

  j["integrator"] = {{"preset", "preview"}};
  d = parse(j);
  EXPECT_EQ(d.integrator.settings.method, sim::Method::symplectic_euler);
  EXPECT_DOUBLE_EQ(d.integrator.settings.safety, 0.9);

  // Fields given with a preset override it.
  j["integrator"] = {{"preset", "precise"}, {"step", "2 ms"}, {"safety", 0.5}};
  d = parse(j);
  EXPECT_EQ(d.integrator.settings.method, sim::Method::rk4);
  EXPECT_DOUBLE_EQ(effective_step(d), 0.002);
  EXPECT_DOUBLE_EQ(d.integrator.settings.safety, 0.5);
}

TEST(QualityPreset, WithContactTheyAreImplicitEuler) {
  json j = tiny_scene();
  j["effects"]["self_collision"] = json::object();
  for (const auto& [name, steps] : {std::pair{"preview", 4}, {"standard", 4}, {"precise", 8}}) {
    j["integrator"] = {{"preset", name}};
    const SceneDef d = parse(j);
    EXPECT_EQ(d.integrator.settings.method, sim::Method::implicit_euler) << name;
    EXPECT_DOUBLE_EQ(effective_step(d), 1.0 / (25.0 * steps)) << name;
    EXPECT_DOUBLE_EQ(d.integrator.settings.cg_tolerance, 1e-2) << name;
  }
}

TEST(QualityPreset, AnUnknownPresetNamesTheChoices) {
  json j = tiny_scene();
  j["integrator"] = {{"preset", "ultra"}};
  try {
    parse(j);
    FAIL() << "accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("integrator.preset"), std::string::npos) << m;
    EXPECT_NE(m.find("preview, standard, precise"), std::string::npos) << m;
  }
  EXPECT_THROW(parse_quality("fast"), std::invalid_argument);
}

// The flag of docs/accuracy-vs-time.md (10 x 10, mass-spring without its
// Provot limit, 0.5 s of gusty wind) against RK4 at 1/32 of its limit: each
// preset is more accurate and costs more force evaluations than the one
// before (measured 378 / 106 / 5.2 mm for 132 / 1 248 / 2 496 evaluations).
TEST(QualityPreset, PresetsOrderByErrorAndCostOnTheFlag) {
  SceneDef def = load_scene(shipped_scene("flag"));
  def.outputs.clear();
  def.run.duration = 0.5;
  auto& c = def.cloth.front();
  c.grid->nu = c.grid->nv = 10;
  MaterialDef m = load_xvc_material(data_file("materials/seed-flag.xvc"), "seed-flag");
  m.mass_spring->max_strain = 0.0;  // a projection per step: no step converges (docs/accuracy-vs-time.md)
  def.materials[c.material] = MaterialSource{{}, {}, m};

  auto run = [&](sim::IntegratorSettings st, long* rhs) {
    Scene s = build(def);
    auto integ = sim::make_integrator(st);
    sim::State x = sim::initial_state(s.system->model());
    s.system->apply_prescribed(x);
    integ->prepare(*s.system, x);
    for (int k = 1; k <= 12; ++k) integ->advance(*s.system, x, k / 25.0);
    if (rhs) *rhs = integ->stats().rhs_evaluations;
    return s.system->expand(x.x);
  };
  const Scene probe = build(def);
  sim::IntegratorSettings ref = probe.integrator;
  ref.method = sim::Method::rk4;
  ref.auto_substep = false;
  ref.step = sim::stability_limit(sim::Method::rk4, probe.system->stiffness()) / 32;
  const sim::VecX reference = run(ref, nullptr);

  double last_error = 1e9;
  long last_rhs = 0;
  for (const auto q : {Quality::preview, Quality::standard, Quality::precise}) {
    sim::IntegratorSettings st = quality_integrator(q, has_contact(def.effects)).settings;
    st.step = 1.0 / 25;  // one frame, shrunk to the preset's fraction of the limit
    long rhs = 0;
    const sim::VecX x = run(st, &rhs);
    double error = 0;
    for (int i = 0; i < x.size() / 3; ++i) error = std::max(error, (sim::at(x, i) - sim::at(reference, i)).norm());
    EXPECT_LT(error, last_error) << to_string(q);
    EXPECT_GT(rhs, last_rhs) << to_string(q);
    last_error = error, last_rhs = rhs;
  }
  EXPECT_LT(last_error, 0.02);  // precise: within 2 cm of the reference after 0.5 s of gusts
}
