// vgd drape end to end: the project's skirt on its default mannequin, and a
// real imported garment (MEN_CLASSIC_TEE) sewn with the seam file written for
// it in tests/data. Each test reads the certificate the drape writes and
// checks the drape's figures against their limits.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <nlohmann/json.hpp>

#include "support/json_file.hpp"
#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"

namespace vgd::test {
namespace {

using nlohmann::json;


int closed_pairs(const json& cert) {
  int n = 0;
  for (const auto& s : cert["seams"]) n += s["closed"].get<int>();
  return n;
}
int all_pairs(const json& cert) {
  int n = 0;
  for (const auto& s : cert["seams"]) n += s["pairs"].get<int>();
  return n;
}

TEST(CliDrape, ShippedSkirtSewsAndComesToRestOnTheMannequin) {
  const auto out = scratch_dir("drape-skirt");
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/a-line-skirt.xvc").string(), "-o", out.string(),
                          "--time-limit", "6", "-q"});
  EXPECT_EQ(r.code, 0) << r.err;  // every check passed (3 would say one failed)
  ASSERT_TRUE(std::filesystem::exists(out / "garment.obj"));
  ASSERT_TRUE(std::filesystem::exists(out / "avatar.obj"));
  const json c = read_json(out / "certificate.json");
  EXPECT_TRUE(c["passed"].get<bool>());
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  // No cloth triangle passes through another (exact test, sewn topology).
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0) << c["triangle_intersections_by_pieces"].dump();
  EXPECT_LT(c["stop"]["simulated_s"].get<double>(), 6.0);
  // Every seam closed (side seams and the waist seam with its three hems).
  ASSERT_EQ(c["seams"].size(), 3u);
  EXPECT_GT(all_pairs(c), 100);
  EXPECT_EQ(closed_pairs(c), all_pairs(c)) << c["seams"].dump();
  // No particle inside the body by more than 1 mm (exact, against its triangles),
  // nor the body showing through the cloth between particles, nothing warned.
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 1e-3);
  EXPECT_EQ(c["body_through_cloth"].get<int>(), 0);
  EXPECT_TRUE(c["warnings"].empty()) << c["warnings"].dump();
  // The skirt hangs from the waist: it touches the body and the body carries it.
  EXPECT_GT(c["contact"]["particles"].get<int>(), 100);
  EXPECT_GT(c["contact"]["force_n"].get<double>(), 0.0);
  // The certificate holds the kinetic-energy history, one value per frame.
  EXPECT_EQ(c["kinetic_energy"]["values"].size(), c["stop"]["frames"].get<std::size_t>());
  // Strain stays that of a hanging garment, not of cloth pulled apart: p95
  // under 15 % for every piece. The waistband, 1 cm of ease round the waist,
  // is the tightest: 11.6 % since self-collision keeps cloth out of the body
  // (17.1 % before, when corrections pushed the band into the waist and the
  // body pushed it back; docs/drape.md).
  for (const auto& s : c["strain"]) {
    EXPECT_LT(s["warp"]["p95"].get<double>(), 0.15) << s.dump();
    EXPECT_LT(s["weft"]["p95"].get<double>(), 0.15) << s.dump();
  }
}

// The strain rosette (seed 002's orthotropic membrane with bending) drapes
// too: `--model strain-rosette`, said in the certificate's settings. At a
// 2.5 cm mesh to keep the test short (10 s; the default 1.5 cm: 33 s,
// docs/drape.md).
TEST(CliDrape, TheSkirtDrapesWithTheStrainRosette) {
  const auto out = scratch_dir("drape-skirt-rosette");
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/a-line-skirt.xvc").string(), "-o", out.string(),
                          "--model", "strain-rosette", "--spacing", "0.025", "--time-limit", "6", "-q"});
  EXPECT_EQ(r.code, 0) << r.err;
  const json c = read_json(out / "certificate.json");
  EXPECT_EQ(c["settings"]["model"], "strain-rosette");
  EXPECT_TRUE(c["passed"].get<bool>()) << c["failures"].dump();
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  EXPECT_EQ(closed_pairs(c), all_pairs(c)) << c["seams"].dump();
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0);
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 1e-3);
  for (const auto& s : c["strain"]) {
    EXPECT_LT(s["warp"]["p95"].get<double>(), 0.15) << s.dump();
    EXPECT_LT(s["weft"]["p95"].get<double>(), 0.15) << s.dump();
  }
  // A model vgd does not have is refused by name.
  const auto bad = run_vgd({"drape", (source_dir() / "data/garments/a-line-skirt.xvc").string(), "-o", out.string(),
                            "--model", "finite-elements", "-q"});
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--model"), std::string::npos) << bad.err;
}

