// vgd compare: snapshot QA of two PNG images (docs/qa.md).
//
//   vgd compare golden.png new.png --threshold 0.99 --diff diff.png
//
// Prints SSIM (Wang et al. 2004, luminance, 11 x 11 Gaussian window, σ 1.5),
// the colour SSIM (the lowest of the R, G, B channels' SSIMs) and pixel
// statistics; exit 0 when both SSIMs reach the threshold, 3 when one is below,
// 1 for a missing or unreadable file or images of different sizes.
#include <cstdio>
#include <memory>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/qa/compare.hpp"

namespace cmd_compare {
namespace {

struct Options {
  std::string a, b, diff;
  double threshold = 0.99;
  int pixel_threshold = 8;
  bool json = false, luminance_only = false;
  std::uint64_t max_pixels = vgd::render::kMaxImagePixels;
};

vgd::cli::Registrar reg{"compare", 76, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("compare", "Compare two PNG images: SSIM, pixel statistics, a diff image");
  auto o = std::make_shared<Options>();
  sub->add_option("A", o->a, "Reference image (PNG), e.g. a golden preview")->required();
  sub->add_option("B", o->b, "Image to check (PNG), the same size")->required();
  sub->add_option("--threshold", o->threshold, "Pass when SSIM and colour SSIM are both >= this (0–1)")
      ->check(CLI::Range(-1.0, 1.0))
      ->capture_default_str();
  sub->add_option("--pixel-threshold", o->pixel_threshold,
                  "A pixel differs when a channel differs by more than this (0–255)")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  sub->add_option("--diff", o->diff, "Write a diff image: A in light grey, differing pixels in red");
  sub->add_flag("--luminance-only", o->luminance_only,
                "Judge by the luminance SSIM alone (blind to a change of hue at equal brightness)");
  sub->add_option("--max-pixels", o->max_pixels,
                  "Refuse an image with more pixels than this (8192 x 8192 by default)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_flag("--json", o->json, "Print the result as JSON on stdout");
  sub->footer("Exit codes: 0 SSIM >= threshold, 1 bad input (missing file, not a PNG, sizes differ), "
              "2 usage, 3 SSIM below the threshold (docs/qa.md).");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    namespace qa = vgd::qa;
    const qa::Image a = vgd::render::read_png(o->a, o->max_pixels),
                   b = vgd::render::read_png(o->b, o->max_pixels);
    if (a.width != b.width || a.height != b.height)
      throw vgd::Error(o->b, "", "is " + std::to_string(b.width) + " x " + std::to_string(b.height) + " pixels but " +
                                     o->a + " is " + std::to_string(a.width) + " x " + std::to_string(a.height) +
                                     ": images of different sizes cannot be compared");
    qa::CompareOptions opts;
    opts.ssim_threshold = o->threshold;
    opts.pixel_threshold = o->pixel_threshold;
    opts.luminance_only = o->luminance_only;
    const qa::Comparison c = qa::compare(a, b, opts);
    if (!o->diff.empty()) vgd::render::write_png(qa::diff_image(a, b, o->pixel_threshold), o->diff);

    const auto& s = c.stats;
    if (o->json) {
      nlohmann::json j{{"a", o->a},
                       {"b", o->b},
                       {"width", a.width},
                       {"height", a.height},
                       {"ssim", c.ssim},
                       {"colour_ssim", c.colour_ssim},
                       {"luminance_only", o->luminance_only},
                       {"threshold", o->threshold},
                       {"passed", c.passed},
                       {"max_abs_difference", s.max_abs_difference},
                       {"mean_abs_difference", s.mean_abs_difference},
                       {"pixel_threshold", s.threshold},
                       {"differing_pixels", s.differing_pixels},
                       {"differing_percent", s.differing_percent}};
      if (!o->diff.empty()) j["diff"] = o->diff;
      vgd::cli::print_json(j);
    } else {
      const std::string colour = o->luminance_only ? "" : ", colour SSIM " + vgd::format_fixed(c.colour_ssim, 6);
      std::printf("SSIM %s%s (threshold %s): %s\n", vgd::format_fixed(c.ssim, 6).c_str(), colour.c_str(),
                  vgd::format_double(o->threshold).c_str(), c.passed ? "pass" : "FAIL");
      std::printf("%d x %d pixels: max difference %d/255, mean %s/255; %lld pixels (%s%%) differ by more than %d\n",
                  a.width, a.height, s.max_abs_difference, vgd::format_fixed(s.mean_abs_difference, 3).c_str(),
                  s.differing_pixels, vgd::format_fixed(s.differing_percent, 3).c_str(), s.threshold);
      if (!o->diff.empty()) std::printf("diff image: %s\n", o->diff.c_str());
      std::fflush(stdout);
    }
    if (!c.passed && !o->json)
      vgd::cli::say(common, "vgd: " + o->b + " differs from " + o->a + " (SSIM " + vgd::format_fixed(c.score, 4) +
                                " < " + vgd::format_double(o->threshold) + ")");
    return c.passed ? vgd::cli::kOk : vgd::cli::kCheckFailed;
  }};
}};

}  // namespace
}  // namespace cmd_compare
