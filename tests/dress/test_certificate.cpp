// The certificate's verdict: every check that fails is named with its class
// from the fixed list and the figures behind it, and a drape with any of
// them is not passed.
#include <gtest/gtest.h>

#include <string>

#include "vgd/core/diagnostics.hpp"
#include "vgd/dress/certificate.hpp"
#include "vgd/scene/build.hpp"
#include "vgd/scene/json.hpp"
#include "vgd/sim/system.hpp"

namespace vgd::dress {
namespace {

// A drape that passes: at rest, every seam closed, nothing inside the body or
// through itself, strain and placement within their limits.
Certificate good() {
  Certificate c;
  c.stop_reason = "rest";
  c.simulated_s = 2.0;
  c.seams.push_back({"left side seam", 30, 30, 0.0, 0.0, Vec3::Zero()});
  c.triangle_intersections = 0;
  c.max_penetration = 0.0002;
  PieceStrain s;
  s.piece = "FRONT_38";
  s.warp.p95 = 0.04, s.weft.p95 = 0.05;
  c.strain.push_back(s);
  c.placement.push_back({"FRONT_38", "torso", Vec3(0, -0.02, 0.01)});
  return c;
}

std::string classes(const Certificate& c) {
  std::string out;
  for (const auto& f : c.failures()) out += f.kind + "|";
  return out;
}

TEST(Certificate, AGoodDrapePasses) {
  EXPECT_TRUE(good().passed());
  EXPECT_EQ(classes(good()), "");
}

TEST(Certificate, EachFailureIsNamedWithItsFigures) {
  Certificate c = good();
  c.strain.front().weft.p95 = 2.4;  // 240 %: pulled, not draped
  auto f = c.failures();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].kind, "over-stretched");
  EXPECT_NE(f[0].detail.find("FRONT_38"), std::string::npos) << f[0].detail;
  EXPECT_NE(f[0].detail.find("240 %"), std::string::npos) << f[0].detail;
  EXPECT_FALSE(c.passed());

  c = good();
  c.placement.front().moved = Vec3(0, 0.25, 0);  // a skirt ridden up to the armpits
  f = c.failures();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].kind, "displaced");
  EXPECT_NE(f[0].detail.find("25.0 cm up"), std::string::npos) << f[0].detail;

  c = good();
  c.stop_reason = "time limit";
  c.seams.front().closed = 12;
  c.max_penetration = 0.004;
  c.triangle_intersections = 7;
  c.crossings_by_pieces["BACK_38 / FRONT_38"] = 7;
  EXPECT_EQ(classes(c), "no rest|seams open|penetration|self-intersection|");
  EXPECT_NE(c.failures()[1].detail.find("left side seam: 12/30"), std::string::npos) << c.failures()[1].detail;
  EXPECT_EQ(c.failures()[1].detail.find("the body between"), std::string::npos) << c.failures()[1].detail;
  c.seams.front().body_between = true;  // a foot between an outseam's two sides at the hem
  EXPECT_NE(c.failures()[1].detail.find(", the body between its two sides there"), std::string::npos)
      << c.failures()[1].detail;

  c = good();
  c.open_sides.push_back({"left", 1.06, 0.92, 51.0});  // front and back hanging apart
  c.open_sides.push_back({"right", 0, 0, 8.0});        // sewn: the mesh's spacing
  f = c.failures();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].kind, "open side");
  EXPECT_NE(f[0].detail.find("left side from 1.06 m down to 0.92 m high: up to 51°"), std::string::npos) << f[0].detail;

  c = good();
  c.stop_reason = "error";
  c.stop_message = "the step diverged";
  EXPECT_EQ(classes(c), "error|");
}

