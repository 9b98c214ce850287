// SSIM and pixel statistics: identical images score 1, a constant offset
// scores what the formula says, noise lowers SSIM monotonically, a change of
// hue at equal brightness is caught by the colour SSIM, and the statistics and
// the diff image count and show exactly the pixels that changed.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "vgd/qa/compare.hpp"

using namespace vgd;

namespace {

std::uint8_t clamp_byte(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0))); }

// Grey image with value f(x, y) in every channel.
template <class F>
qa::Image grey(int w, int h, F f) {
  qa::Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto* p = im.pixel(x, y);
      p[0] = p[1] = p[2] = clamp_byte(f(x, y));
    }
  return im;
}

// Texture with structure at several scales, values within 60–190.
double texture(int x, int y) { return 125 + 40 * std::sin(0.21 * x) * std::cos(0.17 * y) + 25 * std::sin(0.9 * (x + y)); }

}  // namespace

TEST(Ssim, IdenticalImagesScoreOne) {
  const auto a = grey(64, 48, texture);
  EXPECT_NEAR(qa::ssim(a, a), 1.0, 1e-12);
  EXPECT_NEAR(qa::colour_ssim(a, a), 1.0, 1e-12);
  const auto c = qa::compare(a, a);
  EXPECT_TRUE(c.passed);
  EXPECT_EQ(c.stats.max_abs_difference, 0);
  EXPECT_EQ(c.stats.differing_pixels, 0);
}

TEST(Ssim, AConstantOffsetOnAFlatImageScoresTheLuminanceTerm) {
  // Flat images: σ = 0, so SSIM = (2 μx μy + C1) / (μx² + μy² + C1), C1 = (0.01 · 255)².
  const double c1 = std::pow(0.01 * 255, 2);
  for (const auto& [mu, offset] : {std::pair{100.0, 20.0}, std::pair{200.0, 20.0}, std::pair{50.0, 20.0}}) {
    const auto a = grey(32, 32, [&](int, int) { return mu; });
    const auto b = grey(32, 32, [&](int, int) { return mu + offset; });
    const double expected = (2 * mu * (mu + offset) + c1) / (mu * mu + (mu + offset) * (mu + offset) + c1);
    EXPECT_NEAR(qa::ssim(a, b), expected, 1e-9) << "mean " << mu;
  }
  // On a textured image the same offset leaves structure and contrast intact:
  // SSIM stays above the flat case's value for the darkest local mean.
  const auto a = grey(64, 64, texture);
  const auto b = grey(64, 64, [](int x, int y) { return texture(x, y) + 20; });
  const double s = qa::ssim(a, b);
  EXPECT_LT(s, 1.0);
  EXPECT_GT(s, (2 * 60.0 * 80 + c1) / (60.0 * 60 + 80.0 * 80 + c1));
}

TEST(Ssim, MoreNoiseLowersItMonotonically) {
  const auto a = grey(96, 96, texture);
  std::mt19937 rng(12345);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<double> noise(96 * 96);
  for (auto& n : noise) n = unit(rng);
  double previous = 1.0;
  for (const double sigma : {1.0, 3.0, 6.0, 12.0, 25.0, 50.0}) {
    const auto b = grey(96, 96, [&](int x, int y) { return texture(x, y) + sigma * noise[96 * y + x]; });
    const double s = qa::ssim(a, b);
    EXPECT_LT(s, previous) << "σ = " << sigma;
    EXPECT_NEAR(s, qa::ssim(b, a), 1e-12) << "symmetric";
    previous = s;
  }
  EXPECT_LT(previous, 0.5);
}

TEST(Ssim, AHueChangeAtEqualBrightnessIsCaughtByTheColourSsim) {
  // Two colours of nearly the same Rec. 601 luminance (111): a luminance-only index
  // cannot see the change; the colour SSIM can.
  qa::Image a(64, 64, {240, 240, 240, 255}), b = a;
  for (int y = 16; y < 48; ++y)
    for (int x = 16; x < 48; ++x) {
      auto* p = a.pixel(x, y);
      p[0] = 40, p[1] = 120, p[2] = 250;  // blue
      auto* q = b.pixel(x, y);
      q[0] = 140, q[1] = 117, q[2] = 8;  // olive
    }
  EXPECT_GT(qa::ssim(a, b), 0.99);
  EXPECT_LT(qa::colour_ssim(a, b), 0.7);
  EXPECT_FALSE(qa::compare(a, b).passed);
  qa::CompareOptions lum;
  lum.luminance_only = true;
  EXPECT_TRUE(qa::compare(a, b, lum).passed);
}

TEST(Ssim, ImagesSmallerThanTheWindowStillCompare) {
  const auto a = grey(5, 4, texture);
  EXPECT_NEAR(qa::ssim(a, a), 1.0, 1e-12);
  const auto b = grey(5, 4, [](int x, int y) { return texture(x, y) + 30; });
  EXPECT_LT(qa::ssim(a, b), 1.0);
}

TEST(PixelStats, CountExactlyThePixelsBeyondTheThreshold) {
  qa::Image a(20, 10, {100, 100, 100, 255}), b = a;
  for (int i = 0; i < 10; ++i) b.pixel(i, 0)[1] = 130;  // 10 pixels, +30 in green
  for (int i = 0; i < 5; ++i) b.pixel(i, 5)[2] = 105;   // 5 pixels, +5 in blue: below 8
  b.pixel(19, 9)[3] = 0;                                // alpha is ignored
  const auto s = qa::pixel_stats(a, b, 8);
  EXPECT_EQ(s.pixels, 200);
  EXPECT_EQ(s.max_abs_difference, 30);
  EXPECT_EQ(s.differing_pixels, 10);
  EXPECT_DOUBLE_EQ(s.differing_percent, 5.0);
  EXPECT_NEAR(s.mean_abs_difference, (10 * 30 + 5 * 5) / 600.0, 1e-12);
  EXPECT_EQ(qa::pixel_stats(a, b, 4).differing_pixels, 15);
}

TEST(DiffImage, ChangedPixelsAreRedTheRestLightGrey) {
  qa::Image a(8, 8, {50, 60, 70, 255}), b = a;
  b.pixel(3, 4)[0] = 250;
  const auto d = qa::diff_image(a, b, 8);
  const auto* changed = d.pixel(3, 4);
  EXPECT_GE(changed[0], 160);
  EXPECT_EQ(changed[1], 0);
  EXPECT_EQ(changed[2], 0);
  const auto* same = d.pixel(0, 0);
  EXPECT_EQ(same[0], same[1]);
  EXPECT_EQ(same[1], same[2]);
  EXPECT_GE(same[0], 170);
}
