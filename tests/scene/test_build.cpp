// Building: the model a scene describes (particles, placement, masses), exactly
// the effects it lists (an effect not listed is never constructed, and
// switching one off removes exactly its work), pins chosen by index, named set
// and region, and pieces of an XVC document meshed and laid flat.
#include <gtest/gtest.h>

#include <algorithm>

#include "vgd/sim/sdf.hpp"

#include <cmath>
#include <numeric>

#include "fixtures.hpp"
#include "mesh/synthetic.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/run.hpp"
#include "vgd/xvc/document.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

using namespace vgd;
using namespace vgd::scene;
using namespace vgd::scene::test;

namespace {

std::vector<std::string> profile_names(const sim::System& sys) {
  std::vector<std::string> n;
  for (const auto& p : sys.profile()) n.push_back(p.name);
  return n;
}

// Runs a built scene with no sinks; returns the summary.
sim::RunSummary run(Scene& s) {
  auto integ = sim::make_integrator(s.integrator);
  sim::State st = sim::initial_state(s.system->model());
  return sim::run(*s.system, *integ, st, s.run, {});
}

// A deterministic measure of the work a run did: per effect, its force calls
// times the elements one call visits (particles, edges, triangles, springs).
long work(const Scene& s) {
  const auto& m = s.system->model();
  std::vector<sim::MassSpringMaterial> mats;
  for (const auto& p : s.pieces)
    if (p.material.mass_spring) mats.push_back(*p.material.mass_spring);
  long w = 0;
  for (const auto& p : s.system->profile()) {
    long elements = 0;
    if (p.name == "gravity" || p.name == "viscosity") elements = m.num_particles();
    else if (p.name == "damping") elements = static_cast<long>(sim::mesh_edges(m.triangles).size());
    else if (p.name == "wind" || p.name == "strain-rosette") elements = static_cast<long>(m.triangles.size());
    else if (p.name == "pins") elements = static_cast<long>(s.pinned.size());
    else if (p.name == "mass-spring") elements = sim::mass_spring_topology(m, mats).size();
    w += p.force_calls * elements;
  }
  return w;
}

// A style of two pieces (a 0.5 m and a 0.3 m square) saved as XVC, mesh.spacing 5 cm.
std::filesystem::path two_squares(const std::filesystem::path& dir) {
  pattern::Style style;
  style.name = "squares";
  style.sample_size = "M";
  style.sizes = {"M"};
  style.pieces.push_back(vgd::test::piece("BIG", vgd::test::square(0.5)));
  style.pieces.push_back(vgd::test::piece("SMALL", vgd::test::square(0.3)));
  auto doc = xvc::from_style(style);
  xvc::set_parameter(doc, "mesh.spacing", 0.05);
  const auto path = dir / "squares.xvc";
  xvc::save_file(doc, path);
  return path;
}

}  // namespace

TEST(SceneBuild, AGridIsPlacedAsTheSceneSays) {
  const Scene s = build(parse(tiny_scene()));
  const auto& m = s.system->model();
  ASSERT_EQ(m.num_particles(), 25);
  EXPECT_EQ(m.triangles.size(), 32u);
  ASSERT_EQ(s.pieces.size(), 1u);
  EXPECT_EQ(s.pieces[0].name, "sheet");
  EXPECT_EQ(s.pieces[0].nu, 5);
  // Particle (i, j) at origin + i du u + j dv v: u = +x, v = -y, spacing 0.1 m.
  EXPECT_TRUE(sim::at(m.x0, 0).isApprox(Vec3(0, 1, 0)));
  EXPECT_TRUE(sim::at(m.x0, 4).isApprox(Vec3(0.4, 1, 0)));
  EXPECT_TRUE(sim::at(m.x0, 24).isApprox(Vec3(0.4, 0.6, 0)));
  // Rest shape: material coordinates, warp along u.
  EXPECT_TRUE(m.uv[24].isApprox(sim::Vec2(0.4, 0.4)));
  // The mass-spring particle mass.
  for (int i = 0; i < 25; ++i) EXPECT_DOUBLE_EQ(m.mass[i], 0.01);
  EXPECT_DOUBLE_EQ(s.integrator.step, 0.001);
}

