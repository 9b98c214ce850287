// The virtual fabric lab (docs/fabric-lab.md): its analytic references
// against ../shared/reference, and each test's agreement with mechanics at a
// stated resolution, on the shipped cotton shirting (data/materials/shirting.xvc).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "support/reference_csv.hpp"
#include "support/test_paths.hpp"
#include "vgd/lab/lab.hpp"

using namespace vgd::scene;
using namespace vgd::lab;
namespace lab = vgd::lab;

namespace {

std::string sci(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2e", v);
  return b;
}

// Prints the points (the test log shows the measured table) and records the largest error.
void report(const LabResult& r) {
  std::printf("%s, %s, %s, %d x %d cells, %.2f s\n", r.test.c_str(), r.material.c_str(), r.model.c_str(), r.cells_along,
              r.cells_across, r.wall_s);
  for (const auto& p : r.points)
    std::printf("  %-18s %6g  measured %12.7g  expected %12.7g  %+.2e\n", p.quantity.c_str(), p.x, p.measured,
                p.expected, p.rel_error);
  ::testing::Test::RecordProperty("max_rel_error", sci(r.max_rel_error));
  ::testing::Test::RecordProperty("wall_s", sci(r.wall_s));
}

LabResult run_on_shirting(lab::Test test, ClothModel model, double resolution, double angle = 0.0,
                          bool poisson_free = false) {
  LabSpec spec;
  spec.test = test, spec.model = model, spec.resolution = resolution, spec.angle_deg = angle;
  spec.poisson_free = poisson_free;
  const LabResult r = run(spec, lab_material("shirting"));
  report(r);
  return r;
}

}  // namespace

// ---- the references ----

TEST(LabReference, TipLoadElasticaMatchesTheSharedTable) {
  VGD_REQUIRE_SHARED();
  const auto t = vgd::test::reference_csv("cantilever_tip_load.csv");
  ASSERT_FALSE(t.at("k").empty());
  for (std::size_t i = 0; i < t.at("k").size(); ++i) {
    const Elastica e = tip_load_elastica(t.at("k")[i]);
    EXPECT_NEAR(e.u_over_L, t.at("u_over_L")[i], 1e-8) << "k = " << t.at("k")[i];
    EXPECT_NEAR(e.w_over_L, t.at("w_over_L")[i], 1e-8) << "k = " << t.at("k")[i];
    EXPECT_NEAR(e.tip_angle, t.at("tip_angle_rad")[i], 1e-8) << "k = " << t.at("k")[i];
  }
}

TEST(LabReference, HeavyElasticaMatchesTheSharedTable) {
  VGD_REQUIRE_SHARED();
  const auto t = vgd::test::reference_csv("heavy_elastica.csv");
  ASSERT_FALSE(t.at("g").empty());
  for (std::size_t i = 0; i < t.at("g").size(); ++i) {
    const double g = t.at("g")[i];
    if (g > 50) continue;  // the lab's specimens stay below; the tip is then within 1e-3 rad of vertical
    const Elastica e = heavy_elastica(g);
    EXPECT_NEAR(e.w_over_L, t.at("w_over_L")[i], 1e-8) << "g = " << g;
    EXPECT_NEAR(e.chord_deg(), t.at("chord_angle_deg")[i], 1e-7) << "g = " << g;
    EXPECT_NEAR(1.0 / peirce_bending_length_over_L(e.chord_deg() * M_PI / 180), t.at("L_over_c_peirce_from_chord")[i],
                1e-6) << "g = " << g;
  }
}