TEST(CliDrape, ACutShortDrapeSaysWhyAndFailsItsChecks) {
  const auto out = scratch_dir("drape-short");
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/a-line-skirt.xvc").string(), "-o", out.string(),
                          "--time-limit", "0.04", "-q"});
  EXPECT_EQ(r.code, 3) << r.err;  // ran, but not to rest with every seam closed
  const json c = read_json(out / "certificate.json");
  EXPECT_EQ(c["stop"]["reason"], "time limit");
  EXPECT_FALSE(c["passed"].get<bool>());
  EXPECT_NEAR(c["stop"]["simulated_s"].get<double>(), 0.04, 1e-9);
  EXPECT_LT(closed_pairs(c), all_pairs(c));
  // Inputs and settings are recorded.
  EXPECT_NE(c["inputs"]["garment"].get<std::string>().find("a-line-skirt.xvc"), std::string::npos);
  EXPECT_EQ(c["inputs"]["avatar"], "mannequin 38");
  EXPECT_EQ(c["settings"]["integrator"], "implicit-euler");
}

TEST(CliDrape, BadInputIsNamed) {
  const auto out = scratch_dir("drape-bad");
  const auto missing = run_vgd({"drape", (out / "nope.xvc").string(), "-o", out.string()});
  EXPECT_EQ(missing.code, 2);  // CLI11: the file does not exist
  const auto doc = out / "empty.xvc";
  std::ofstream(doc) << "<GARMENT";
  const auto bad = run_vgd({"drape", doc.string(), "-o", out.string()});
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("empty.xvc"), std::string::npos) << bad.err;
}

// Two garments: the T-shirt worn over the skirt. Both are assembled, each
// with its own pieces (named after their garment), the outer one placed
// outside the inner one's cloth; the same garment twice is refused.
TEST(CliDrape, TwoGarmentsAreDressedInLayers) {
  const auto out = scratch_dir("drape-two");
  const auto skirt = (source_dir() / "data/garments/a-line-skirt.xvc").string();
  const auto tee = (source_dir() / "data/garments/t-shirt.xvc").string();
  const auto r = run_vgd({"drape", skirt, tee, "-o", out.string(), "--spacing", "0.02", "--time-limit", "0.04", "-q"});
  EXPECT_EQ(r.code, 3) << r.err;  // a frame only: not at rest
  const json c = read_json(out / "certificate.json");
  EXPECT_NE(c["inputs"]["garment"].get<std::string>().find("a-line-skirt.xvc"), std::string::npos);
  EXPECT_NE(c["inputs"]["garment_2"].get<std::string>().find("t-shirt.xvc"), std::string::npos);
  EXPECT_EQ(c["seams"].size(), 3u + 8u);  // the skirt's and the T-shirt's
  std::set<std::string> pieces;
  for (const auto& s : c["strain"]) pieces.insert(s["piece"].get<std::string>());
  EXPECT_TRUE(pieces.count("a-line-skirt/FRONT_38")) << c["strain"].dump();
  EXPECT_TRUE(pieces.count("t-shirt/FRONT_38")) << c["strain"].dump();
  EXPECT_EQ(pieces.size(), 7u);  // 3 skirt pieces + 4 T-shirt pieces
  // The T-shirt starts outside the skirt (placed round the skirt's cloth, not
  // only the body's rings): no triangle of one passes through the other
  // before the first step (99 pairs did when its hem over the hips was placed
  // from the torso's rings).
  const auto start = out / "start";
  const auto r0 = run_vgd({"drape", skirt, tee, "-o", start.string(), "--time-limit", "0.001", "--no-self-collision",
                           "-q"});
  ASSERT_TRUE(r0.code == 0 || r0.code == 3) << r0.err;
  const json c0 = read_json(start / "certificate.json");
  if (c0.contains("triangle_intersections_by_pieces")) {
    for (const auto& [pair, n] : c0["triangle_intersections_by_pieces"].items()) {
      EXPECT_FALSE(pair.find("a-line-skirt/") != std::string::npos && pair.find("t-shirt/") != std::string::npos)
          << pair << ": " << n;
    }
  }
  const auto twice = run_vgd({"drape", skirt, skirt, "-o", out.string(), "-q"});
  EXPECT_EQ(twice.code, 1);
  EXPECT_NE(twice.err.find("twice"), std::string::npos) << twice.err;
}