// The body showing through between particles is measured and named, per
// piece, as a warning: it does not fail the drape.
// The body through the cloth between its particles: a warning up to the
// limit (5 mm; flat triangles over a curved body stand off it by a mm or
// two), a penetration failure beyond it, named with its figures and pieces.
TEST(Certificate, TheBodyThroughTheClothWarnsUpToItsLimitAndFailsBeyond) {
  Certificate c = good();
  c.body_through_cloth = 0;
  EXPECT_TRUE(c.warnings().empty());
  c.body_through_cloth = 12;
  c.max_body_through = 0.0041;
  c.body_through_by_piece["FRONT_38"] = 9;
  c.body_through_by_piece["LEFT_SLEEVE_38"] = 3;
  const auto w = c.warnings();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, "body through cloth");
  EXPECT_NE(w[0].detail.find("12 cloth triangles, up to 4.10 mm"), std::string::npos) << w[0].detail;
  EXPECT_NE(w[0].detail.find("FRONT_38 9, LEFT_SLEEVE_38 3"), std::string::npos) << w[0].detail;
  EXPECT_TRUE(c.passed());
  c.max_body_through = c.body_through_limit;  // inclusive
  EXPECT_TRUE(c.passed());
  c.max_body_through = 0.0061;
  EXPECT_TRUE(c.warnings().empty());
  EXPECT_EQ(classes(c), "penetration|");
  const auto f = c.failures();
  EXPECT_NE(f[0].detail.find("12 cloth triangles, up to 6.10 mm inside it between their particles (FRONT_38 9, "
                             "LEFT_SLEEVE_38 3) (limit 5.0 mm)"),
            std::string::npos)
      << f[0].detail;
}

// The limits are the certificate's own: just within passes, just beyond fails.
TEST(Certificate, LimitsAreInclusive) {
  Certificate c = good();
  c.strain.front().warp.p95 = c.strain_limit;
  c.placement.front().moved = Vec3(0, c.displacement_limit, 0);
  c.max_penetration = c.penetration_limit;
  EXPECT_TRUE(c.passed()) << classes(c);
  c.strain.front().warp.p95 = c.strain_limit * 1.01;
  EXPECT_EQ(classes(c), "over-stretched|");
}

// A fabric that states where its yarns lock (MATERIAL strain_limit) is held
// to it instead of the certificate's own bound: a woven locked at 10 % with
// a sleeve at 45 % weft p95 is over-stretched, the same sleeve in a fabric
// that states none is not; the fabric's limit is said and read back.
TEST(Certificate, AFabricsOwnStrainLimitIsTheBoundForItsPieces) {
  Certificate c = good();
  PieceStrain sleeve;
  sleeve.piece = "LEFT_SLEEVE_38";
  sleeve.fabric = "locked woven";
  sleeve.weft.p95 = 0.45;
  c.strain.push_back(sleeve);
  EXPECT_TRUE(c.passed()) << classes(c);
  c.strain.back().fabric_limit = 0.10;
  auto f = c.failures();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].kind, "over-stretched");
  EXPECT_EQ(f[0].detail, "LEFT_SLEEVE_38: weft strain p95 45 % (limit 10 %, the fabric's strain_limit)");
  c.strain.back().weft.p95 = 0.10;  // inclusive, as the certificate's own
  EXPECT_TRUE(c.passed()) << classes(c);
  c.strain.back().weft.p95 = 0.45;
  const std::string text = to_json(c);
  EXPECT_NE(text.find("\"fabric_strain_limit\": 0.1"), std::string::npos);
  const Certificate back = certificate_from_json(text, "certificate.json");
  EXPECT_EQ(back.strain.back().fabric_limit, 0.10);
  EXPECT_EQ(back.strain.front().fabric_limit, 0.0);
  EXPECT_EQ(classes(back), "over-stretched|");
  EXPECT_EQ(to_json(back), text);
}