TEST(LabReference, EulerBucklingLoadsMatchTheSharedTable) {
  VGD_REQUIRE_SHARED();
  // The buckling test's expected loads for the shirting's B_strip, scaled to
  // B = 1e-5 N·m, against euler_buckling.csv (L = 50 and 100 mm).
  std::ifstream in(vgd::test::shared_dir() / "reference" / "euler_buckling.csv");
  std::map<std::string, double> table;  // "case@L" -> P_cr for B = 1e-5
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string name, b, l, p;
    std::getline(ss, name, ','), std::getline(ss, b, ','), std::getline(ss, l, ','), std::getline(ss, p, ',');
    table[name + "@" + std::to_string(std::lround(std::stod(l) * 1000))] = std::stod(p);
  }
  ASSERT_FALSE(table.empty());
  LabSpec spec;
  spec.test = lab::Test::buckling, spec.resolution = 0.01, spec.poisson_free = true;  // B_strip = B_warp = 1e-5
  const LabResult r = run(spec, lab_material("shirting"));
  ASSERT_EQ(r.points.size(), 7u);  // 4 Euler points, then the shear case's 3
  for (const auto& p : r.points) {
    if (p.quantity.find("shear") != std::string::npos) continue;
    const std::string which = p.quantity.find("clamped-free") != std::string::npos ? "clamped_free" : "clamped_clamped";
    const std::string key = which + "@" + std::to_string(std::lround(p.x));
    ASSERT_TRUE(table.count(key)) << key;
    EXPECT_NEAR(p.expected / table[key], 1.0, 1e-9) << key;
  }
}

TEST(LabReference, OffAxisModulusMatchesTheSharedTable) {
  VGD_REQUIRE_SHARED();
  // The lab's tensile reference is sim::off_axis_modulus; the shipped
  // shirting is mechanics.md §3's example fabric, so its lab run reproduces
  // orthotropic_E_theta.csv.
  const auto t = vgd::test::reference_csv("orthotropic_E_theta.csv");
  ASSERT_FALSE(t.at("theta_deg").empty());
  const LabResult r = run_on_shirting(lab::Test::tensile, ClothModel::strain_rosette, 0.005, -1.0);
  ASSERT_EQ(r.points.size(), t.at("theta_deg").size());
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    EXPECT_DOUBLE_EQ(r.points[i].x, t.at("theta_deg")[i]);
    EXPECT_NEAR(r.points[i].expected / t.at("E_theta_N_per_m")[i], 1.0, 1e-9) << r.points[i].x << " deg";
  }
}

// ---- the lab tests ----
//
// Bending tests run twice: with the Poisson coupling off (ν_xy = 0), where the
// strip's and the plate's rigidity coincide and the elastica's single EI is
// unambiguous (the lab's 2 % target), and on the shirting as shipped
// (ν_xy = 0.3), where the strip stiffens from B_strip towards B_plate as it
// curves (docs/fabric-lab.md, "Strip or plate"): there the measured shortfall
// is asserted as it stands.

TEST(Lab, TipCantileverRosetteFollowsTheElasticaWithin2Percent) {
  const LabResult r = run_on_shirting(lab::Test::tip_cantilever, ClothModel::strain_rosette, 0.005, 0.0, true);
  ASSERT_EQ(r.points.size(), 20u);
  EXPECT_LT(r.max_rel_error, 0.02);
}

TEST(Lab, TipCantileverRosetteWithPoissonIsWithin4PercentOfTheStripElastica) {
  const LabResult r = run_on_shirting(lab::Test::tip_cantilever, ClothModel::strain_rosette, 0.005);
  ASSERT_EQ(r.points.size(), 20u);
  EXPECT_LT(r.max_rel_error, 0.04);
}

TEST(Lab, TensileRosetteFollowsTheOffAxisModulusWithin2Percent) {
  const LabResult r = run_on_shirting(lab::Test::tensile, ClothModel::strain_rosette, 0.005, -1.0);
  ASSERT_EQ(r.points.size(), 7u);
  EXPECT_LT(r.max_rel_error, 0.02);
}

TEST(Lab, TensileRosetteReproducesPiecewiseLinearCurvesWithin1Percent) {
  // A stiffening warp curve and a weft curve (their first slopes are E_warp
  // and E_weft), read at their points and half-way between.
  MaterialDef m = lab_material("shirting");
  m.orthotropic->curve_warp = {{0.0, 0.01, 0.03, 0.06}, {0.0, 50.0, 200.0, 700.0}};
  m.orthotropic->curve_weft = {{0.0, 0.02, 0.05}, {0.0, 60.0, 300.0}};
  for (double angle : {0.0, 90.0}) {
    LabSpec spec;
    spec.test = lab::Test::tensile, spec.angle_deg = angle, spec.resolution = 0.01;
    const LabResult r = run(spec, m);
    report(r);
    ASSERT_EQ(r.points.size(), angle == 0.0 ? 7u : 5u);
    EXPECT_LT(r.max_rel_error, 0.01);
  }
}