// Sewing pulls the T-shirt in against the skirt, and the body pushes the
// skirt out: layered self-collision (the outer garment kept on the far side
// of the inner one from the body, docs/collisions.md) leaves no triangle of
// one through the other 0.4 s in, while both sew. Without layers 855 pairs
// crossed at this point (2 cm mesh).
TEST(CliDrape, TwoGarmentsDoNotPassThroughEachOtherWhileSewing) {
  const auto out = scratch_dir("drape-two-sewing");
  const auto skirt = (source_dir() / "data/garments/a-line-skirt.xvc").string();
  const auto tee = (source_dir() / "data/garments/t-shirt.xvc").string();
  const auto r = run_vgd({"drape", skirt, tee, "-o", out.string(), "--spacing", "0.02", "--time-limit", "0.4", "-q"});
  ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
  const json c = read_json(out / "certificate.json");
  int closed = 0, pairs = 0;
  for (const auto& sm : c["seams"]) closed += sm["closed"].get<int>(), pairs += sm["pairs"].get<int>();
  EXPECT_GT(closed, pairs / 2) << "the seams should be closing";
  // While seams sew, the strips along them are left free to dip into the body
  // (docs/collisions.md, "The body in the corrections"): 6.3 mm at the left
  // armpit here. The drape's 1 mm promise is for the end, once every seam is
  // sewn (SkirtAndTShirtOverItComeToRestUntangled); this bounds the dip.
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 0.01);
  if (c.contains("triangle_intersections_by_pieces")) {
    for (const auto& [pair, n] : c["triangle_intersections_by_pieces"].items()) {
      EXPECT_FALSE(pair.find("a-line-skirt/") != std::string::npos && pair.find("t-shirt/") != std::string::npos)
          << pair << ": " << n;
    }
  }
}

// The whole dressing: the skirt and the T-shirt over it, from flat pieces to
// rest, every seam sewn, nothing inside the body by more than 1 mm and no
// cloth triangle through another, within either garment or between them
// (measured: rest after 5.64 s simulated, 47 s wall on two threads — the
// layers slip on each other in bursts for seconds; docs/drape.md). The
// drape's default time limit, 8 s.
TEST(CliDrape, SkirtAndTShirtOverItComeToRestUntangled) {
  const auto out = scratch_dir("drape-two-rest");
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/a-line-skirt.xvc").string(),
                          (source_dir() / "data/garments/t-shirt.xvc").string(), "-o", out.string(), "--time-limit",
                          "8", "-q"});
  EXPECT_EQ(r.code, 0) << r.err;
  const json c = read_json(out / "certificate.json");
  EXPECT_TRUE(c["passed"].get<bool>());
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  EXPECT_EQ(closed_pairs(c), all_pairs(c)) << c["seams"].dump();
  EXPECT_EQ(all_pairs(c), 294);
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 1e-3);
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0) << c["triangle_intersections_by_pieces"].dump();
}

// MEN_CLASSIC_TEE (Gerber, ../shared): the front and back are half pieces on
// the fold; imported unfolded, their shoulders and side seams sewn from
// tests/data/men-classic-tee.unfolded.seams.json on the men's size-50
// mannequin. The sleeves (a two-piece sleeve the seam suggestions have no
// rule for, and no seam in the file) are left out.
TEST(CliDrape, ImportedMenClassicTeeBodySews) {
  VGD_REQUIRE_SHARED();
  const auto out = scratch_dir("drape-tee");
  const auto xvc = out / "tee.xvc", sewn = out / "tee-sewn.xvc";
  ASSERT_EQ(run_vgd({"import", shared_dxf("MEN_CLASSIC_TEE.DXF").string(), "--unfold-mirrored", "-o", xvc.string(),
                     "-q"})
                .code,
            0);
  const auto applied = run_vgd({"seams", "apply", xvc.string(),
                                (source_dir() / "tests/data/men-classic-tee.unfolded.seams.json").string(), "--size",
                                "50", "-o", sewn.string(), "-q"});
  ASSERT_EQ(applied.code, 0) << applied.err;
  const auto r = run_vgd({"drape", sewn.string(), "--size", "50", "--size-table", "en13402-men", "--pieces",
                          "REGULAR TEEFR", "REGULAR TEEBK", "--time-limit", "4", "-o", out.string(), "-q"});
  ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
  const json c = read_json(out / "certificate.json");
  ASSERT_EQ(c["seams"].size(), 4u);  // two shoulders, two side seams
  EXPECT_EQ(closed_pairs(c), all_pairs(c)) << c["seams"].dump();
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 1e-3);
  // No cloth triangle through another (38 pairs before the hem started
  // outside the hips; a few where seams zip before untangling).
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0) << c["triangle_intersections_by_pieces"].dump();
  // It hangs on the shoulders: the body carries it.
  EXPECT_GT(c["contact"]["particles"].get<int>(), 50);
  EXPECT_GT(c["contact"]["force_n"].get<double>(), 0.0);
}

// A polo cut with one sleeve pattern twice (drill-holes.DXF, Gerber): seams
// suggested at the sample size 50 (the left armhole first: suggestions go by
// score), the front, back and both sleeves draped on the men's mannequin.
// Each armhole gets the sleeve placed on its own side, the mirrored copy
// sews as well as the other, and a graded size (44) sews with the sample's
// seams at its own stretches.
class CliDrapePolo : public ::testing::TestWithParam<std::string> {};