// certificate.json read back (the studio reads the server's): every field
// to_json writes comes back, so writing the read certificate gives the same
// text, and its verdict is the same.
TEST(Certificate, ItsJsonReadsBackToTheSameCertificate) {
  Certificate c = good();
  c.version = "1.2.3";
  c.inputs = {{"garment", "skirt.xvc"}, {"size", "38"}};
  c.settings = {{"quality", "standard"}, {"spacing", "0.015 m"}};
  c.stop_message = "kinetic energy below 1e-6 J per particle";
  c.wall_s = 3.25, c.frames = 51, c.frames_on_fewer_threads = 2;
  c.stages = {{"placing", 0.5, 0.0}, {"sewing", 1.5, 0.6}, {"settling", 1.25, 1.4}};
  c.effect_seconds = {{"gravity", 0.01}, {"springs", 0.75}};
  c.steps = 200, c.force_evaluations = 410, c.linear_iterations = 9000;
  c.self_detections = 20, c.self_pairs = 3000, c.self_reverted = 4, c.self_untangled = 1;
  c.contact_detections = 850, c.contact_cut = 17000, c.contact_unfinished = 13, c.contact_merges_held = 6;
  c.particles = 1234, c.triangles = 2222;
  c.particles_inside = 1, c.deepest_at = Vec3(0.1, 1.2, -0.05);
  c.body_through_cloth = 3, c.max_body_through = 0.002, c.body_through_by_piece = {{"FRONT_38", 3}};
  c.body_through_opening = 0;
  c.crossings_by_pieces = {};
  c.seams.push_back({"right side seam", 30, 12, 0.04, 0.01, Vec3(-0.2, 1.0, 0.0), true});
  c.open_sides.push_back({"right", 1.1, 0.9, 41.5});
  c.contact = {120, 0.05, 3.5, {0.1, 1, 2, 3, 4}};
  c.times = {0.0, 0.04, 0.08}, c.kinetic_energy = {1e-3, 5e-4, 1e-7};
  c.strain.back().shear_deg = {-3, -1, 0.5, 2, 4};
  c.placement.push_back({"BACK_38", "left-leg", Vec3(0, -0.05, 0), 0.078});
  const std::string text = to_json(c);
  const Certificate back = certificate_from_json(text, "certificate.json");
  EXPECT_EQ(to_json(back), text);
  EXPECT_EQ(classes(back), classes(c));
  EXPECT_EQ(classes(back), "seams open|open side|");
  EXPECT_EQ(back.seam_totals().closed, 42);
  EXPECT_EQ(back.seams[1].widest_at.x(), -0.2);
  EXPECT_TRUE(back.seams[1].body_between);
  EXPECT_FALSE(back.seams[0].body_between);
  EXPECT_EQ(back.placement.back().raised, 0.078);
  EXPECT_EQ(back.placement.front().raised, 0.0);
}

// A drape stopped at the time limit says where its cloth still moves: the
// particle that moved furthest over the last second, where, beside which
// body segments, and the pieces moving half as far; read back the same.
TEST(Certificate, ANoRestSaysWhereTheClothStillMoves) {
  Certificate c = good();
  c.stop_reason = "time limit";
  c.simulated_s = 8.0;
  EXPECT_EQ(c.failures().front().detail, "stopped at the time limit, 8.00 s simulated");
  c.still_moving = StillMoving{1.0, 0.4213, Vec3(0.214, 1.33, -0.018), {{"SL1_58", 6}, {"FR_58", 3}}, {"torso", "left-arm"}};
  const auto f = c.failures();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].kind, "no rest");
  EXPECT_EQ(f[0].detail,
            "stopped at the time limit, 8.00 s simulated; still moving: a particle 42.1 cm over the last 1.00 s, at "
            "(0.214, 1.330, -0.018) m between the torso and the left-arm (particles moving half as far or more: "
            "SL1_58 6, FR_58 3)");
  const std::string text = to_json(c);
  const Certificate back = certificate_from_json(text, "certificate.json");
  ASSERT_TRUE(back.still_moving.has_value());
  EXPECT_EQ(back.still_moving->pieces, c.still_moving->pieces) << "most first";
  EXPECT_EQ(back.failures().front().detail, f[0].detail);
  EXPECT_EQ(to_json(back), text);
  c.still_moving->near = {"left-arm"};
  EXPECT_NE(c.failures().front().detail.find("m by the left-arm ("), std::string::npos) << c.failures().front().detail;
}