TEST(Lab, CantileverRosetteFollowsTheHeavyElasticaWithin2Percent) {
  const LabResult r = run_on_shirting(lab::Test::cantilever, ClothModel::strain_rosette, 0.005, 0.0, true);
  EXPECT_LT(r.max_rel_error, 0.02);
}

TEST(Lab, CantileverRosetteWithPoissonIsWithin3PercentOfTheStripHeavyElastica) {
  const LabResult r = run_on_shirting(lab::Test::cantilever, ClothModel::strain_rosette, 0.005);
  EXPECT_LT(r.max_rel_error, 0.03);
}

// The seed 000 mass-spring cloth with the shirting's spring constants: what
// it measures is the result (docs/fabric-lab.md). Its sheet modulus is within
// 10 % of E along the yarns (8.1 % warp, 7.6 % weft, the free edges' extra row
// of springs included) and 34–69 % too stiff off-axis (the mesh path's
// springs at 15°…75°); its strip has no linear bending stiffness (the bending
// springs lie in the sheet), so no static equilibrium is found under a tip
// load or its own weight, and the lab says so (NaN, infinite error).
TEST(Lab, BucklingRosetteFollowsEulerWithin5Percent) {
  // Clamped-free and clamped-clamped, L = 50 and 100 mm, as shipped (ν = 0.3)
  // and with ν = 0. Measured at 5 mm: 1.25 % and 2.69 % (clamped-clamped, 50 mm).
  for (bool poisson_free : {false, true}) {
    const LabResult r = run_on_shirting(lab::Test::buckling, ClothModel::strain_rosette, 0.005, 0.0, poisson_free);
    ASSERT_EQ(r.points.size(), 7u);  // CF, CC at 50 and 100 mm; shear N_xy,cr, half-waves, wavelength
    EXPECT_LT(r.max_rel_error, 0.05);
    // The shirting's bending is orthotropic: the shear case has no reference,
    // but it buckles.
    EXPECT_TRUE(std::isnan(r.points[4].expected));
    EXPECT_GT(r.points[4].measured, 0.0);
  }
}

TEST(Lab, ShearBucklingOfALongClampedPlateIsWithin10PercentOfKs898) {
  // The buckling test's shear case on a fabric made isotropic in bending
  // (B_weft = B_warp, ν = 0, D66 = B/2, so D11 = D22 = D12 + 2 D66 = D):
  // N_xy,cr vs k_s π² D / b², k_s = 8.98 (infinitely long plate, clamped
  // long edges; Timoshenko & Gere §9.7), 200 x 50 mm at 5 mm.
  MaterialDef mat = lab_material("shirting");
  mat.orthotropic->B_weft = mat.orthotropic->B_warp;
  mat.orthotropic->D_twist = 0.5 * mat.orthotropic->B_warp;
  LabSpec spec;
  spec.test = lab::Test::buckling, spec.resolution = 0.005, spec.poisson_free = true;
  const LabResult r = run(spec, mat);
  report(r);
  ASSERT_EQ(r.points.size(), 7u);
  const LabPoint& shear = r.points[4];
  ASSERT_EQ(shear.quantity, "N_xy,cr shear N/m");
  EXPECT_NEAR(shear.expected, 8.98 * M_PI * M_PI * mat.orthotropic->B_warp / (0.05 * 0.05), 1e-9 * shear.expected);
  EXPECT_LT(std::abs(shear.rel_error), 0.10);
  EXPECT_GE(r.points[5].measured, 2.0);  // the buckle is a train of inclined wrinkles
  EXPECT_GT(r.points[6].measured, 0.0);
}

TEST(Lab, MassSpringShortfallIsReported) {
  const LabResult tensile = run_on_shirting(lab::Test::tensile, ClothModel::mass_spring, 0.005, -1.0);
  ASSERT_EQ(tensile.points.size(), 7u);
  EXPECT_LT(std::abs(tensile.points.front().rel_error), 0.10);
  EXPECT_LT(std::abs(tensile.points.back().rel_error), 0.10);
  EXPECT_GT(tensile.max_rel_error, 0.02) << "mass-spring now meets the target: update docs/fabric-lab.md";
  const LabResult tip = run_on_shirting(lab::Test::tip_cantilever, ClothModel::mass_spring, 0.005);
  EXPECT_FALSE(std::isfinite(tip.max_rel_error)) << "mass-spring bending now converges: update docs/fabric-lab.md";
}