TEST_P(CliDrapePolo, BothSleevesAreSewnToTheirOwnArmholes) {
  VGD_REQUIRE_SHARED();
  const std::string size = GetParam();
  const auto out = scratch_dir("drape-polo-" + size);
  const auto xvc = out / "polo.xvc", sewn = out / "polo-sewn.xvc";
  ASSERT_EQ(run_vgd({"import", shared_dxf("drill-holes.DXF").string(), "--unfold-mirrored", "-o", xvc.string(), "-q"}).code, 0);
  const auto suggested = run_vgd({"seams", "suggest", xvc.string(), "--size", "50", "--apply", "-o", sewn.string()});
  ASSERT_EQ(suggested.code, 0) << suggested.err;
  ASSERT_LT(suggested.out.find("left armhole"), suggested.out.find("right armhole")) << suggested.out;
  const auto r = run_vgd({"drape", sewn.string(), "--size", size, "--size-table", "en13402-men", "--pieces",
                          "SS17_M POLO REG FR", "SS17_M POLO REG BK", "SS17_M POLO REG SL1", "--time-limit", "8", "-o",
                          (out / "drape").string()});
  ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
  EXPECT_EQ(r.err.find("no SEAM sews this size") == std::string::npos, size == "50") << r.err;
  const json c = read_json(out / "drape" / "certificate.json");
  ASSERT_EQ(c["seams"].size(), 8u) << c["seams"].dump();
  for (const auto& sm : c["seams"]) EXPECT_EQ(sm["closed"], sm["pairs"]) << sm.dump();
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0) << c["triangle_intersections_by_pieces"].dump();
  EXPECT_TRUE(c["passed"].get<bool>()) << c["failures"].dump();
}

INSTANTIATE_TEST_SUITE_P(SampleAndGradedSize, CliDrapePolo, ::testing::Values("50", "44"));

// Two threads give the one-thread drape bit for bit, self-collision on:
// forces summed in fixed chunks, detection's threads on fixed triangle ranges
// joined in order (docs/accuracy-vs-time.md, "Reproducibility"). 0.4 s of
// the T-shirt: sewing, contacts and the fail-safe all at work.
TEST(CliDrape, TwoThreadsGiveTheOneThreadDrapeBitForBit) {
  std::string obj[2];
  for (int threads : {1, 2}) {
    const auto out = scratch_dir("drape-threads-" + std::to_string(threads));
    const auto r = run_vgd({"--threads", std::to_string(threads), "drape",
                            (source_dir() / "data/garments/t-shirt.xvc").string(), "--time-limit", "0.4", "-o",
                            out.string(), "-q"});
    ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
    std::ifstream in(out / "garment.obj", std::ios::binary);
    obj[threads - 1].assign(std::istreambuf_iterator<char>(in), {});
  }
  ASSERT_GT(obj[0].size(), 100000u);
  EXPECT_TRUE(obj[0] == obj[1]) << "garment.obj differs between one and two threads";
}

// The drafted T-shirt (front, back, two sleeves) sews every pair and comes to
// rest on the size-38 mannequin with self-collision on (the default): no
// particle inside the body and no triangle through another. Before the
// untangling, the body's push after self-collision and sewn hems left exempt
// left 1–207 crossing pairs depending on the run and the size, most at the
// armholes (docs/collisions.md); without self-collision ~500.
// A drape stopped at its time limit says where its cloth still moves: the
// particle that moved furthest over the run's last second (here the whole
// 0.4 s, the T-shirt still sewing), beside which body segments (on the
// mannequin and on a body file), and the pieces moving half as far; in the
// certificate and in what vgd prints.
TEST(CliDrape, ADrapeStoppedAtItsTimeLimitSaysWhereItStillMoves) {
  const auto out = scratch_dir("drape-still-moving");
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/t-shirt.xvc").string(), "-o", out.string(),
                          "--time-limit", "0.4"});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("no rest: stopped at the time limit, 0.40 s simulated; still moving: a particle "),
            std::string::npos)
      << r.err;
  const json c = read_json(out / "certificate.json");
  ASSERT_TRUE(c.contains("still_moving")) << c.dump();
  const json& m = c["still_moving"];
  EXPECT_NEAR(m["window_s"].get<double>(), 0.4, 1e-9);
  EXPECT_GT(m["path_m"].get<double>(), 0.01);
  std::set<std::string> placed;
  for (const auto& p : c["placement"]) placed.insert(p["piece"].get<std::string>());
  ASSERT_FALSE(m["pieces"].empty());
  for (const auto& [piece, n] : m["pieces"].items()) {
    EXPECT_TRUE(placed.count(piece)) << piece;
    EXPECT_GE(n.get<int>(), 1);
  }
  const std::set<std::string> segments{"head", "neck", "torso", "hips", "left-arm", "right-arm", "left-leg", "right-leg"};
  ASSERT_FALSE(m["near"].empty());
  EXPECT_LE(m["near"].size(), 2u);
  for (const auto& s : m["near"]) EXPECT_TRUE(segments.count(s.get<std::string>())) << s;

  // On a body file (its triangles not labelled: segments from its
  // landmarks) the segments beside it are found as well (the repulsion
  // damped: vgd drape --repulsion-damping).
  const auto body = out / "m38.obj";
  ASSERT_EQ(run_vgd({"mannequin", "--size", "38", "-o", body.string(), "-q"}).code, 0);
  const auto on_file = out / "on-file";
  EXPECT_EQ(run_vgd({"drape", (source_dir() / "data/garments/t-shirt.xvc").string(), "--avatar", body.string(), "-o",
                     on_file.string(), "--time-limit", "0.4", "--repulsion-damping", "1", "-q"})
                .code,
            3);
  const json f = read_json(on_file / "certificate.json");
  // The repulsion's damping, when asked for, is in the settings.
  EXPECT_FALSE(c["settings"].contains("repulsion_damping"));
  EXPECT_EQ(f["settings"]["repulsion_damping"], "1 of critical");
  ASSERT_TRUE(f.contains("still_moving")) << f.dump();
  ASSERT_FALSE(f["still_moving"]["near"].empty()) << f["still_moving"].dump();
  for (const auto& s : f["still_moving"]["near"]) EXPECT_TRUE(segments.count(s.get<std::string>())) << s;
}

