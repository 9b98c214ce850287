// `vgd mannequin` and `vgd avatar` end to end.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"

using namespace vgd;

TEST(CmdMannequin, SizeFromTheTable) {
  const auto dir = test::scratch_dir("cmd_mannequin_size");
  const auto out = (dir / "body.obj").string();
  const auto r = test::run_vgd("-q mannequin --size 38 -o " + out + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j.at("watertight").get<bool>());
  EXPECT_GE(j.at("triangles").get<int>(), 5000);
  EXPECT_LE(j.at("triangles").get<int>(), 20000);
  EXPECT_DOUBLE_EQ(j.at("measurements").at("bust_m").get<double>(), 0.88);
  EXPECT_NEAR(j.at("height_m").get<double>(), 1.68, 0.0168);
  ASSERT_TRUE(std::filesystem::exists(out));
  // The file reads back with the same triangle count.
  const auto rep = test::run_vgd("avatar report " + out + " --json");
  ASSERT_EQ(rep.code, 0) << rep.err;
  EXPECT_EQ(nlohmann::json::parse(rep.out).at("triangles"), j.at("triangles"));
}

TEST(CmdMannequin, MeasurementsWithUnits) {
  const auto dir = test::scratch_dir("cmd_mannequin_custom");
  const auto out = (dir / "body.glb").string();
  const auto r = test::run_vgd("-q mannequin --height 168cm --bust 0.92 --waist 74cm --hip 0.99 --triangles 6000 -o " + out + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(j.at("measurements").at("height_m").get<double>(), 1.68);
  EXPECT_DOUBLE_EQ(j.at("measurements").at("waist_m").get<double>(), 0.74);
  EXPECT_NEAR(j.at("triangles").get<int>(), 6000, 1200);
}

TEST(CmdMannequin, ErrorsAndListing) {
  EXPECT_EQ(test::run_vgd("-q mannequin --size 99 -o /tmp/x.obj").code, 1);
  const auto bad = test::run_vgd("-q mannequin --height 168 -o /tmp/x.obj");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("1.68, not 168"), std::string::npos) << bad.err;
  EXPECT_EQ(test::run_vgd("-q mannequin --bust lots -o /tmp/x.obj").code, 2);
  const auto list = test::run_vgd("mannequin --list-sizes");
  EXPECT_EQ(list.code, 0);
  EXPECT_NE(list.out.find("en13402-men"), std::string::npos);
  const auto missing = test::run_vgd("avatar report /nonexistent/body.glb");
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.err.find("no such file"), std::string::npos) << missing.err;
}

TEST(CmdAvatar, ConvertNormalises) {
  const auto dir = test::scratch_dir("cmd_avatar_convert");
  ASSERT_EQ(test::run_vgd("-q mannequin --size 40 --triangles 5000 -o " + (dir / "b.stl").string()).code, 0);
  const auto r = test::run_vgd("-q avatar convert " + (dir / "b.stl").string() + " -o " + (dir / "b.dae").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto a = nlohmann::json::parse(test::run_vgd("avatar report --json " + (dir / "b.stl").string()).out);
  const auto b = nlohmann::json::parse(test::run_vgd("avatar report --json " + (dir / "b.dae").string()).out);
  EXPECT_EQ(a.at("triangles"), b.at("triangles"));
  EXPECT_NEAR(a.at("height_m").get<double>(), b.at("height_m").get<double>(), 1e-6);
}