// The body through the cloth says where its deepest point is and beside
// which body segments, read back the same.
TEST(Certificate, TheBodyThroughTheClothSaysWhereItIsDeepest) {
  Certificate c = good();
  c.body_through_cloth = 17, c.max_body_through = 0.0053, c.body_through_opening = 0;
  c.body_through_by_piece = {{"SL1_54", 12}, {"FR_54", 5}};
  c.body_through_at = Vec3(0.2, 1.324, -0.004);
  c.body_through_near = {"left-arm", "torso"};
  const auto f = c.failures();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].detail,
            "the body passes through 17 cloth triangles, up to 5.30 mm inside it between their particles (FR_54 5, "
            "SL1_54 12), the deepest at (0.200, 1.324, -0.004) m between the left-arm and the torso (limit 5.0 mm)");
  const std::string text = to_json(c);
  const Certificate back = certificate_from_json(text, "certificate.json");
  ASSERT_TRUE(back.body_through_at.has_value());
  EXPECT_EQ(back.body_through_near, c.body_through_near);
  EXPECT_EQ(back.failures().front().detail, f[0].detail);
  EXPECT_EQ(to_json(back), text);
}

// What holding the touching cloth may mend: a drape that failed only in the
// crease between an arm and the torso (still moving there, or the body
// through the cloth there between particles that are all outside it), not
// one that failed anywhere else or for anything else as well.
TEST(Certificate, AFailureCaughtOnlyAtAnArmpitIsToldFromOthers) {
  EXPECT_FALSE(caught_at_armpit(good()).has_value()) << "passed";
  Certificate moving = good();
  moving.stop_reason = "time limit", moving.simulated_s = 8.0;
  moving.still_moving = StillMoving{1.0, 0.17, Vec3(0.21, 1.332, 0.008), {{"FR_58", 17}}, {"torso", "left-arm"}};
  ASSERT_TRUE(caught_at_armpit(moving).has_value());
  EXPECT_EQ(*caught_at_armpit(moving), "the torso and the left-arm, at (0.210, 1.332, 0.008) m");
  Certificate by_the_hips = moving;
  by_the_hips.still_moving->near = {"torso"};
  EXPECT_FALSE(caught_at_armpit(by_the_hips).has_value()) << "the torso alone: a hem swaying";
  by_the_hips.still_moving->near = {"left-leg", "right-leg"};
  EXPECT_FALSE(caught_at_armpit(by_the_hips).has_value()) << "a crotch";
  Certificate and_open = moving;
  and_open.seams.push_back({"left armhole", 37, 30, 0.02, 0.005, Vec3::Zero()});
  EXPECT_FALSE(caught_at_armpit(and_open).has_value()) << "a seam open as well";

  Certificate through = good();
  through.body_through_cloth = 17, through.max_body_through = 0.0053, through.body_through_opening = 0;
  through.body_through_at = Vec3(-0.214, 1.34, 0.002);
  through.body_through_near = {"right-arm", "torso"};
  ASSERT_EQ(classes(through), "penetration|");
  EXPECT_EQ(*caught_at_armpit(through), "the right-arm and the torso, at (-0.214, 1.340, 0.002) m");
  Certificate both = through;  // no rest at one armpit, the body through at the other
  both.stop_reason = "time limit", both.still_moving = moving.still_moving;
  EXPECT_EQ(*caught_at_armpit(both), "the torso and the left-arm, at (0.210, 1.332, 0.008) m");
  Certificate opening = through;
  opening.body_through_opening = 4;
  EXPECT_FALSE(caught_at_armpit(opening).has_value()) << "a hole the body shows through";
  Certificate inside = through;
  inside.max_penetration = 0.003;
  EXPECT_FALSE(caught_at_armpit(inside).has_value()) << "particles inside the body";
  Certificate crossing = through;
  crossing.triangle_intersections = 3;
  EXPECT_FALSE(caught_at_armpit(crossing).has_value()) << "the cloth through itself as well";
}