TEST(CliDrape, DraftedTShirtSewsEverySeamAndComesToRest) {
  const auto out = scratch_dir("drape-tshirt");
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/t-shirt.xvc").string(), "-o", out.string(),
                          "--time-limit", "6", "-q"});
  ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
  const json c = read_json(out / "certificate.json");
  ASSERT_EQ(c["seams"].size(), 8u);  // sides, shoulders, armholes, underarms
  EXPECT_EQ(closed_pairs(c), all_pairs(c)) << c["seams"].dump();
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  EXPECT_FALSE(c.contains("still_moving")) << "at rest: nothing still moves";
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 1e-3);
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0) << c["triangle_intersections_by_pieces"].dump();
  EXPECT_GT(c["contact"]["particles"].get<int>(), 200);
  // The contact-pressure map beside it: a pressure per particle (per vertex
  // of garment.obj), the certificate's largest among them, nothing where the
  // cloth does not touch the body.
  const json p = read_json(out / "contact-pressure.json");
  EXPECT_EQ(p["unit"], "Pa");
  ASSERT_EQ(p["values"].size(), c["cloth"]["particles"].get<std::size_t>());
  double largest = 0.0;
  int pressing = 0;
  for (const auto& v : p["values"]) largest = std::max(largest, v.get<double>()), pressing += v.get<double>() > 0.0;
  EXPECT_DOUBLE_EQ(largest, c["contact"]["pressure_pa"]["max"].get<double>());
  EXPECT_GT(pressing, 100);
  EXPECT_LE(pressing, c["contact"]["particles"].get<int>());
  // The bodice hangs without being pulled apart: strain p95 under 15 %.
  for (const auto& s : c["strain"])
    if (s["piece"].get<std::string>().find("SLEEVE") == std::string::npos) {
      EXPECT_LT(s["warp"]["p95"].get<double>(), 0.15) << s.dump();
      EXPECT_LT(s["weft"]["p95"].get<double>(), 0.15) << s.dump();
    }
}

// `in` (OBJ, metres, +Y up, facing +Z) rewritten scaled by `scale` with up
// `up` (z or y) and facing `facing` (+z or +x, once up is turned to +Y).
void rewrite_obj(const std::filesystem::path& in_path, const std::filesystem::path& out_path, double scale,
                 const std::string& up, const std::string& facing) {
  std::ifstream in(in_path);
  std::ofstream out(out_path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream v(line.substr(2));
      double x, y, z;
      v >> x >> y >> z;
      if (facing == "+x") std::tie(x, z) = std::pair{z, -x};  // +Z turned to +X about +Y
      if (up == "z") std::tie(y, z) = std::pair{-z, y};        // +Y turned to +Z about +X
      out << "v " << scale * x << ' ' << scale * y << ' ' << scale * z << '\n';
    } else if (line.rfind("f ", 0) == 0) {
      std::istringstream f(line.substr(2));
      std::string a;
      out << 'f';
      while (f >> a) out << ' ' << a.substr(0, a.find('/'));
      out << '\n';
    }
  }
}

