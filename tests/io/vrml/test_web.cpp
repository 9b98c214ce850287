// Real viewers read what vgd writes. three.js's VRMLLoader (under node) parses
// the static and animated flavours and builds the shapes with the vertex and
// face counts vgd wrote; X_ITE in headless Chromium (playwright-core) shows the
// web catalogue: every flavour loads, the animated and live files move (the
// seed's flag flies from its two pinned corners) and a screenshot of the
// garment's page shows the garment's colour where the garment is.
// three.js cannot parse PROTO or Script declarations (the live flavour) nor,
// as shipped, the CoordinateInterpolator of the animated one: check_vrml.mjs
// reparses that with node names matched longest first; X_ITE reads them all.
// Skipped with a message when node, tests/web/node_modules or chromium are
// absent (.ci/install-deps installs them).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "support/command.hpp"
#include "support/test_paths.hpp"
#include "tube_skirt.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/vrml/vrml.hpp"
#include "vgd/io/vrml/web.hpp"

using namespace vgd;
namespace fs = std::filesystem;
namespace vrml = vgd::io::vrml;
using nlohmann::json;

namespace {

const fs::path kWeb = VGD_WEB_TESTS_DIR;

bool have_node() { return std::system("node --version > /dev/null 2>&1") == 0; }
bool have_module(const char* name) { return fs::is_regular_file(kWeb / "node_modules" / name / "package.json"); }

#define VGD_REQUIRE_NODE_MODULE(name)                                                                          \
  do {                                                                                                         \
    if (!have_node()) GTEST_SKIP() << "SKIPPED: node not found (.ci/install-deps installs nodejs)";            \
    if (!have_module(name))                                                                                    \
      GTEST_SKIP() << "SKIPPED: " << name << " not in " << (kWeb / "node_modules")                             \
                   << " (run .ci/install-deps, which runs npm ci there)";                                      \
  } while (0)

// Runs a command in tests/web, returns its stdout.
std::string run(const std::string& command) { return test::command_output("cd '" + kWeb.string() + "' && " + command); }

// Distinct output vertices each piece's faces use.
std::vector<std::size_t> piece_vertex_counts(const vrml::Garment& g, bool welded) {
  std::vector<std::size_t> counts;
  for (const auto& p : vrml::output_mesh(g.cloth, welded).pieces) {
    std::set<int> s;
    for (const auto& f : p.coord) s.insert(f.begin(), f.end());
    counts.push_back(s.size());
  }
  return counts;
}

const json* mesh_named(const json& file, const std::string& name) {
  for (const auto& m : file["meshes"])
    if (m["name"] == name) return &m;
  return nullptr;
}

}  // namespace

TEST(ThreeJsVrmlLoader, ParsesTheStaticAndAnimatedFlavoursWithTheCountsVgdWrote) {
  VGD_REQUIRE_NODE_MODULE("three");
  const auto dir = test::scratch_dir("vrml_threejs");
  auto g = test::tube_skirt();
  write_file_atomic(dir / "static.wrl", vrml::static_vrml(g));
  write_file_atomic(dir / "animated.wrl", vrml::animated_vrml(g));
  auto textured = g;
  textured.looks[0].texture = "denim.png";
  write_file_atomic(dir / "textured.wrl", vrml::static_vrml(textured));
  const std::string out = run("node check_vrml.mjs '" + (dir / "static.wrl").string() + "' '" +
                              (dir / "animated.wrl").string() + "' '" + (dir / "textured.wrl").string() + "'");
  const json r = json::parse(out, nullptr, false);
  ASSERT_TRUE(r.is_array() && r.size() == 3) << out;

  const auto welded = piece_vertex_counts(g, true), unwelded = piece_vertex_counts(g, false);
  for (std::size_t f = 0; f < 3; ++f) {
    SCOPED_TRACE(r[f]["file"].get<std::string>());
    ASSERT_TRUE(r[f]["ok"].get<bool>()) << r[f].value("error", "");
    // FRONT, BACK and the body (three also makes a sky dome of the Background).
    int named = 0;
    for (const auto& m : r[f]["meshes"]) named += m["name"] != "";
    EXPECT_EQ(named, 3);
    // Only the animated file needs three's lexer fixed (see check_vrml.mjs).
    EXPECT_EQ(r[f].value("lexer_fix", false), f == 1);
    const auto& counts = f == 1 ? unwelded : welded;
    int piece = 0;
    for (const char* name : {"Piece_FRONT", "Piece_BACK"}) {
      const json* m = mesh_named(r[f], name);
      ASSERT_NE(m, nullptr) << name;
      EXPECT_EQ((*m)["faces"].get<int>(), 96) << name;
      EXPECT_EQ((*m)["vertices"].get<int>(), 3 * 96) << name;  // three.js unshares vertices with texture coordinates
      EXPECT_EQ((*m)["distinct_vertices"].get<std::size_t>(), counts[piece++]) << name;
      EXPECT_TRUE((*m)["uv"].get<bool>());
      EXPECT_TRUE((*m)["double_sided"].get<bool>());  // solid FALSE
      // Texture coordinates are the material coordinates: 0.6 m along the grain, 0.5 m across.
      EXPECT_NEAR((*m)["uv_max"][0].get<double>() - (*m)["uv_min"][0].get<double>(), 0.6, 1e-4);
      EXPECT_NEAR((*m)["uv_max"][1].get<double>() - (*m)["uv_min"][1].get<double>(), 0.5, 1e-4);
    }
    const json* body = mesh_named(r[f], "avatar");
    ASSERT_NE(body, nullptr);
    EXPECT_EQ((*body)["faces"].get<std::size_t>(), g.body->triangles.size());
    EXPECT_EQ((*body)["distinct_vertices"].get<std::size_t>(), g.body->vertices.size());
  }
  // The static file's FRONT has its explicit normals; the BACK is red.
  EXPECT_TRUE((*mesh_named(r[0], "Piece_FRONT"))["normal"].get<bool>());
  const auto& red = (*mesh_named(r[0], "Piece_BACK"))["color"];
  EXPECT_GT(red[0].get<double>(), 4 * red[1].get<double>());
}

