// The orthotropic fabric: validation names the field, reciprocity, the
// off-axis modulus and the consistent B_θ against ../shared/reference.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "support/reference_csv.hpp"
#include "support/test_paths.hpp"
#include "vgd/sim/material.hpp"

using namespace vgd::sim;

namespace {

// The first problem that mentions `field`, or "" if none does.
std::string problem_about(const OrthotropicMaterial& m, const std::string& field) {
  for (const auto& p : problems(m))
    if (p.find(field) != std::string::npos) return p;
  return "";
}

double deg(double d) { return d * M_PI / 180.0; }

}  // namespace

// ---- validation ----

TEST(Material, TheReferenceFabricIsValid) {
  const OrthotropicMaterial m;
  EXPECT_TRUE(problems(m).empty()) << problems(m).front();
  EXPECT_NO_THROW(validate(m));
}

TEST(Material, NegativeZeroOrNonFiniteModuliAreRefusedByName) {
  struct Case {
    const char* field;
    void (*set)(OrthotropicMaterial&);
  };
  const Case cases[] = {
      {"E_warp", [](OrthotropicMaterial& m) { m.E_warp = -5000; }},
      {"E_weft", [](OrthotropicMaterial& m) { m.E_weft = 0; }},
      {"G is", [](OrthotropicMaterial& m) { m.G = std::nan(""); }},
      {"B_warp", [](OrthotropicMaterial& m) { m.B_warp = -1e-5; }},
      {"B_weft", [](OrthotropicMaterial& m) { m.B_weft = INFINITY; }},
      {"density", [](OrthotropicMaterial& m) { m.density = 0; }},
      {"thickness", [](OrthotropicMaterial& m) { m.thickness = -0.001; }},
      {"D_twist", [](OrthotropicMaterial& m) { m.D_twist = -1e-6; }},
      {"residual_warp", [](OrthotropicMaterial& m) { m.residual_warp = INFINITY; }},
  };
  for (const auto& c : cases) {
    OrthotropicMaterial m;
    c.set(m);
    EXPECT_NE(problem_about(m, c.field), "") << c.field;
    try {
      validate(m, "of piece 0 'front'");
      ADD_FAILURE() << c.field << " accepted";
    } catch (const SimulationError& e) {
      EXPECT_NE(std::string(e.what()).find("material of piece 0 'front': "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.field), std::string::npos) << e.what();
    }
  }
}

TEST(Material, PoissonRatiosMustKeepTheComplianceDefinite) {
  OrthotropicMaterial m;
  m.nu_warp_weft = 1.3;  // ν_xy² = 1.69 > E_x/E_y = 1.67: 1 − ν_xy ν_yx < 0
  const std::string p = problem_about(m, "nu_warp_weft");
  EXPECT_NE(p.find("not positive definite"), std::string::npos) << p;
  m.nu_warp_weft = 1.29;  // just inside: 1 − 1.29² · 0.6 = 0.0015
  EXPECT_EQ(problem_about(m, "positive definite"), "");
}

TEST(Material, NuWeftWarpIsDerivedByReciprocityOrCheckedAgainstIt) {
  OrthotropicMaterial m;  // E_x 5000, E_y 3000, ν_xy 0.3
  EXPECT_DOUBLE_EQ(nu_weft_warp(m), 0.18);  // orthotropic_constants.csv
  m.nu_weft_warp = 0.18;
  EXPECT_TRUE(problems(m).empty());
  m.nu_weft_warp = 0.1801;  // within 0.1 %
  EXPECT_TRUE(problems(m).empty());
  m.nu_weft_warp = 0.3;  // the paper's other convention
  const std::string p = problem_about(m, "nu_weft_warp");
  EXPECT_NE(p.find("reciprocity"), std::string::npos) << p;
  EXPECT_NE(p.find("0.18"), std::string::npos) << p;
}

TEST(Material, BendingPoissonCouplingMustKeepTheRigidityDefinite) {
  OrthotropicMaterial m;
  m.B_weft = 3e-7;  // < ν_yx² B_x = 3.24e-7
  EXPECT_NE(problem_about(m, "B_weft"), "");
}

TEST(Material, CurvesMustRiseFromTheResidualStrainWithTwoPointsOrMore) {
  OrthotropicMaterial m;
  m.curve_warp = {{0.0}, {0.0}};
  EXPECT_NE(problem_about(m, "curve_warp has 1 point"), "");
  m.curve_warp = {{0.0, 0.01}, {0.0}};
  EXPECT_NE(problem_about(m, "curve_warp has 2 strains but 1 stresses"), "");
  m.curve_warp = {{0.0, 0.02, 0.01}, {0.0, 10.0, 20.0}};
  EXPECT_NE(problem_about(m, "curve_warp strain does not increase"), "");
  m.curve_warp = {};
  m.curve_weft = {{0.0, 0.01, 0.02}, {0.0, 30.0, 25.0}};
  EXPECT_NE(problem_about(m, "curve_weft is not monotone"), "");
  m.curve_weft = {{0.0, 0.01, 0.02}, {0.0, 30.0, 30.0}};  // flat: not elastic
  EXPECT_NE(problem_about(m, "curve_weft is not monotone"), "");
  m.curve_weft = {{0.0, 0.01}, {5.0, 30.0}};  // 5 N/m at zero strain
  EXPECT_NE(problem_about(m, "curve_weft does not pass through (residual_weft, 0)"), "");
  m.residual_weft = -0.002;  // ... which is fine when the fabric's rest strain says so
  m.curve_weft = {{-0.002, 0.01}, {0.0, 30.0}};
  EXPECT_TRUE(problems(m).empty()) << problems(m).front();
}

