#pragma once
// Images: 8-bit RGBA pixels, rows top to bottom, and PNG files (libpng).
//
// The renderer returns an Image; the qa stage reads two PNGs back as Images and
// compares them. PNG encoding is deterministic: the same pixels give the same
// bytes (no time stamp, fixed compression settings).
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vgd::render {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, row 0 at the top

  Image() = default;
  Image(int w, int h, std::array<std::uint8_t, 4> fill = {0, 0, 0, 255});

  bool empty() const { return width <= 0 || height <= 0; }
  // The 4 bytes of pixel (x, y), x to the right, y down from the top row.
  const std::uint8_t* pixel(int x, int y) const { return rgba.data() + 4 * (static_cast<std::size_t>(y) * width + x); }
  std::uint8_t* pixel(int x, int y) { return rgba.data() + 4 * (static_cast<std::size_t>(y) * width + x); }
};

// Box-filter downsampling by an integer factor (supersampling anti-aliasing):
// each output pixel is the rounded mean of factor × factor input pixels. The
// input's width and height must be multiples of `factor`.
Image downsample(const Image& image, int factor);

// Flips the rows (OpenGL reads the bottom row first).
void flip_rows(Image& image);

// PNG bytes of an image: 8-bit RGB when every pixel is opaque, else RGBA.
std::string encode_png(const Image& image);

// Writes a PNG atomically (vgd::write_file_atomic). Throws vgd::Error naming
// the file on failure.
void write_png(const Image& image, const std::filesystem::path& path);

// The largest image decoded unless the caller allows more: 8192 x 8192 pixels
// (256 MiB as RGBA). A PNG's header can claim 10^10 pixels in 69 bytes.
inline constexpr std::uint64_t kMaxImagePixels = 8192ull * 8192ull;

// Decodes PNG bytes (any bit depth, palette, grey or alpha) into 8-bit RGBA.
// Throws vgd::Error naming `name` when the bytes are not a PNG image, or when
// its header claims more than max_pixels pixels (nothing is allocated then).
Image decode_png(std::string_view bytes, const std::string& name, std::uint64_t max_pixels = kMaxImagePixels);

// Reads a PNG file. Throws vgd::Error naming the file when it is missing,
// unreadable, not a PNG image or larger than max_pixels.
Image read_png(const std::filesystem::path& path, std::uint64_t max_pixels = kMaxImagePixels);

}  // namespace vgd::render