TEST(XIteInChromium, TheCatalogueShowsEveryFlavourAndTheLiveFilesMove) {
  VGD_REQUIRE_NODE_MODULE("x_ite");
  if (!have_module("playwright-core")) GTEST_SKIP() << "SKIPPED: playwright-core not in tests/web/node_modules";
  if (!fs::exists("/usr/bin/chromium")) GTEST_SKIP() << "SKIPPED: /usr/bin/chromium not found (Debian chromium)";
  const fs::path x_ite = VGD_X_ITE_TEST_DIR;
  if (!fs::is_regular_file(x_ite / "x_ite.min.js")) GTEST_SKIP() << "SKIPPED: no x_ite.min.js in " << x_ite;

  // The catalogue: the skirt in three flavours and the seed's flag.
  const auto dir = test::scratch_dir("vrml_web");
  auto g = test::tube_skirt();
  write_file_atomic(dir / "skirt.wrl", vrml::static_vrml(g));
  write_file_atomic(dir / "skirt-animated.wrl", vrml::animated_vrml(g));
  vrml::LiveOptions live;
  live.pinned = vrml::top_particles(g, 0.01);
  live.colliders = vrml::body_colliders(g, 4);
  live.wind = {0, 0, -4}, live.wind_coefficient = 2.4;
  write_file_atomic(dir / "skirt-live.wrl", vrml::live_vrml(g, live));
  write_file_atomic(dir / "flag.wrl", vrml::live_flag_vrml());
  vrml::write_vrml(dir / "flag.wrl.gz", vrml::live_flag_vrml());
  std::vector<vrml::WebEntry> entries;
  for (const char* name : {"skirt", "skirt-animated", "skirt-live", "flag"})
    entries.push_back({name, name, std::string(name) + ".wrl", {}, {{"pieces", "2"}}});
  entries.push_back({"flag-gz", "flag, gzip", "flag.wrl.gz", {}, {}});
  vrml::write_web_catalogue(dir, entries, x_ite);
  ASSERT_TRUE(fs::is_regular_file(dir / "index.html"));
  ASSERT_TRUE(fs::is_regular_file(dir / "x_ite" / "x_ite.min.js"));
  EXPECT_NE(read_file(dir / "skirt.html").find("<x3d-canvas id=\"scene\" src=\"skirt.wrl\""), std::string::npos);
  EXPECT_NE(read_file(dir / "index.html").find("href=\"flag.html\""), std::string::npos);

  const auto pins = vrml::top_particles(g, 0.01);
  const auto mesh = vrml::output_mesh(g.cloth, true);
  const json spec = {
      {"pages",
       {{{"page", "skirt.html"},
         {"lengths", {"GarmentCoord.point", "Piece_FRONT.geometry.coordIndex", "Piece_BACK.geometry.texCoordIndex"}},
         {"screenshot", "skirt.png"},
         {"colour", {vrml::kDefaultFabric.r, vrml::kDefaultFabric.g, vrml::kDefaultFabric.b}}},
        {{"page", "skirt-animated.html"},
         {"lengths", {"GarmentCoord.point"}},
         {"motion", {{"node", "GarmentCoord"}, {"field", "point"}, {"after_s", 0.6}}}},
        {{"page", "skirt-live.html"},
         {"lengths", {"Cloth.coordinate"}},
         {"motion", {{"node", "Cloth"}, {"field", "coordinate"}, {"after_s", 0.8},
                     {"pinned", {mesh.particle_vertex[pins[0]]}}}}},
        {{"page", "flag.html"},
         {"lengths", {"Flag.coordinate", "Flag.texCoord"}},
         {"motion", {{"node", "Flag"}, {"field", "coordinate"}, {"after_s", 1.0}, {"pinned", {0, 870}}}},
         {"screenshot", "flag.png"},
         {"colour", {0.8, 0.1, 0.1}}},
        {{"page", "flag-gz.html"}, {"lengths", {"Flag.texCoord"}}}}}};
  write_file_atomic(dir / "spec.json", spec.dump());
  const std::string out = run("node web_check.mjs '" + dir.string() + "' '" + (dir / "spec.json").string() + "'");
  const json r = json::parse(out, nullptr, false);
  ASSERT_TRUE(r.is_object() && r.contains("pages")) << out;
  ASSERT_FALSE(r.contains("error")) << r["error"];
  ASSERT_EQ(r["pages"].size(), 5u) << out;
  for (const auto& p : r["pages"]) EXPECT_EQ(p["event"], "load") << p.dump();

  // Static: X_ITE holds what vgd wrote; the screenshot is not blank and shows the fabric in the middle.
  const auto& st = r["pages"][0];
  EXPECT_EQ(st["lengths"]["GarmentCoord.point"].get<std::size_t>(), mesh.vertex_particle.size());
  EXPECT_EQ(st["lengths"]["Piece_FRONT.geometry.coordIndex"].get<int>(), 4 * 96);
  EXPECT_EQ(st["lengths"]["Piece_BACK.geometry.texCoordIndex"].get<int>(), 4 * 96);
  EXPECT_GT(st["pixels"]["luma_stddev"].get<double>(), 0.03) << st["pixels"];
  EXPECT_GT(st["pixels"]["distinct_colours"].get<int>(), 20) << st["pixels"];
  EXPECT_GT(st["pixels"]["centre_garment_fraction"].get<double>(), 0.3) << st["pixels"];
  // Animated: the interpolator moves the coordinates (the hem sways).
  const auto& an = r["pages"][1];
  EXPECT_EQ(an["lengths"]["GarmentCoord.point"].get<int>(), g.cloth.num_particles());
  EXPECT_GT(an["motion"]["max_moved"].get<double>(), 1e-3) << an["motion"];
  // Live skirt: the script moves the cloth, the waist stays pinned.
  const auto& lv = r["pages"][2];
  EXPECT_EQ(lv["lengths"]["Cloth.coordinate"].get<std::size_t>(), mesh.vertex_particle.size());
  EXPECT_GT(lv["motion"]["max_moved"].get<double>(), 1e-4) << lv["motion"];
  EXPECT_LT(lv["motion"]["pinned_moved"][0].get<double>(), 1e-6) << lv["motion"];
  // The flag: the script made the 30 x 30 grid, it flies, its staff corners stay.
  const auto& fl = r["pages"][3];
  EXPECT_EQ(fl["lengths"]["Flag.coordinate"].get<int>(), 900);
  EXPECT_EQ(fl["lengths"]["Flag.texCoord"].get<int>(), 900);
  EXPECT_GT(fl["motion"]["max_moved"].get<double>(), 0.02) << fl["motion"];
  EXPECT_LT(fl["motion"]["pinned_moved"][0].get<double>(), 1e-6);
  EXPECT_LT(fl["motion"]["pinned_moved"][1].get<double>(), 1e-6);
  EXPECT_GT(fl["pixels"]["garment_fraction"].get<double>(), 0.01) << fl["pixels"];
  // The gzip-compressed flag loads the same.
  EXPECT_EQ(r["pages"][4]["lengths"]["Flag.texCoord"].get<int>(), 900);
}

