// `vgd lab all` and `vgd lab fit` end to end. Coarse (20 mm) so that every
// test of `all` and its seven single runs take a few seconds together.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"

using namespace vgd;

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The `measured` column of a lab CSV (test,material,model,quantity,x,measured,...);
// the material never holds a comma in these runs.
std::vector<double> measured_column(const std::string& csv) {
  std::vector<double> out;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string f;
    for (int i = 0; i < 6; ++i) std::getline(fields, f, ',');
    out.push_back(std::strtod(f.c_str(), nullptr));
  }
  return out;
}

}  // namespace

TEST(CmdLab, AllWritesAReportWhoseNumbersMatchTheSingleRuns) {
  const auto dir = test::scratch_dir("cmd_lab_all");
  const auto all = test::run_vgd("-q lab all --material shirting --resolution 20 -o " + (dir / "all").string());
  ASSERT_EQ(all.code, 0) << all.err;
  const std::string report = slurp(dir / "all" / "report.md");
  ASSERT_FALSE(report.empty());
  EXPECT_NE(report.find("vgd lab all --material shirting"), std::string::npos);
  EXPECT_NE(report.find("Total wall time"), std::string::npos);
  for (const std::string test : {"tip-cantilever", "tensile", "cantilever", "buckling", "shear", "bending", "drape"}) {
    SCOPED_TRACE(test);
    EXPECT_NE(report.find("\n## " + test + "\n"), std::string::npos);
    EXPECT_NE(report.find("](" + test + ".png)"), std::string::npos);
    EXPECT_NE(all.out.find(test + " "), std::string::npos);  // the summary on stdout
    // The same test alone (the drape at 20 mm too: --resolution is coarser than `all`'s 10 mm default).
    const auto one = test::run_vgd("-q lab " + test + " --material shirting --resolution 20 -o " +
                                   (dir / "one").string());
    ASSERT_EQ(one.code, 0) << one.err;
    const std::string csv = slurp(dir / "all" / (test + ".csv"));
    EXPECT_EQ(csv, slurp(dir / "one" / (test + ".csv")));
    EXPECT_TRUE(std::filesystem::file_size(dir / "all" / (test + ".png")) > 0);
    for (double v : measured_column(csv)) {
      char cell[48];
      std::snprintf(cell, sizeof cell, "| %.7g |", v);
      EXPECT_NE(report.find(cell), std::string::npos) << cell;
    }
  }
  EXPECT_NE(all.out.find("total"), std::string::npos);
}

TEST(CmdLab, AllAndFitNeedTheirArguments) {
  EXPECT_EQ(test::run_vgd("-q lab all --material shirting").code, 2);
  EXPECT_EQ(test::run_vgd("-q lab fit -o /tmp/x.xvc").code, 2);
  EXPECT_EQ(test::run_vgd("-q lab tensile").code, 2);
}

TEST(CmdLab, FitWritesAMaterialTheLabReads) {
  const auto dir = test::scratch_dir("cmd_lab_fit");
  const auto csv = dir / "shirting.csv";
  // The shirting's own values (data/materials/shirting.xvc), no bias data: ν held at 0.3.
  std::ofstream(csv) << "quantity,direction,x,value,unit\n"
                        "weight,,,200,g/m2\n"
                        "thickness,,,0.5,mm\n"
                        "tensile,warp,1%,50,N/m\n"
                        "tensile_modulus,weft,,3000,N/m\n"
                        "shear_rigidity,,,400,N/m\n"
                        "bending_rigidity,warp,,1e-5,N.m\n"
                        "bending_rigidity,weft,,6e-6,N.m\n";
  const auto xvc = dir / "fitted.xvc";
  const auto r = test::run_vgd("-q lab fit " + csv.string() + " -o " + xvc.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("residuals").size(), 7u);
  EXPECT_LT(j.at("rms_rel_residual").get<double>(), 1e-6);
  // The lab runs on it and finds the shirting's moduli.
  const auto t = test::run_vgd("-q lab tensile --material " + xvc.string() + " --angle 0 --resolution 20 --json");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NEAR(nlohmann::json::parse(t.out).at("points")[0].at("expected").get<double>(), 5000.0, 1e-3);

  std::ofstream(dir / "bad.csv") << "quantity,direction,x,value,unit\nweight,,,heavy,g/m2\n";
  const auto bad = test::run_vgd("-q lab fit " + (dir / "bad.csv").string() + " -o " + (dir / "bad.xvc").string());
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find((dir / "bad.csv").string() + ":2: weight: the value 'heavy' is not a number"),
            std::string::npos)
      << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.xvc"));
}

// --json output is JSON and nothing else, also when the drape's implicit
// steps meet an indefinite matrix (CHOLMOD printed its warnings on stdout).
TEST(CmdLab, DrapeJsonIsCleanJson) {
  const auto r = test::run_vgd("-q lab drape --material shirting --resolution 20 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find("CHOLMOD"), std::string::npos);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("test"), "drape");
  EXPECT_GT(j.at("points").at(0).at("measured").get<double>(), 0.0);
}
