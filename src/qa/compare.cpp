// SSIM (Wang et al. 2004), pixel statistics and diff images.
#include "vgd/qa/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "vgd/core/diagnostics.hpp"

namespace vgd::qa {

namespace {

void check_same_size(const Image& a, const Image& b) {
  VGD_ASSERT(a.width == b.width && a.height == b.height, "images to compare must have the same size");
  VGD_ASSERT(!a.empty(), "cannot compare empty images");
}

// Normalised 1-D Gaussian of `size` taps (the 2-D window is its outer product).
std::vector<double> gaussian(int size, double sigma) {
  std::vector<double> g(static_cast<std::size_t>(size));
  double sum = 0;
  for (int i = 0; i < size; ++i) {
    const double x = i - (size - 1) / 2.0;
    g[static_cast<std::size_t>(i)] = std::exp(-x * x / (2 * sigma * sigma));
    sum += g[static_cast<std::size_t>(i)];
  }
  for (auto& v : g) v /= sum;
  return g;
}

// "Valid" separable filtering of a w x h plane: (w - n + 1) x (h - n + 1) out.
std::vector<double> filter_valid(const std::vector<double>& in, int w, int h, const std::vector<double>& g) {
  const int n = static_cast<int>(g.size()), ow = w - n + 1, oh = h - n + 1;
  std::vector<double> rows(static_cast<std::size_t>(ow) * h), out(static_cast<std::size_t>(ow) * oh);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      const double* p = &in[static_cast<std::size_t>(y) * w + x];
      for (int k = 0; k < n; ++k) s += g[k] * p[k];
      rows[static_cast<std::size_t>(y) * ow + x] = s;
    }
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int k = 0; k < n; ++k) s += g[k] * rows[static_cast<std::size_t>(y + k) * ow + x];
      out[static_cast<std::size_t>(y) * ow + x] = s;
    }
  return out;
}

int channel_difference(const std::uint8_t* p, const std::uint8_t* q) {
  return std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])});
}

}  // namespace

std::vector<double> luminance(const Image& image) {
  std::vector<double> y(static_cast<std::size_t>(image.width) * image.height);
  for (std::size_t i = 0; i < y.size(); ++i) {
    const std::uint8_t* p = &image.rgba[4 * i];
    y[i] = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
  }
  return y;
}

namespace {

// Mean SSIM of two planes of w x h values (Wang et al. 2004, "valid" windows).
double ssim_planes(const std::vector<double>& x, const std::vector<double>& y, int w, int h,
                   const SsimOptions& options) {
  VGD_ASSERT(options.window >= 1 && options.window % 2 == 1 && options.sigma > 0, "the SSIM window must be odd, σ > 0");
  // The window, shrunk (kept odd) for images smaller than it.
  int n = std::min({options.window, w, h});
  if (n % 2 == 0) --n;
  const auto g = gaussian(n, options.sigma);

  // Local statistics: filtered x, y, x², y², xy.
  std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
  const auto mx = filter_valid(x, w, h, g), my = filter_valid(y, w, h, g);
  const auto sxx = filter_valid(xx, w, h, g), syy = filter_valid(yy, w, h, g), sxy = filter_valid(xy, w, h, g);

  const double c1 = std::pow(options.k1 * options.dynamic_range, 2);
  const double c2 = std::pow(options.k2 * options.dynamic_range, 2);
  double sum = 0;
  for (std::size_t i = 0; i < mx.size(); ++i) {
    const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cxy = sxy[i] - mx[i] * my[i];
    sum += ((2 * mx[i] * my[i] + c1) * (2 * cxy + c2)) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
  }
  return sum / static_cast<double>(mx.size());
}

// One channel (0 R, 1 G, 2 B) of every pixel, row by row.
std::vector<double> channel(const Image& image, int c) {
  std::vector<double> v(static_cast<std::size_t>(image.width) * image.height);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = image.rgba[4 * i + static_cast<std::size_t>(c)];
  return v;
}

}  // namespace

double ssim(const Image& a, const Image& b, const SsimOptions& options) {
  check_same_size(a, b);
  return ssim_planes(luminance(a), luminance(b), a.width, a.height, options);
}

double colour_ssim(const Image& a, const Image& b, const SsimOptions& options) {
  check_same_size(a, b);
  double lowest = 1;
  for (int c = 0; c < 3; ++c)
    lowest = std::min(lowest, ssim_planes(channel(a, c), channel(b, c), a.width, a.height, options));
  return lowest;
}

PixelStats pixel_stats(const Image& a, const Image& b, int threshold) {
  check_same_size(a, b);
  PixelStats s;
  s.pixels = static_cast<long long>(a.width) * a.height;
  s.threshold = threshold;
  long long total = 0;
  for (long long i = 0; i < s.pixels; ++i) {
    const std::uint8_t* p = &a.rgba[4 * static_cast<std::size_t>(i)];
    const std::uint8_t* q = &b.rgba[4 * static_cast<std::size_t>(i)];
    for (int c = 0; c < 3; ++c) total += std::abs(p[c] - q[c]);
    const int d = channel_difference(p, q);
    s.max_abs_difference = std::max(s.max_abs_difference, d);
    if (d > threshold) ++s.differing_pixels;
  }
  s.mean_abs_difference = static_cast<double>(total) / (3.0 * static_cast<double>(s.pixels));
  s.differing_percent = 100.0 * static_cast<double>(s.differing_pixels) / static_cast<double>(s.pixels);
  return s;
}

Image diff_image(const Image& a, const Image& b, int threshold) {
  check_same_size(a, b);
  Image out(a.width, a.height);
  const auto y = luminance(a);
  for (std::size_t i = 0; i < y.size(); ++i) {
    const std::uint8_t* p = &a.rgba[4 * i];
    const std::uint8_t* q = &b.rgba[4 * i];
    std::uint8_t* o = &out.rgba[4 * i];
    const int d = channel_difference(p, q);
    if (d > threshold) {
      // Red, from 160 (just over the threshold) to 255.
      o[0] = static_cast<std::uint8_t>(160 + (95 * d) / 255);
      o[1] = o[2] = 0;
    } else {
      // A's luminance squeezed into 170–255: light, so the red stands out.
      o[0] = o[1] = o[2] = static_cast<std::uint8_t>(170 + std::lround(y[i] / 3.0));
    }
    o[3] = 255;
  }
  return out;
}

Comparison compare(const Image& a, const Image& b, const CompareOptions& options) {
  Comparison c;
  c.ssim = ssim(a, b, options.ssim);
  c.colour_ssim = options.luminance_only ? c.ssim : colour_ssim(a, b, options.ssim);
  c.score = std::min(c.ssim, c.colour_ssim);
  c.stats = pixel_stats(a, b, options.pixel_threshold);
  c.passed = c.score >= options.ssim_threshold;
  return c;
}

}  // namespace vgd::qa
