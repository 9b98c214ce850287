// Images in memory: construction, supersampling reduction, row order.
#include "vgd/render/image.hpp"

#include <algorithm>

#include "vgd/core/diagnostics.hpp"

namespace vgd::render {

Image::Image(int w, int h, std::array<std::uint8_t, 4> fill) : width(w), height(h) {
  VGD_ASSERT(w >= 0 && h >= 0, "an image cannot have a negative size");
  rgba.resize(static_cast<std::size_t>(w) * h * 4);
  for (std::size_t i = 0; i < rgba.size(); i += 4) std::copy(fill.begin(), fill.end(), rgba.begin() + i);
}

Image downsample(const Image& image, int factor) {
  VGD_ASSERT(factor >= 1, "the downsampling factor must be at least 1");
  VGD_ASSERT(image.width % factor == 0 && image.height % factor == 0,
             "the image size must be a multiple of the downsampling factor");
  if (factor == 1) return image;
  Image out(image.width / factor, image.height / factor);
  const unsigned n = static_cast<unsigned>(factor * factor);
  // Integer sums, rounded: the same input gives the same bytes everywhere.
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      unsigned sum[4] = {0, 0, 0, 0};
      for (int j = 0; j < factor; ++j) {
        const std::uint8_t* row = image.pixel(x * factor, y * factor + j);
        for (int i = 0; i < factor; ++i)
          for (int c = 0; c < 4; ++c) sum[c] += row[4 * i + c];
      }
      std::uint8_t* o = out.pixel(x, y);
      for (int c = 0; c < 4; ++c) o[c] = static_cast<std::uint8_t>((sum[c] + n / 2) / n);
    }
  }
  return out;
}

void flip_rows(Image& image) {
  const std::size_t stride = static_cast<std::size_t>(image.width) * 4;
  for (int y = 0; y < image.height / 2; ++y)
    std::swap_ranges(image.rgba.begin() + y * stride, image.rgba.begin() + (y + 1) * stride,
                     image.rgba.begin() + (image.height - 1 - y) * stride);
}

}  // namespace vgd::render
