// Work-precision diagrams: one curve per method in its colour, points below
// the reference's floor drawn hollow, the file a PNG of the stated size.
#include <gtest/gtest.h>

#include <cstdint>

#include "support/test_paths.hpp"
#include "vgd/render/image.hpp"
#include "vgd/study/plot.hpp"

namespace vgd::study {
namespace {

int count_colour(const render::Image& img, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const auto* p = img.pixel(x, y);
      n += p[0] == r && p[1] == g && p[2] == b;
    }
  return n;
}

TEST(StudyPlot, EachMethodIsDrawnInItsColour) {
  const auto file = test::scratch_dir("study-plot") / "wp.png";
  plot_work_precision("test", {{"rk4", 0.01, 0.1, 1.0}, {"rk4", 0.005, 0.2, 0.5}, {"midpoint", 0.01, 0.05, 3.0}}, file);
  const render::Image img = render::read_png(file);
  EXPECT_EQ(img.width, 900);
  EXPECT_EQ(img.height, 620);
  EXPECT_GT(count_colour(img, 0, 114, 178), 50);   // rk4: a segment and two squares
  EXPECT_GT(count_colour(img, 0, 158, 115), 20);   // midpoint: a square and its legend line
  EXPECT_EQ(count_colour(img, 213, 94, 0), 0);     // symplectic Euler: not in the data
}

// A hollow (unresolved) point keeps a white centre inside its square.
TEST(StudyPlot, UnresolvedPointsAreHollow) {
  const auto dir = test::scratch_dir("study-plot-hollow");
  // One point alone sits at the plot's lower-left decade corner: (90, 550).
  plot_work_precision("solid", {{"rk4", 0.01, 1.0, 1.0, false}}, dir / "solid.png");
  plot_work_precision("hollow", {{"rk4", 0.01, 1.0, 1.0, true}}, dir / "hollow.png");
  const render::Image solid = render::read_png(dir / "solid.png"), hollow = render::read_png(dir / "hollow.png");
  const int solid_ink = count_colour(solid, 0, 114, 178), hollow_ink = count_colour(hollow, 0, 114, 178);
  EXPECT_EQ(solid_ink - hollow_ink, 9) << "a 3 x 3 white centre in a 7 x 7 square";
}

}  // namespace
}  // namespace vgd::study