// ---- the shipped fabrics ----

TEST(LabMaterials, NineFabricsLoadWithBothModelsAndPassTheTensileTarget) {
  for (const char* name : {"shirting", "denim", "silk-crepe", "wool-suiting", "linen", "polyester", "cotton-jersey",
                           "cotton-rib", "chiffon"}) {
    SCOPED_TRACE(name);
    const MaterialDef m = lab_material(name);
    EXPECT_GT(m.density, 0.0);
    EXPECT_GT(m.thickness, 0.0);
    ASSERT_TRUE(m.mass_spring.has_value());
    EXPECT_EQ(orthotropic_problem(m), "");
    LabSpec spec;
    spec.test = lab::Test::tensile, spec.angle_deg = -1.0, spec.resolution = 0.01;
    const LabResult r = run(spec, m);
    EXPECT_LT(r.max_rel_error, 0.02);
  }
}

// ---- shear, pure bending, drape (KES-FB1, KES-FB2, Cusick) ----

TEST(LabReference, PlateBendingRigidityMatchesTheSharedTable) {
  VGD_REQUIRE_SHARED();
  // The bending test's reference is sim::bending_rigidity (the plate's B_θ
  // with the consistent D₁₂ = ν_yx B_x); the shirting is mechanics.md §3's
  // example fabric (its D₆₆ derived, G h²/12).
  const auto t = vgd::test::reference_csv("orthotropic_B_theta.csv");
  ASSERT_FALSE(t.at("theta_deg").empty());
  const auto o = orthotropic_of(lab_material("shirting"));
  for (std::size_t i = 0; i < t.at("theta_deg").size(); ++i) {
    const double theta = t.at("theta_deg")[i];
    EXPECT_NEAR(vgd::sim::bending_rigidity(o, theta * M_PI / 180) / t.at("B_theta_consistent_D12")[i], 1.0, 1e-9)
        << theta << " deg";
  }
}

TEST(LabReference, DrapeCoefficientMatchesTheSharedExample) {
  VGD_REQUIRE_SHARED();
  // Every row of cusick_drape_example.csv (30/18, 36/18, 24/18 cm, and the
  // worked example: 400 cm² on 30/18 gives DC = 0.3217).
  const auto t = vgd::test::reference_csv("cusick_drape_example.csv");
  ASSERT_FALSE(t.at("DC").empty());
  for (std::size_t i = 0; i < t.at("DC").size(); ++i)
    EXPECT_NEAR(drape_coefficient(t.at("A_shadow_cm2")[i] * 1e-4, t.at("specimen_diameter_cm")[i] / 100,
                                  t.at("disk_diameter_cm")[i] / 100),
                t.at("DC")[i], 1e-9)
        << "row " << i;
  EXPECT_NEAR(drape_coefficient(400e-4, 0.30, 0.18), 0.3216941283, 1e-9);
}

namespace {

LabResult run_on(const char* material, lab::Test test, double resolution, double angle = 0.0, bool poisson_free = false) {
  LabSpec spec;
  spec.test = test, spec.resolution = resolution, spec.angle_deg = angle, spec.poisson_free = poisson_free;
  const LabResult r = run(spec, lab_material(material));
  report(r);
  return r;
}

const LabPoint& point(const LabResult& r, const std::string& quantity, double x) {
  for (const auto& p : r.points)
    if (p.quantity == quantity && p.x == x) return p;
  throw std::runtime_error("no point " + quantity);
}

}  // namespace

