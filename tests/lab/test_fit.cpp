// vgd lab fit: measurements synthesised from known parameters with the lab's
// own forward formulas are fitted back; malformed files are refused with the
// file, the line and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/lab/lab.hpp"
#include "vgd/lab/fit.hpp"

using namespace vgd;
namespace lab = vgd::lab;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// One scratch folder per test: ctest runs the tests as parallel processes,
// and scratch_dir empties the folder it makes (a folder shared by the file's
// tests lost one test's CSV to another's start).
std::filesystem::path scratch() {
  static std::string made_for;
  const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const auto dir = test::binary_dir() / "test-scratch" / ("lab_fit-" + name);
  if (made_for != name) {
    made_for = name;
    return test::scratch_dir("lab_fit-" + name);
  }
  return dir;
}

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto file = scratch() / name;
  std::ofstream(file) << text;
  return file;
}

std::string row(const std::string& quantity, const std::string& direction, const std::string& x, double value,
                const std::string& unit) {
  char b[64];
  std::snprintf(b, sizeof b, "%.12g", value);
  return quantity + "," + direction + "," + x + "," + b + "," + unit + "\n";
}

// A denim-like fabric, every value different from the fit's start (the shirting).
sim::OrthotropicMaterial known() {
  sim::OrthotropicMaterial o;
  o.E_warp = 9807, o.E_weft = 4904, o.G = 123, o.nu_warp_weft = 0.2;
  o.B_warp = 1.766e-4, o.B_weft = 9.042e-5, o.D_twist = 2.0e-5;
  o.density = 0.42, o.thickness = 0.0008;
  return o;
}

// Measurements of `o` by the lab's references: sim::off_axis_modulus (tensile),
// sim::bending_rigidity (KES-FB2), B_strip (cantilever bending length, c =
// (B / w)^(1/3)) and lab::simple_shear_modulus (KES-FB1 shear).
std::string synthesised(const sim::OrthotropicMaterial& o) {
  std::string csv = "# synthesised from known parameters\nquantity,direction,x,value,unit\n";
  csv += row("weight", "", "", o.density * 1000, "g/m2");
  csv += row("thickness", "", "", o.thickness * 1000, "mm");
  csv += row("tensile", "warp", "0", 0, "N/m");
  for (double e : {0.005, 0.01, 0.02}) {
    csv += row("tensile", "warp", std::to_string(e), sim::off_axis_modulus(o, 0) * e, "N/m");
    csv += row("tensile", "weft", std::to_string(e), sim::off_axis_modulus(o, 90 * kDeg) * e, "N/m");
  }
  for (double a : {15.0, 45.0, 75.0})
    csv += row("tensile_modulus", a == 45.0 ? "bias" : std::to_string(a), "", sim::off_axis_modulus(o, a * kDeg), "N/m");
  csv += row("shear_rigidity", "", "", lab::simple_shear_modulus(o, 0.0), "N/m");
  csv += row("bending_rigidity", "warp", "", sim::bending_rigidity(o, 0), "N.m");
  csv += row("bending_rigidity", "weft", "", sim::bending_rigidity(o, 90 * kDeg), "N.m");
  csv += row("bending_rigidity", "45", "", sim::bending_rigidity(o, 45 * kDeg), "N.m");
  for (double a : {0.0, 90.0})
    csv += row("bending_length", a == 0 ? "warp" : "weft", "",
               1000 * std::cbrt(sim::bending_rigidity_strip(o, a * kDeg) / (o.density * 9.81)), "mm");
  return csv;
}

void expect_within(double fitted, double truth, double tolerance, const char* what) {
  EXPECT_NEAR(fitted / truth, 1.0, tolerance) << what << ": fitted " << fitted << ", true " << truth;
}

}  // namespace

TEST(LabFit, RosetteParametersAreFittedBackWithin1Percent) {
  const sim::OrthotropicMaterial o = known();
  const auto csv = write("denim.csv", synthesised(o));
  const auto ms = lab::read_measurements(csv);
  ASSERT_EQ(ms.size(), 18u);
  const lab::FitResult f = lab::fit(ms, scene::ClothModel::strain_rosette, "fitted", csv.string());
  EXPECT_EQ(f.fitted.size(), 9u);  // ν and D_twist too: bias tensile, shear and 45° bending determine them
  EXPECT_LT(f.rms_rel_residual, 1e-6);
  for (const auto& r : f.residuals)
    if (r.measurement.value > 0.0) {
      EXPECT_LT(std::abs(r.rel_residual), 1e-6) << lab::describe(r);
    }
  // Through the file: written, read back as the lab reads a material.
  const auto xvc = scratch() / "fitted-denim.xvc";
  lab::write_material_xvc(f, xvc, csv.string());
  const scene::MaterialDef m = lab::lab_material(xvc.string());
  ASSERT_TRUE(m.orthotropic);
  const auto& g = *m.orthotropic;
  expect_within(g.E_warp, o.E_warp, 0.01, "E_warp");
  expect_within(g.E_weft, o.E_weft, 0.01, "E_weft");
  expect_within(g.G, o.G, 0.01, "G");
  expect_within(g.nu_warp_weft, o.nu_warp_weft, 0.01, "nu_warp_weft");
  expect_within(g.B_warp, o.B_warp, 0.01, "B_warp");
  expect_within(g.B_weft, o.B_weft, 0.01, "B_weft");
  expect_within(g.D_twist, o.D_twist, 0.01, "D_twist");
  expect_within(m.density, o.density, 0.01, "density");
  expect_within(m.thickness, o.thickness, 0.01, "thickness");
}

