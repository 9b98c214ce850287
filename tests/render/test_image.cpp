// Images and PNG files: what is written reads back pixel for pixel, the same
// pixels give the same bytes, anything that is not a PNG is refused by name,
// and supersampling reduction averages.
#include <gtest/gtest.h>

#include <algorithm>

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/render/image.hpp"

using namespace vgd;

namespace {

// A gradient with some alpha, so every channel carries information.
render::Image gradient(int w, int h, bool opaque) {
  render::Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto* p = im.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(x * 255 / std::max(1, w - 1));
      p[1] = static_cast<std::uint8_t>(y * 255 / std::max(1, h - 1));
      p[2] = static_cast<std::uint8_t>((x * 7 + y * 13) % 256);
      p[3] = opaque ? 255 : static_cast<std::uint8_t>(128 + (x % 2) * 100);
    }
  return im;
}

}  // namespace

TEST(Png, OpaqueAndTranslucentImagesReadBackExactly) {
  const auto dir = test::scratch_dir("render_png");
  for (const bool opaque : {true, false}) {
    const auto im = gradient(37, 21, opaque);
    const auto path = dir / (opaque ? "opaque.png" : "alpha.png");
    render::write_png(im, path);
    const auto back = render::read_png(path);
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 21);
    EXPECT_EQ(back.rgba, im.rgba);
  }
}

TEST(Png, TheSamePixelsGiveTheSameBytes) {
  const auto im = gradient(64, 48, true);
  EXPECT_EQ(render::encode_png(im), render::encode_png(im));
  EXPECT_EQ(render::encode_png(im).substr(1, 3), "PNG");
}

TEST(Png, ANonPngFileIsRefusedByName) {
  const auto dir = test::scratch_dir("render_png_bad");
  write_file_atomic(dir / "fake.png", "this is text, not an image\n");
  try {
    render::read_png(dir / "fake.png");
    FAIL() << "expected vgd::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fake.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a PNG"), std::string::npos) << e.what();
  }
  // A PNG signature followed by garbage: unreadable, named.
  write_file_atomic(dir / "cut.png", std::string("\x89PNG\r\n\x1a\n", 8) + "garbage");
  EXPECT_THROW(render::read_png(dir / "cut.png"), Error);
  EXPECT_THROW(render::read_png(dir / "missing.png"), Error);
}

TEST(Image, DownsamplingAveragesEachBlockRounded) {
  render::Image big(4, 2);
  const std::uint8_t values[4] = {0, 10, 20, 31};  // block 0: 0,10 / 20,31 -> 61/4 = 15.25 -> 15
  big.pixel(0, 0)[0] = values[0], big.pixel(1, 0)[0] = values[1];
  big.pixel(0, 1)[0] = values[2], big.pixel(1, 1)[0] = values[3];
  for (int x = 2; x < 4; ++x)
    for (int y = 0; y < 2; ++y) big.pixel(x, y)[1] = 255;
  const auto small = render::downsample(big, 2);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_EQ(small.pixel(0, 0)[0], 15);
  EXPECT_EQ(small.pixel(1, 0)[1], 255);
  EXPECT_EQ(small.pixel(1, 0)[3], 255);
}

TEST(Image, FlippingRowsTwiceRestoresTheImage) {
  auto im = gradient(5, 7, true);
  const auto original = im.rgba;
  render::flip_rows(im);
  EXPECT_EQ(im.pixel(0, 0)[1], original[4 * (6 * 5) + 1]);  // the old bottom row is on top
  render::flip_rows(im);
  EXPECT_EQ(im.rgba, original);
}