TEST(SceneBuild, WithoutAParticleMassMassesAreAreaTimesDensity) {
  json j = tiny_scene();
  j["materials"]["cloth"].erase("particle_mass");
  const Scene s = build(parse(j));
  const auto& m = s.system->model();
  EXPECT_NEAR(m.mass.sum(), 0.1 * 0.4 * 0.4, 1e-15);  // density 0.1 kg/m², 0.16 m²
  EXPECT_LT(m.mass[0], m.mass[12]);                    // a corner carries less than an interior particle
}

TEST(SceneBuild, TheProfileListsExactlyTheScenesEffects) {
  json j = tiny_scene();
  j["effects"]["viscosity"] = {{"k", 0.01}};
  j["effects"]["damping"] = {{"c", 0.001}};
  j["effects"]["wind"] = {{"velocity", {0, 0, 1}}};
  SceneDef d = parse(j);
  const Scene all = build(d);
  const std::vector<std::string> expected{"mass-spring", "gravity", "viscosity", "damping", "wind", "pins"};
  EXPECT_EQ(profile_names(*all.system), expected);
  EXPECT_EQ(effect_names(d), expected);

  // Only what is listed is constructed: the tiny scene has no viscosity, damping or wind.
  const Scene few = build(parse(tiny_scene()));
  EXPECT_EQ(profile_names(*few.system), (std::vector<std::string>{"mass-spring", "gravity", "pins"}));
  EXPECT_EQ(few.system->effects().size(), 3u);

  // A fabric that states its yarns' lock adds the strain limit after the cloth model.
  j["materials"]["cloth"]["strain_limit"] = 0.1;
  EXPECT_EQ(profile_names(*build(parse(j)).system),
            (std::vector<std::string>{"mass-spring", "strain-limit", "gravity", "viscosity", "damping", "wind", "pins"}));
  EXPECT_EQ(effect_names(parse(j)), profile_names(*build(parse(j)).system));
  j["materials"]["cloth"].erase("strain_limit");

  // Strain rosette: membrane and bending effects, bending only when asked.
  j["cloth"][0]["model"] = "strain-rosette";
  EXPECT_EQ(profile_names(*build(parse(j)).system),
            (std::vector<std::string>{"strain-rosette", "bending", "gravity", "viscosity", "damping", "wind", "pins"}));
  j["cloth"][0]["bending"] = false;
  EXPECT_EQ(profile_names(*build(parse(j)).system),
            (std::vector<std::string>{"strain-rosette", "gravity", "viscosity", "damping", "wind", "pins"}));
}

TEST(SceneBuild, SwitchingAnEffectOffRemovesExactlyItsWork) {
  json j = tiny_scene();
  j["effects"]["viscosity"] = {{"k", 0.01}};
  j["effects"]["wind"] = {{"velocity", {0, 0, 2}}, {"turbulence", 0.2}};
  Scene on = build(parse(j));
  const auto r_on = run(on);
  ASSERT_TRUE(r_on.ok) << r_on.error;
  j["effects"]["wind"]["enabled"] = false;
  Scene off = build(parse(j));
  const auto r_off = run(off);
  ASSERT_TRUE(r_off.ok) << r_off.error;

  // Same steps and force evaluations; the wind's calls are gone, every other effect's unchanged.
  ASSERT_EQ(r_on.stats.steps, 200);
  EXPECT_EQ(r_on.stats.steps, r_off.stats.steps);
  EXPECT_EQ(on.system->force_evaluations(), off.system->force_evaluations());
  const auto& pon = on.system->profile();
  const auto& poff = off.system->profile();
  ASSERT_EQ(pon.size(), poff.size() + 1);
  EXPECT_EQ(pon[3].name, "wind");
  EXPECT_EQ(pon[3].force_calls, r_on.stats.rhs_evaluations);
  for (std::size_t k = 0, l = 0; k < pon.size(); ++k) {
    if (pon[k].name == "wind") continue;
    EXPECT_EQ(pon[k].name, poff[l].name);
    EXPECT_EQ(pon[k].force_calls, poff[l].force_calls);
    ++l;
  }
  // The work saved is the wind's: one visit per triangle per force evaluation.
  EXPECT_EQ(work(on) - work(off), r_on.stats.rhs_evaluations * static_cast<long>(on.system->model().triangles.size()));
}