TEST(Certificate, JsonThatIsNotACertificateIsRefusedNamingTheField) {
  const auto error_of = [](const std::string& text) {
    try {
      certificate_from_json(text, "job/certificate.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  EXPECT_NE(error_of("{not json").find("job/certificate.json"), std::string::npos);
  EXPECT_NE(error_of("{not json").find("not JSON"), std::string::npos);
  EXPECT_NE(error_of("[]").find("expected an object"), std::string::npos);
  std::string text = to_json(good());
  EXPECT_EQ(error_of(text), "read");
  const auto at = text.find("\"reason\"");
  ASSERT_NE(at, std::string::npos);
  const std::string renamed = text.substr(0, at) + "\"cause\"" + text.substr(at + 8);
  EXPECT_NE(error_of(renamed).find("stop.reason"), std::string::npos) << error_of(renamed);
  EXPECT_NE(error_of(renamed).find("missing"), std::string::npos);
  const auto frames = text.find("\"frames\": ");
  ASSERT_NE(frames, std::string::npos);
  const std::string wrong = text.substr(0, frames) + "\"frames\": \"many\"," + text.substr(text.find('\n', frames) + 1);
  EXPECT_NE(error_of(wrong).find("stop.frames"), std::string::npos) << error_of(wrong);
}

// Contact pressure against its analytic value: a sheet lying flat 2 mm above
// a cylinder's flat top, in its rest shape, carries nothing but its weight,
// so every particle presses ρ g on the body (areal density 0.1 kg/m²:
// 0.981 Pa), a corner with a quarter of an inner particle's cloth as much as
// the inner one, and the body carries the sheet's weight. Particles beyond
// the contact distance press nothing. The piece above is cut from a fabric
// that states its strain limit, and its strain says so.
TEST(Certificate, ASheetLyingFlatPressesItsWeightPerAreaEverywhere) {
  const std::string scene_json = R"({
    "version": 1, "name": "lying",
    "materials": { "cloth": { "density": 0.1, "spring.warp": 100, "spring.weft": 100, "spring.shear": 20,
                              "spring.bend_warp": 5, "spring.bend_weft": 5, "spring.damping": 0.01 },
                   "locked": { "density": 0.1, "spring.warp": 100, "spring.weft": 100, "spring.shear": 20,
                               "spring.bend_warp": 5, "spring.bend_weft": 5, "spring.damping": 0.01,
                               "strain_limit": 0.05 } },
    "cloth": [ { "name": "sheet", "grid": { "particles": [7, 5], "size": [0.3, 0.2] },
                 "placement": { "origin": [-0.15, 0.802, -0.1], "u": [1, 0, 0], "v": [0, 0, 1] },
                 "model": "mass-spring", "material": "cloth" },
               { "name": "above", "grid": { "particles": [3, 3], "size": [0.1, 0.1] },
                 "placement": { "origin": [-0.05, 0.9, -0.05], "u": [1, 0, 0], "v": [0, 0, 1] },
                 "model": "mass-spring", "material": "locked" } ],
    "avatar": { "cylinder": { "base": [0, 0, 0], "radius": 0.4, "height": 0.8 } },
    "effects": { "gravity": {}, "collision": {} },
    "integrator": { "method": "euler", "step": 0.001 },
    "frames": { "fps": 25, "duration": 0.04 }
  })";
  const scene::Scene s = scene::build(scene::parse_scene(scene_json, "lying.json"));
  const auto& m = s.system->model();
  Certificate c;
  measure_state(s, m.x0, 0.002, 0.004, false, c);
  const int sheet = 7 * 5;
  ASSERT_EQ(c.contact.particle_pressure.size(), static_cast<std::size_t>(m.num_particles()));
  EXPECT_EQ(c.contact.particles, sheet);
  const double rho_g = 0.1 * 9.81;
  for (int i = 0; i < sheet; ++i) EXPECT_NEAR(c.contact.particle_pressure[i], rho_g, 1e-9 * rho_g) << i;
  for (int i = sheet; i < m.num_particles(); ++i) EXPECT_EQ(c.contact.particle_pressure[i], 0.0) << i;
  EXPECT_NEAR(c.contact.force, 0.3 * 0.2 * rho_g, 1e-9);
  EXPECT_NEAR(c.contact.area, 0.3 * 0.2, 1e-12);
  EXPECT_NEAR(c.contact.pressure.p50, rho_g, 1e-9);
  // Each piece's strain carries its fabric's own limit, where it states one.
  ASSERT_EQ(c.strain.size(), 2u);
  EXPECT_EQ(c.strain[0].fabric_limit, 0.0);
  EXPECT_EQ(c.strain[1].fabric_limit, 0.05);
}

}  // namespace
}  // namespace vgd::dress