TEST(Material, EachTriangleGetsItsPiecesMaterial) {
  Model model = make_grid(3, 2, 0.1, 0.1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 0.01);
  model.triangle_piece = {0, 0, 1, 1};
  model.pieces = {"front", "back"};
  EXPECT_EQ(triangle_materials(model, {OrthotropicMaterial{}}), (std::vector<int>{0, 0, 0, 0}));
  EXPECT_EQ(triangle_materials(model, {OrthotropicMaterial{}, OrthotropicMaterial{}}), (std::vector<int>{0, 0, 1, 1}));
  OrthotropicMaterial bad;
  bad.E_weft = -1;
  try {
    triangle_materials(model, {OrthotropicMaterial{}, bad});
    FAIL();
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("piece 1 'back'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("E_weft"), std::string::npos) << e.what();
  }
  model.triangle_piece = {0, 0, 2, 2};
  EXPECT_THROW(triangle_materials(model, {OrthotropicMaterial{}, OrthotropicMaterial{}}), SimulationError);
  EXPECT_THROW(triangle_materials(model, {}), SimulationError);
}

// ---- off-axis modulus (mechanics.md §3) ----

TEST(Material, OffAxisModulusIsEwarpEweftAndRecoversGFromTheBias) {
  const OrthotropicMaterial m;
  EXPECT_NEAR(off_axis_modulus(m, 0.0), 5000.0, 1e-9);
  EXPECT_NEAR(off_axis_modulus(m, M_PI / 2), 3000.0, 1e-9);
  // 1/G = 4/E_45 − 1/E_x − 1/E_y + 2ν_xy/E_x (the paper's printed form is wrong unless E_x = E_y).
  const double E45 = off_axis_modulus(m, M_PI / 4);
  EXPECT_NEAR(1.0 / (4.0 / E45 - 1.0 / 5000 - 1.0 / 3000 + 2 * 0.3 / 5000), 400.0, 1e-9);
  EXPECT_NEAR(E45, 1372.997712, 1e-6);
}

TEST(Material, OffAxisModulusMatchesTheReferenceCsv) {
  const auto csv = vgd::test::reference_csv("orthotropic_E_theta.csv");
  if (csv.empty()) GTEST_SKIP() << "SKIPPED: " << vgd::test::shared_dir() / "reference" << " not found";
  const OrthotropicMaterial m;
  const auto& th = csv.at("theta_deg");
  ASSERT_EQ(th.size(), 7u);
  for (std::size_t k = 0; k < th.size(); ++k)
    EXPECT_NEAR(off_axis_modulus(m, deg(th[k])) / csv.at("E_theta_N_per_m")[k], 1.0, 1e-9) << th[k] << "°";
}

// ---- bending rigidity (mechanics.md §3: the consistent form) ----

TEST(Material, TwistRigidityIsTheSheetShearModulusTimesHSquaredOver12) {
  OrthotropicMaterial m;  // G 400 N/m, h 0.5 mm: G₃D h³/12 = 8e5 Pa · (5e-4 m)³/12
  EXPECT_NEAR(twist_rigidity(m), 8.333333333e-6, 1e-15);
  m.D_twist = 2e-6;
  EXPECT_EQ(twist_rigidity(m), 2e-6);
}

TEST(Material, BendingRigidityMatchesTheConsistentColumnNotThePapers) {
  const auto csv = vgd::test::reference_csv("orthotropic_B_theta.csv");
  if (csv.empty()) GTEST_SKIP() << "SKIPPED: " << vgd::test::shared_dir() / "reference" << " not found";
  const OrthotropicMaterial m;
  const auto& th = csv.at("theta_deg");
  for (std::size_t k = 0; k < th.size(); ++k) {
    const double B = bending_rigidity(m, deg(th[k]));
    EXPECT_NEAR(B / csv.at("B_theta_consistent_D12")[k], 1.0, 1e-9) << th[k] << "°";
    EXPECT_NEAR(bending_rigidity_strip(m, deg(th[k])) / csv.at("B_theta_strip")[k], 1.0, 1e-9) << th[k] << "°";
    // The paper's Poisson term (2ν_xy B_x) and the literal sheet G differ off the yarns.
    if (th[k] > 0 && th[k] < 90) {
      EXPECT_GT(std::abs(B / csv.at("B_theta_paper_G3D")[k] - 1.0), 0.01) << th[k] << "°";
      EXPECT_GT(std::abs(B / csv.at("B_theta_paper_Gsheet_literal")[k] - 1.0), 0.1) << th[k] << "°";
    }
  }
}

TEST(Material, BendingRigidityClosedFormWithoutFiles) {
  const OrthotropicMaterial m;
  EXPECT_NEAR(bending_rigidity(m, 0.0), 1e-5, 1e-18);
  EXPECT_NEAR(bending_rigidity(m, M_PI / 2), 6e-6, 1e-18);
  // 45°: (B_x + B_y)/4 + (ν_yx B_x + 2 D₆₆)/2 = 4e-6 + (1.8e-6 + 1.6667e-5)/2
  EXPECT_NEAR(bending_rigidity(m, M_PI / 4), 4e-6 + 0.5 * (1.8e-6 + 2 * 8.333333333333e-6), 1e-15);
  // The strip is softer: at 0°, B_x (1 − ν_yx² B_x/B_y) = 9.46e-6.
  EXPECT_NEAR(bending_rigidity_strip(m, 0.0), 9.46e-6, 1e-15);
}