// KES-FB1 at 10 mm (5 × 20 cells, coarse to stay fast). The whole clamp reads
// G short by the free ends' share (2.3 % on the shirting here, 3.6 % at
// 2.5 mm, less on stiffer-to-shear-ratio fabrics); its middle half reads the
// uniform simple shear, within 0.5 %.
TEST(Lab, ShearRosetteMeasuresTheShearRigidityWithin5Percent) {
  for (const char* name : {"shirting", "denim", "chiffon"}) {
    SCOPED_TRACE(name);
    const LabResult r = run_on(name, lab::Test::shear, 0.01);
    ASSERT_EQ(r.points.size(), 11u);
    EXPECT_LT(r.max_rel_error, 0.05);
    EXPECT_DOUBLE_EQ(point(r, "G N/m", 0.0).expected, lab_material(name).orthotropic->G);
    EXPECT_LT(std::abs(point(r, "G N/m", 0.0).rel_error), 0.05);
    EXPECT_LT(std::abs(point(r, "G middle N/m", 0.0).rel_error), 0.01);
  }
}

// KES-FB2 at 10 mm (16 × 5 cells): B warp and weft within 5 % of the plate's
// B_x and B_y (measured −1.9 %, the free sides' anticlastic curl); with ν = 0
// the plate and the strip agree and the error is the 16 cells' (−0.8 %).
TEST(Lab, PureBendingRosetteMeasuresTheBendingRigidityWithin5Percent) {
  const LabResult r = run_on("shirting", lab::Test::bending, 0.01, -1.0);
  ASSERT_EQ(r.points.size(), 22u);
  EXPECT_DOUBLE_EQ(point(r, "B N.m", 0.0).expected, 1e-5);
  EXPECT_DOUBLE_EQ(point(r, "B N.m", 90.0).expected, 6e-6);
  EXPECT_LT(std::abs(point(r, "B N.m", 0.0).rel_error), 0.05);
  EXPECT_LT(std::abs(point(r, "B N.m", 90.0).rel_error), 0.05);
  EXPECT_LT(r.max_rel_error, 0.05);
  const LabResult free = run_on("shirting", lab::Test::bending, 0.01, -1.0, true);
  EXPECT_LT(free.max_rel_error, 0.01);
}

// Cusick drape at 20 mm (4 rings × 48 segments; about 1 s a fabric): too
// coarse to resolve a limp fabric's folds (its DC comes out high: docs/fabric-lab.md
// has the 5 mm figures), fine enough for the order. Mechanics gives no DC to
// compare with: the denim (B_warp 1.8e-4 N·m) must stand out further than the
// silk crepe (1.9e-6 N·m), each DC inside (0, 1), each hem in 3–12 nodes.
TEST(Lab, DrapeOrdersDenimAboveSilkCrepeWithThreeToTwelveNodes) {
  const LabResult denim = run_on("denim", lab::Test::drape, 0.02);
  const LabResult silk = run_on("silk-crepe", lab::Test::drape, 0.02);
  for (const LabResult* r : {&denim, &silk}) {
    ASSERT_EQ(r->points.size(), 3u);
    const double dc = point(*r, "DC", 30.0).measured, nodes = point(*r, "nodes", 30.0).measured;
    EXPECT_GT(dc, 0.0);
    EXPECT_LT(dc, 1.0);
    EXPECT_GE(nodes, 3.0);
    EXPECT_LE(nodes, 12.0);
    EXPECT_TRUE(std::isnan(r->max_rel_error));  // no reference
    EXPECT_EQ(r->top_view_size * r->top_view_size, static_cast<int>(r->top_view.size()));
  }
  EXPECT_GT(point(denim, "DC", 30.0).measured, point(silk, "DC", 30.0).measured + 0.1);
  EXPECT_GT(point(denim, "DC", 30.0).measured, 0.7);  // the stiff class's range, mechanics.md §6
}

TEST(LabAll, RunsEveryTestWithTheDrapeAtItsOwnResolution) {
  const auto specs = lab::all_specs(ClothModel::strain_rosette, 0.005, 0.01, false);
  ASSERT_EQ(specs.size(), 7u);
  for (const auto& s : specs) EXPECT_DOUBLE_EQ(s.resolution, s.test == lab::Test::drape ? 0.01 : 0.005);
  EXPECT_LT(specs[1].angle_deg, 0.0);  // tensile at every angle
  // The mass-spring strip cannot buckle (no stiffness across the sheet): left out.
  for (const auto& s : lab::all_specs(ClothModel::mass_spring, 0.005, 0.01, false))
    EXPECT_NE(s.test, lab::Test::buckling);
  EXPECT_EQ(lab::all_specs(ClothModel::mass_spring, 0.005, 0.01, false).size(), 6u);
}