TEST(LabFit, WithoutBiasDataPoissonIsHeldAndTheRestFitted) {
  const sim::OrthotropicMaterial o = known();
  std::string csv = "quantity,direction,x,value,unit\n";
  csv += row("weight", "", "", o.density, "kg/m2");
  csv += row("tensile_modulus", "warp", "", sim::off_axis_modulus(o, 0), "N/m");
  csv += row("tensile_modulus", "weft", "", sim::off_axis_modulus(o, 90 * kDeg), "N/m");
  csv += row("shear_rigidity", "warp", "", o.G, "N/m");
  csv += row("bending_rigidity", "warp", "", o.B_warp, "N.m");
  csv += row("bending_rigidity", "weft", "", o.B_weft, "N.m");
  const auto file = write("no-bias.csv", csv);
  const auto f = lab::fit(lab::read_measurements(file), scene::ClothModel::strain_rosette, "x", file.string());
  EXPECT_EQ(f.fitted.size(), 6u);
  EXPECT_DOUBLE_EQ(f.material.orthotropic->nu_warp_weft, 0.3);
  expect_within(f.material.orthotropic->E_weft, o.E_weft, 1e-6, "E_weft");
  expect_within(f.material.orthotropic->B_warp, o.B_warp, 1e-6, "B_warp");
  EXPECT_NE(f.notes.front().find("nu_warp_weft"), std::string::npos);
}

TEST(LabFit, MassSpringParametersAreFittedBackWithin1Percent) {
  // The shirting's springs; E along a yarn = spring + shear + 4 bend, B = bend x 1e-6 m².
  const double warp = 4560, weft = 2560, shear = 400, bend_warp = 10, bend_weft = 8, density = 0.2;
  std::string csv = "quantity,direction,x,value,unit\n";
  csv += row("weight", "", "", density, "kg/m2");
  csv += row("tensile", "warp", "2%", 0.02 * (warp + shear + 4 * bend_warp), "N/m");
  csv += row("tensile", "weft", "0.02", 0.02 * (weft + shear + 4 * bend_weft), "N/m");
  csv += row("tensile_modulus", "bias", "", 1500, "N/m");  // no closed form for the springs: not used
  csv += row("shear_rigidity", "", "", shear, "N/m");
  csv += row("bending_rigidity", "warp", "", bend_warp * 1e-6, "N.m");
  csv += row("bending_length", "weft", "", std::cbrt(bend_weft * 1e-6 / (density * 9.81)), "m");
  const auto file = write("springs.csv", csv);
  const auto f = lab::fit(lab::read_measurements(file), scene::ClothModel::mass_spring, "springs", file.string());
  ASSERT_TRUE(f.material.mass_spring);
  const auto& s = *f.material.mass_spring;
  expect_within(s.warp, warp, 0.01, "spring.warp");
  expect_within(s.weft, weft, 0.01, "spring.weft");
  expect_within(s.shear, shear, 0.01, "spring.shear");
  expect_within(s.bend_warp, bend_warp, 0.01, "spring.bend_warp");
  expect_within(s.bend_weft, bend_weft, 0.01, "spring.bend_weft");
  EXPECT_TRUE(std::isnan(f.residuals[3].rel_residual));  // the bias line, reported as not used
}

TEST(LabFit, MalformedMeasurementsNameTheFileTheLineAndTheProblem) {
  struct Case {
    std::string text;
    int line;
    std::string problem;
  };
  const std::string header = "quantity,direction,x,value,unit\n";
  const std::vector<Case> cases{
      {"# comment\nquantity,value\n", 2, "the first line must be 'quantity,direction,x,value,unit'"},
      {header + "weight,,,200\n", 2, "expected 5 fields"},
      {header + "\nstiffness,warp,,5000,N/m\n", 3, "unknown quantity 'stiffness'"},
      {header + "tensile_modulus,warp,,lots,N/m\n", 2, "the value 'lots' is not a number"},
      {header + "tensile_modulus,warp,,5000,N\n", 2, "the unit 'N' is N, but tensile_modulus needs N/m"},
      {header + "tensile_modulus,sideways,,5000,N/m\n", 2, "direction 'sideways' is not warp, weft, bias"},
      {header + "tensile,warp,,50,N/m\n", 2, "x must be the engineering strain"},
      {header + "bending_rigidity,warp,,-1e-5,N.m\n", 2, "the value must be > 0"},
      {header + "weight,warp,,200,g/m2\n", 2, "weight has no direction"},
      {header + "shear_rigidity,,,400,furlongs\n", 2, "unknown unit 'furlongs'"},
  };
  int n = 0;
  for (const auto& c : cases) {
    const auto file = write("bad" + std::to_string(++n) + ".csv", c.text);
    try {
      lab::read_measurements(file);
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(file.string() + ":" + std::to_string(c.line) + ":"), std::string::npos) << what;
      EXPECT_NE(what.find(c.problem), std::string::npos) << what;
    }
  }
  // Well-formed but not enough: no weight, so no density.
  const auto file = write("no-weight.csv", header + "tensile_modulus,warp,,5000,N/m\n");
  try {
    lab::fit(lab::read_measurements(file), scene::ClothModel::strain_rosette, "x", file.string());
    ADD_FAILURE() << "fitted without a weight";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("add"), std::string::npos) << e.what();
  }
}