TEST(SceneBuild, PinsByIndexSetAndRegion) {
  json j = tiny_scene();
  auto pins = [&](json group) {
    j["effects"]["pins"] = json::array({group});
    return build(parse(j)).pinned;
  };
  EXPECT_EQ(pins({{"sets", {"corner-u0v0", "corner-u1v1"}}}), (std::vector<int>{0, 24}));
  EXPECT_EQ(pins({{"sets", {"corners"}}}), (std::vector<int>{0, 4, 20, 24}));
  EXPECT_EQ(pins({{"sets", {"edge-v0"}}}), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(pins({{"sets", {"edge-u1"}}}), (std::vector<int>{4, 9, 14, 19, 24}));
  EXPECT_EQ(pins({{"sets", {"row-2"}}}), (std::vector<int>{10, 11, 12, 13, 14}));
  EXPECT_EQ(pins({{"sets", {"column-1"}}}), (std::vector<int>{1, 6, 11, 16, 21}));
  EXPECT_EQ(pins({{"particles", {7, 3, 7}}}), (std::vector<int>{3, 7}));
  // A box around the top row (y = 1).
  EXPECT_EQ(pins({{"region", {{"min", {-1, 0.95, -1}}, {"max", {1, 1.05, 1}}}}}), (std::vector<int>{0, 1, 2, 3, 4}));
  // The union of all three.
  EXPECT_EQ(pins({{"particles", {12}}, {"sets", {"corner-u0v0"}}, {"region", {{"min", {0.35, 0.55, -1}}, {"max", {1, 0.65, 1}}}}}),
            (std::vector<int>{0, 12, 24}));
}

TEST(SceneBuild, PinnedParticlesStayAndMovingPinsMove) {
  json j = tiny_scene();
  j["effects"]["pins"] = json::array({{{"sets", {"corner-u0v0"}}}, {{"sets", {"corner-u1v0"}}, {"velocity", {0.1, 0, 0}}}});
  Scene s = build(parse(j));
  auto integ = sim::make_integrator(s.integrator);
  sim::State st = sim::initial_state(s.system->model());
  sim::MemorySink mem;
  const auto r = sim::run(*s.system, *integ, st, s.run, {&mem});
  ASSERT_TRUE(r.ok) << r.error;
  const auto& last = mem.frames.back();
  EXPECT_TRUE(sim::at(last, 0).isApprox(Vec3(0, 1, 0)));
  EXPECT_TRUE(sim::at(last, 4).isApprox(Vec3(0.4 + 0.1 * 0.2, 1, 0), 1e-12));
  EXPECT_LT(sim::at(last, 24).y(), 0.6);  // the free bottom corner fell
  EXPECT_EQ(profile_names(*s.system), (std::vector<std::string>{"mass-spring", "gravity", "pins", "pins"}));
}

TEST(SceneBuild, XvcPiecesAreMeshedAndLaidInARow) {
  const auto dir = vgd::test::scratch_dir("scene_xvc_pieces");
  two_squares(dir);
  json j = tiny_scene();
  j["cloth"][0] = {{"name", "squares"},
                   {"xvc", {{"file", "squares.xvc"}, {"gap", 0.1}}},
                   {"placement", {{"origin", {0, 2, 0}}, {"u", {1, 0, 0}}, {"v", {0, 0, -1}}}},
                   {"material", "cloth"}};
  j["materials"]["cloth"].erase("particle_mass");  // masses from density
  j["effects"]["pins"] = json::array({{{"piece", "BIG"}, {"region", {{"min", {-1, 1, -0.51}}, {"max", {1, 3, -0.49}}}}}});
  write_file_atomic(dir / "scene.json", j.dump(2));
  const Scene s = build(load_scene(dir / "scene.json"));

  ASSERT_EQ(s.pieces.size(), 2u);
  EXPECT_EQ(s.pieces[0].name, "BIG");
  EXPECT_EQ(s.pieces[1].name, "SMALL");
  const auto& m = s.system->model();
  EXPECT_EQ(m.pieces, (std::vector<std::string>{"BIG", "SMALL"}));
  // Flat in the plane y = 2; pattern y goes to -z; SMALL starts 0.1 m after BIG ends.
  double small_min_x = 1e9, big_max_x = -1e9;
  for (const auto& p : s.pieces)
    for (int i = p.first; i < p.first + p.count; ++i) {
      EXPECT_DOUBLE_EQ(sim::at(m.x0, i).y(), 2.0);
      EXPECT_LE(sim::at(m.x0, i).z(), 1e-12);
      if (p.name == "BIG") big_max_x = std::max(big_max_x, sim::at(m.x0, i).x());
      else small_min_x = std::min(small_min_x, sim::at(m.x0, i).x());
    }
  EXPECT_NEAR(big_max_x, 0.5, 1e-12);
  EXPECT_NEAR(small_min_x, 0.6, 1e-12);
  // Masses: area x density over both pieces.
  EXPECT_NEAR(m.mass.sum(), 0.1 * (0.25 + 0.09), 1e-12);
  // The region pin holds BIG's far edge (pattern y = 0.5 -> z = -0.5), 11 nodes at 5 cm.
  EXPECT_EQ(s.pinned.size(), 11u);
  for (int i : s.pinned) EXPECT_LT(i, s.pieces[0].count);
}

TEST(SceneBuild, XvcPiecesCanBeChosenByName) {
  const auto dir = vgd::test::scratch_dir("scene_xvc_choose");
  two_squares(dir);
  json j = tiny_scene();
  j["cloth"][0] = {{"name", "one"}, {"xvc", {{"file", "squares.xvc"}, {"pieces", {"SMALL"}}, {"spacing", "10 cm"}}},
                   {"material", "cloth"}};
  j["effects"]["pins"] = json::array({{{"piece", "SMALL"}, {"sets", {"all"}}}});
  write_file_atomic(dir / "scene.json", j.dump(2));
  const Scene s = build(load_scene(dir / "scene.json"));
  ASSERT_EQ(s.pieces.size(), 1u);
  EXPECT_EQ(s.pieces[0].name, "SMALL");
  EXPECT_EQ(s.pinned.size(), static_cast<std::size_t>(s.pieces[0].count));
  EXPECT_LT(s.pieces[0].count, 30);  // 10 cm spacing on a 0.3 m square, not 5 cm
  for (int i = 0; i < s.pieces[0].count; ++i) EXPECT_DOUBLE_EQ(s.system->model().mass[i], 0.01);  // particle_mass

  j["cloth"][0]["xvc"]["pieces"] = {"SLEEVE"};
  write_file_atomic(dir / "scene.json", j.dump(2));
  expect_error([&] { build(load_scene(dir / "scene.json")); }, (dir / "scene.json").string(), "cloth[0].xvc.pieces[0]",
               "no piece or block 'SLEEVE' in size 'M'");
  j["cloth"][0]["xvc"]["file"] = "missing.xvc";
  write_file_atomic(dir / "scene.json", j.dump(2));
  expect_error([&] { build(load_scene(dir / "scene.json")); }, (dir / "scene.json").string(), "cloth[0].xvc.file",
               "no such file");
}

namespace vgd::scene {
namespace {

// A garment entry is dressed on the body by the dress stage: scene::build
// alone refuses it, naming the scene file, the field and what builds it.
TEST(SceneBuild, AGarmentEntryNeedsTheDressStage) {
  json j = test::tiny_scene();
  j["avatar"] = json::parse(R"({"sphere": {"centre": [0, 0.5, 0], "radius": 0.2}})");
  j["cloth"][0] = json{{"name", "skirt"},
                       {"garment", {{"file", (vgd::test::source_dir() / "data/garments/a-line-skirt.xvc").string()}}},
                       {"material", "cloth"}};
  j["effects"].erase("pins");
  const SceneDef def = test::parse(j, "garment-scene.json");
  test::expect_error([&] { build(def); }, "garment-scene.json", "cloth[0].garment", "dress::build");
}

// Offset contact replaces the body collision and self-collision, and the
// cloth starts outside the body: a sheet hanging through a sphere has its
// particles inside moved out to 1.5 contact radii from the sphere's surface.
TEST(SceneBuild, OffsetContactReplacesBothContactsAndStartsTheClothOutsideTheBody) {
  json j = test::tiny_scene();
  j["avatar"] = json::parse(R"({"sphere": {"centre": [0.2, 0.8, 0], "radius": 0.1}})");
  j["effects"]["contact"] = json::parse(R"({"radius": "3 mm"})");
  const SceneDef def = test::parse(j, "contact-scene.json");
  ASSERT_TRUE(def.effects.contact);
  EXPECT_DOUBLE_EQ(def.effects.contact->radius, 0.003);
  const auto names = effect_names(def);
  EXPECT_NE(std::find(names.begin(), names.end(), "contact"), names.end());
  EXPECT_EQ(std::find(names.begin(), names.end(), "body-collision"), names.end());
  const Scene s = build(def);
  bool contact = false;
  for (const auto& e : s.system->effects()) contact = contact || std::string(e->name()) == "contact";
  EXPECT_TRUE(contact);
  const sim::TriangleBvh bvh(s.avatar->surface);
  const auto& m = s.system->model();
  int inside_before = 0;
  const sim::Model raw = [&] {
    json k = j;
    k["effects"].erase("contact");
    return build(test::parse(k, "plain.json")).system->model();
  }();
  for (int i = 0; i < raw.num_particles(); ++i)
    if (bvh.closest(sim::at(raw.x0, i)).distance < 0.0) ++inside_before;
  EXPECT_GT(inside_before, 0);  // the case has cloth inside the body
  for (int i = 0; i < m.num_particles(); ++i)
    EXPECT_GE(bvh.closest(sim::at(m.x0, i)).distance, 1.5 * 0.003 - 1e-9) << i;
}

TEST(SceneBuild, OffsetContactIsCheckedAndGoesAlone) {
  const auto with_avatar = [](json& j) {
    j["avatar"] = json::parse(R"({"sphere": {"centre": [0.2, 0.8, 0], "radius": 0.1}})");
  };
  test::expect_scene_error([](json& j) { j["effects"]["contact"] = json::object(); }, "effects.contact",
                           "no avatar");
  test::expect_scene_error(
      [&](json& j) {
        with_avatar(j);
        j["effects"]["contact"] = json::object();
        j["effects"]["self_collision"] = json::object();
      },
      "effects.contact", "not both");
  test::expect_scene_error(
      [&](json& j) {
        with_avatar(j);
        j["effects"]["contact"] = {{"gamma", 0.6}};
      },
      "effects.contact.gamma", "(0, 0.5)");
  test::expect_scene_error(
      [&](json& j) {
        with_avatar(j);
        j["effects"]["contact"] = {{"radius", "3 mm"}, {"reach", "2 mm"}};
      },
      "effects.contact.reach", ">= radius");
}

}  // namespace
}  // namespace vgd::scene