// A body brought from elsewhere: the size-38 mannequin written the way
// Blender stores it (centimetres, Z up, front towards −Y), read back with
// every decision automatic. The importer finds its unit, up axis, facing,
// landmarks and arms; the T-shirt's sleeves go on the arms it found, and the
// drape passes every check, as on the mannequin itself.
TEST(CliDrape, TShirtOnAnImportedBodyFindsItsArms) {
  const auto dir = scratch_dir("drape-imported-body");
  ASSERT_EQ(run_vgd({"mannequin", "--size", "38", "-o", (dir / "m38.obj").string(), "-q"}).code, 0);
  rewrite_obj(dir / "m38.obj", dir / "blender.obj", 100.0, "z", "+z");  // (x, y, z) m -> (x, -z, y) cm
  const auto report = run_vgd({"avatar", "report", (dir / "blender.obj").string(), "--json"});
  ASSERT_EQ(report.code, 0) << report.err;
  const json j = json::parse(report.out);
  EXPECT_EQ(j["unit"]["value"], "cm");
  EXPECT_EQ(j["up"]["value"], "z");
  EXPECT_EQ(j["facing"]["value"], "+z");
  EXPECT_EQ(j["nearest_size"]["size"], "38");
  const auto out_dir = dir / "drape";
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/t-shirt.xvc").string(), "--avatar",
                          (dir / "blender.obj").string(), "-o", out_dir.string(), "--time-limit", "6"});
  ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
  EXPECT_NE(r.err.find("up z"), std::string::npos) << "the importer's decisions are printed";
  const json c = read_json(out_dir / "certificate.json");
  EXPECT_EQ(closed_pairs(c), all_pairs(c)) << c["seams"].dump();
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 1e-3);
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0) << c["triangle_intersections_by_pieces"].dump();
  EXPECT_TRUE(c["passed"].get<bool>());
}

// MakeHuman's body from Debian's assimp-testmodels (a Collada export it was
// not written for: helper parts, arms hanging forward and out): the skirt
// rests on it with every check passed, on its hips. The T-shirt sews onto
// it, its sleeves on the arms, and is not passed yet: a sleeve crumples
// through itself as it is sewn onto an arm held in front of the trunk (as
// on the mannequin with its arms swung forward; docs/avatar.md). Listed so
// that a change either way shows here.
TEST(CliDrape, GarmentsOnMakeHumansBody) {
  const std::filesystem::path body = "/usr/share/assimp/models/Collada/human.zae";
  if (!std::filesystem::exists(body)) GTEST_SKIP() << body << " not installed (Debian package assimp-testmodels)";
  const auto dir = scratch_dir("drape-makehuman");
  const auto skirt = run_vgd({"--threads", "1", "drape", (source_dir() / "data/garments/a-line-skirt.xvc").string(),
                              "--avatar", body.string(), "-o", (dir / "skirt").string()});
  EXPECT_EQ(skirt.code, 0) << skirt.err;
  EXPECT_NE(skirt.err.find("left out 4 loose parts"), std::string::npos) << skirt.err;
  const json c = read_json(dir / "skirt" / "certificate.json");
  EXPECT_TRUE(c["passed"].get<bool>()) << c["failures"].dump();
  EXPECT_EQ(c["stop"]["reason"], "rest");
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0);
  for (const auto& p : c["placement"]) EXPECT_EQ(p["segment"], "hips") << p.dump();

  const auto tee = run_vgd({"--threads", "1", "drape", (source_dir() / "data/garments/t-shirt.xvc").string(), "--avatar",
                            body.string(), "-o", (dir / "tee").string(), "--time-limit", "3"});
  EXPECT_EQ(tee.code, 3) << tee.err;
  const json t = read_json(dir / "tee" / "certificate.json");
  std::vector<std::string> segments;
  for (const auto& p : t["placement"]) segments.push_back(p["segment"].get<std::string>());
  std::sort(segments.begin(), segments.end());
  EXPECT_EQ(segments, (std::vector<std::string>{"left-arm", "right-arm", "torso", "torso"}));
  EXPECT_FALSE(t["passed"].get<bool>());
  EXPECT_GT(t["triangle_intersections"].get<int>(), 0) << "the sleeve through itself";
  for (const auto& f : t["failures"]) {
    const std::string k = f["class"].get<std::string>();
    EXPECT_TRUE(k == "no rest" || k == "seams open" || k == "penetration" || k == "self-intersection" ||
                k == "over-stretched")
        << f.dump();
    if (k == "self-intersection") {
      EXPECT_NE(f["detail"].get<std::string>().find("SLEEVE"), std::string::npos) << f.dump();
    }
  }
}

// Bodies in other poses as files bring them: vgd's size-38 mannequin in a
// T-pose and with its arms swung forward, rewritten in another unit, up axis
// and facing. Each comes in upright and facing forward by itself, and the
// garments drape on it as on the mannequin: every seam sewn, at rest, nothing
// in the body or through itself, each piece where it was arranged (sleeves on
// the arms at the arms' own angle), and passed. (The T-shirt on arms swung
// forward is not passed yet: docs/avatar.md.)
struct PosedBody {
  std::string name;
  std::vector<std::string> pose;  // vgd mannequin options
  double scale;                   // file units per metre
  std::string unit, up, facing;   // what the importer must find
  std::string garment;
  std::vector<std::string> drape = {};  // vgd drape options
};

void PrintTo(const PosedBody& b, std::ostream* os) { *os << b.name << " + " << b.garment; }

