// `vgd compare` end to end: exit 0 when alike, 3 when SSIM is below the
// threshold, 1 for a missing file, a file that is not a PNG or images of
// different sizes (each named); --json and --diff.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/render/image.hpp"

using namespace vgd;
namespace fs = std::filesystem;

namespace {

struct Files {
  fs::path dir, a, a_copy, changed, small, text;
};

// a.png and its copy, a changed version (a dark square), a smaller image, a text file.
Files make_files(const std::string& name) {
  Files f;
  f.dir = test::scratch_dir(name);
  render::Image a(64, 64, {230, 230, 225, 255});
  for (int y = 10; y < 50; ++y)
    for (int x = 20; x < 40; ++x) a.pixel(x, y)[0] = a.pixel(x, y)[1] = 90;
  render::Image changed = a;
  for (int y = 30; y < 60; ++y)
    for (int x = 30; x < 60; ++x) changed.pixel(x, y)[2] = 20;
  f.a = f.dir / "a.png", f.a_copy = f.dir / "a copy.png", f.changed = f.dir / "changed.png";
  f.small = f.dir / "small.png", f.text = f.dir / "text.png";
  render::write_png(a, f.a);
  render::write_png(a, f.a_copy);
  render::write_png(changed, f.changed);
  render::write_png(render::Image(32, 64), f.small);
  write_file_atomic(f.text, "not an image");
  return f;
}

}  // namespace

TEST(CmdCompare, IdenticalImagesPass) {
  const auto f = make_files("cmd_compare_same");
  const auto r = test::run_vgd({"compare", f.a.string(), f.a_copy.string()});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("SSIM 1.000000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pass"), std::string::npos) << r.out;
}

TEST(CmdCompare, AChangedImageFailsWithExitThreeAndADiff) {
  const auto f = make_files("cmd_compare_changed");
  const auto diff = f.dir / "diff.png";
  const auto r = test::run_vgd({"compare", f.a.string(), f.changed.string(), "--diff", diff.string()});
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
  const auto d = render::read_png(diff);
  EXPECT_EQ(d.pixel(45, 45)[1], 0) << "the changed square is red in the diff";
  EXPECT_GE(d.pixel(45, 45)[0], 160);
  EXPECT_EQ(d.pixel(5, 5)[0], d.pixel(5, 5)[1]) << "unchanged pixels are grey";
  // A threshold low enough lets it pass.
  EXPECT_EQ(test::run_vgd({"compare", f.a.string(), f.changed.string(), "--threshold", "0.2"}).code, 0);
}

TEST(CmdCompare, JsonCarriesTheFigures) {
  const auto f = make_files("cmd_compare_json");
  const auto r = test::run_vgd({"compare", f.a.string(), f.changed.string(), "--json", "--pixel-threshold", "10"});
  EXPECT_EQ(r.code, 3);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j.at("ssim").get<double>(), 0.99);
  EXPECT_LE(j.at("colour_ssim").get<double>(), j.at("ssim").get<double>() + 1e-12);
  EXPECT_FALSE(j.at("passed").get<bool>());
  EXPECT_EQ(j.at("pixel_threshold"), 10);
  EXPECT_EQ(j.at("differing_pixels"), 30 * 30);  // every pixel of the square: blue 225 -> 20
  EXPECT_EQ(j.at("max_abs_difference"), 205);
  EXPECT_EQ(j.at("width"), 64);
}

TEST(CmdCompare, BadInputsExitOneNamingTheFile) {
  const auto f = make_files("cmd_compare_bad");
  const auto missing = test::run_vgd({"compare", f.a.string(), (f.dir / "none.png").string()});
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.err.find("none.png"), std::string::npos) << missing.err;
  const auto text = test::run_vgd({"compare", f.text.string(), f.a.string()});
  EXPECT_EQ(text.code, 1);
  EXPECT_NE(text.err.find("text.png"), std::string::npos) << text.err;
  EXPECT_NE(text.err.find("not a PNG"), std::string::npos) << text.err;
  const auto sizes = test::run_vgd({"compare", f.a.string(), f.small.string()});
  EXPECT_EQ(sizes.code, 1);
  EXPECT_NE(sizes.err.find("small.png"), std::string::npos) << sizes.err;
  EXPECT_NE(sizes.err.find("different sizes"), std::string::npos) << sizes.err;
  EXPECT_EQ(test::run_vgd(std::vector<std::string>{"compare", f.a.string()}).code, 2) << "usage: B missing";
}
