#pragma once
// Snapshot QA: how alike two images are (docs/qa.md).
//
// SSIM is the structural similarity index of Wang, Bovik, Sheikh and
// Simoncelli, "Image quality assessment: from error visibility to structural
// similarity", IEEE Trans. Image Processing 13(4), 2004, computed as in the
// paper and its reference code:
//
//   SSIM(x, y) = (2 μx μy + C1)(2 σxy + C2) / ((μx² + μy² + C1)(σx² + σy² + C2))
//   C1 = (K1 L)², C2 = (K2 L)², K1 = 0.01, K2 = 0.03, L = 255
//
// on the luminance Y = 0.299 R + 0.587 G + 0.114 B of the 8-bit values (alpha
// ignored), with local means, variances and covariance weighted by an 11 × 11
// Gaussian window of σ = 1.5 pixels (normalised to sum 1) at every position
// where the window lies wholly inside the image ("valid" filtering), and the
// index of two images the mean over those positions (MSSIM). 1 means
// identical; the reference code's automatic downsampling is not applied.
//
// Luminance SSIM hardly sees a change of hue at similar brightness (a blue
// skirt turned green scores 0.9999), so a comparison also takes the colour
// SSIM, the lowest SSIM of the R, G and B channels each taken as a grey image,
// and passes only when both reach the threshold (CompareOptions).
#include <string>
#include <vector>

#include "vgd/render/image.hpp"

namespace vgd::qa {

using render::Image;

struct SsimOptions {
  int window = 11;              // pixels per side (odd); shrunk to the image when it is smaller
  double sigma = 1.5;           // Gaussian σ, pixels
  double k1 = 0.01, k2 = 0.03;  // stabilising constants of the paper
  double dynamic_range = 255;   // L
};

// Luminance of every pixel, row by row (Rec. 601 weights on the 8-bit values).
std::vector<double> luminance(const Image& image);

// Mean SSIM of two images of the same size (VGD_ASSERT otherwise).
double ssim(const Image& a, const Image& b, const SsimOptions& options = {});

// The lowest of the SSIMs of the R, G and B channels (each as above, on the
// channel's 8-bit values instead of the luminance).
double colour_ssim(const Image& a, const Image& b, const SsimOptions& options = {});

// Per-pixel differences over R, G and B (alpha ignored), 0–255.
struct PixelStats {
  long long pixels = 0;
  int max_abs_difference = 0;        // largest |a − b| over every channel of every pixel
  double mean_abs_difference = 0;    // mean |a − b| over every channel of every pixel
  int threshold = 0;                 // a pixel differs when a channel differs by more than this
  long long differing_pixels = 0;
  double differing_percent = 0;      // 100 × differing_pixels / pixels
};
PixelStats pixel_stats(const Image& a, const Image& b, int threshold = 8);

// The changes, for eyes: A in light grey, pixels that differ (as in
// pixel_stats) in red, brighter the larger the difference.
Image diff_image(const Image& a, const Image& b, int threshold = 8);

struct CompareOptions {
  double ssim_threshold = 0.99;  // pass when min(SSIM, colour SSIM) >= this
  bool luminance_only = false;   // judge by the luminance SSIM alone (the paper's index)
  int pixel_threshold = 8;       // for the pixel statistics and the diff image
  SsimOptions ssim;
};

struct Comparison {
  double ssim = 0;         // luminance SSIM
  double colour_ssim = 0;  // lowest channel SSIM (= ssim when luminance_only)
  double score = 0;        // min(ssim, colour_ssim): what the threshold judges
  PixelStats stats;
  bool passed = false;     // score >= threshold
};

// SSIMs and pixel statistics of two images of the same size.
Comparison compare(const Image& a, const Image& b, const CompareOptions& options = {});

}  // namespace vgd::qa