class CliDrapePosed : public ::testing::TestWithParam<PosedBody> {};

TEST_P(CliDrapePosed, GarmentsDrapeOnAnImportedBodyInItsOwnPose) {
  const PosedBody& b = GetParam();
  const auto dir = scratch_dir("drape-posed-" + b.name + "-" + b.garment);
  std::vector<std::string> make = {"mannequin", "--size", "38", "-o", (dir / "m.obj").string(), "-q"};
  make.insert(make.end(), b.pose.begin(), b.pose.end());
  ASSERT_EQ(run_vgd(make).code, 0);
  const auto body = dir / (b.name + ".obj");
  rewrite_obj(dir / "m.obj", body, b.scale, b.up, b.facing);
  const auto out = dir / "drape";
  std::vector<std::string> drape = {"drape", (source_dir() / "data/garments" / (b.garment + ".xvc")).string(),
                                    "--avatar", body.string(), "-o", out.string(), "--time-limit", "6"};
  drape.insert(drape.end(), b.drape.begin(), b.drape.end());
  const auto r = run_vgd(drape);
  ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
  EXPECT_NE(r.err.find("unit " + b.unit + " "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("up " + b.up + " "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("facing " + b.facing + " "), std::string::npos) << r.err;
  // Sewn sleeves first, the progress says while the caps wait (each for its
  // sleeve's underarm seam: two seams, on the first frame of the sewing);
  // sewn all at once, nothing waits.
  const bool ordered = std::find(b.drape.begin(), b.drape.end(), "--sleeves-first") != b.drape.end();
  EXPECT_EQ(r.err.find("(2 seams waiting)") != std::string::npos, ordered) << r.err;
  const json c = read_json(out / "certificate.json");
  EXPECT_EQ(closed_pairs(c), all_pairs(c)) << c["seams"].dump();
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 1e-3);
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0) << c["triangle_intersections_by_pieces"].dump();
  // Each piece ends within 12 cm of where it was arranged, on its segment.
  for (const auto& p : c["placement"]) {
    double moved = 0;
    for (const auto& d : p["moved_m"]) moved += d.get<double>() * d.get<double>();
    EXPECT_LT(std::sqrt(moved), 0.12) << p.dump();
  }
  EXPECT_TRUE(c["passed"].get<bool>()) << c["failures"].dump();
  EXPECT_EQ(r.code, 0) << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Poses, CliDrapePosed,
    ::testing::Values(PosedBody{"t_pose_mm_z_up", {"--arm-angle", "90"}, 1000.0, "mm", "z", "+z", "t-shirt"},
                      PosedBody{"t_pose_mm_z_up", {"--arm-angle", "90"}, 1000.0, "mm", "z", "+z", "a-line-skirt"},
                      PosedBody{"arms_forward_in_facing_x", {"--arm-forward", "30"}, 1.0 / 0.0254, "in", "y", "+x", "a-line-skirt"},
                      PosedBody{"arms_forward_in_facing_x", {"--arm-forward", "30"}, 1.0 / 0.0254, "in", "y", "+x", "t-shirt",
                                {"--sleeves-first"}}),
    [](const auto& p) {
      std::string g = p.param.garment;
      for (auto& ch : g)
        if (ch == '-') ch = '_';
      return p.param.name + "_" + g;
    });

// A skirt four sizes too small for its body (size 34 on the size-50
// mannequin) sews and rests with nothing inside the body or through itself,
// but pulled to more than twice its length: the certificate says so, naming
// the piece, and does not pass it.
TEST(CliDrape, ATooSmallSkirtIsNotPassed) {
  const auto dir = scratch_dir("drape-small-skirt");
  ASSERT_EQ(run_vgd({"mannequin", "--size", "50", "-o", (dir / "m50.obj").string(), "-q"}).code, 0);
  const auto out = dir / "drape";
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/a-line-skirt.xvc").string(), "--size", "34",
                          "--avatar", (dir / "m50.obj").string(), "-o", out.string(), "--time-limit", "6"});
  EXPECT_EQ(r.code, 3) << r.err;
  // Said before the drape, with both figures: the skirt's waist and hip (not
  // the bust: a skirt does not cover it).
  EXPECT_NE(r.err.find("too small for the body: size 34 is cut for a waist of 64 cm (women's 34); the body's is 102 cm"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cut for a hip of 88 cm"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("cut for a bust"), std::string::npos) << r.err;
  EXPECT_LT(r.err.find("cut for a waist"), r.err.find("sewing")) << "the warning comes before the run";
  const json c = read_json(out / "certificate.json");
  EXPECT_FALSE(c["passed"].get<bool>());
  bool named = false;
  for (const auto& f : c["failures"])
    named = named || (f["class"] == "over-stretched" && f["detail"].get<std::string>().find("WAISTBAND_34") != std::string::npos);
  EXPECT_TRUE(named) << c["failures"].dump();
}

// A T-shirt two sizes too small (42 on the size-46 mannequin): the fit check
// says so before the run, and the certificate measures where the body shows
// through the stretched cloth between its particles, per piece, and fails
// it as penetration (centimetres through, past the 5 mm limit). (The skirt on
// the mannequin of its size leaves nothing of the body showing:
// CliDrape.ShippedSkirtSewsAndComesToRestOnTheMannequin.)
TEST(CliDrape, ATightTShirtShowsTheBodyThroughItsCloth) {
  const auto dir = scratch_dir("drape-tight-tshirt");
  ASSERT_EQ(run_vgd({"mannequin", "--size", "46", "-o", (dir / "m46.obj").string(), "-q"}).code, 0);
  const auto out = dir / "drape";
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/t-shirt.xvc").string(), "--size", "42", "--avatar",
                          (dir / "m46.obj").string(), "-o", out.string(), "--time-limit", "5"});
  ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
  EXPECT_NE(r.err.find("too small for the body: size 42 is cut for a bust of 96 cm"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("check failed: penetration: the body passes through"), std::string::npos) << r.err;
  const json c = read_json(out / "certificate.json");
  EXPECT_GT(c["body_through_cloth"].get<int>(), 10);
  EXPECT_GT(c["body_through_cloth_max_m"].get<double>(), 0.005);
  EXPECT_GT(c["body_through_cloth_by_piece"]["FRONT_42"].get<int>(), 0) << c["body_through_cloth_by_piece"].dump();
  EXPECT_FALSE(c["passed"].get<bool>());
  bool named = false;
  for (const auto& f : c["failures"])
    named = named || (f["class"] == "penetration" && f["detail"].get<std::string>().find("between their particles") !=
                                                          std::string::npos);
  EXPECT_TRUE(named) << c["failures"].dump();
  EXPECT_TRUE(c["warnings"].empty()) << c["warnings"].dump();
}

// The smallest size: the armpit's corner pair (four pieces meet there) hung
// 2.7 cm open with every other pair sewn, each particle held on its own side
// of the crease, and the drape never came to rest; the seam's last stalled
// pair now merges (docs/drape.md, "The last stitch").
TEST(CliDrape, DraftedTShirtInSize34SewsItsArmpitsAndComesToRest) {
  const auto out = scratch_dir("drape-tshirt-34");
  const auto r = run_vgd({"drape", (source_dir() / "data/garments/t-shirt.xvc").string(), "--size", "34", "-o",
                          out.string(), "--time-limit", "5", "-q"});
  ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
  const json c = read_json(out / "certificate.json");
  EXPECT_EQ(closed_pairs(c), all_pairs(c)) << c["seams"].dump();
  EXPECT_EQ(c["stop"]["reason"], "rest") << c["stop"].dump();
  EXPECT_LE(c["penetration"]["max_m"].get<double>(), 1e-3);
  EXPECT_EQ(c["triangle_intersections"].get<int>(), 0) << c["triangle_intersections_by_pieces"].dump();
}

// --quality: the preset lands in the certificate with its settings; preview
// keeps self-collision and stops at ten times the rest threshold, precise
// halves the step; --no-self-collision is the user's choice, whatever the preset.
TEST(CliDrape, QualityPresetsSetTheStepAndTheRestThreshold) {
  const auto garment = (source_dir() / "data/garments/a-line-skirt.xvc").string();
  struct Case {
    std::vector<std::string> extra;
    std::string quality, step, self_collision, rest;
  };
  for (const auto& k : {Case{{"--quality", "preview"}, "preview", "0.01 s", "on", "5e-08 J per particle"},
                        Case{{"--quality", "preview", "--no-self-collision"}, "preview", "0.01 s", "off", "5e-08 J per particle"},
                        Case{{}, "standard", "0.01 s", "on", "5e-09 J per particle"},
                        Case{{"--quality", "precise"}, "precise", "0.005 s", "on", "5e-09 J per particle"}}) {
    const auto out = scratch_dir("drape-quality-" + k.quality + k.self_collision);
    std::vector<std::string> args{"drape", garment, "--time-limit", "0.02", "-q", "-o", out.string()};
    args.insert(args.end(), k.extra.begin(), k.extra.end());
    const auto r = run_vgd(args);
    ASSERT_TRUE(r.code == 0 || r.code == 3) << r.err;
    const json c = read_json(out / "certificate.json");
    EXPECT_EQ(c["settings"]["quality"], k.quality);
    EXPECT_EQ(c["settings"]["step"], k.step) << k.quality;
    EXPECT_EQ(c["settings"]["self_collision"], k.self_collision) << k.quality;
    EXPECT_EQ(c["settings"]["rest_energy"], k.rest) << k.quality;
  }
  EXPECT_EQ(run_vgd({"drape", garment, "--quality", "ultra", "-q"}).code, 2);  // a usage error
}

}  // namespace
}  // namespace vgd::test
