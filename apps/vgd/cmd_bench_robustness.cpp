// vgd bench robustness: the project's garments draped over a sweep of mesh
// spacings, sizes, fabrics and cloth models, each case also from its start
// moved by 1 µm (study::robustness_study), one thread. Prints per run whether
// it came to rest clean and, if not, the failure classes of its certificate;
// per jittered run how far its particles ended from the run as placed; then
// the share of clean runs against the 99 % target and a Markdown table per
// garment, mesh, fabric and model (study::summarise_robustness); --json: the
// records only. Exit 3 when a run is not clean.
#include <cstdio>
#include <string>
#include <vector>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/study/bench.hpp"

namespace vgd::cli {

namespace {

constexpr double kTargetClean = 0.99;  // share of clean runs

nlohmann::json to_json(const study::RobustnessRecord& r) {
  const auto& c = r.certificate;
  const auto [closed, pairs] = c.seam_totals();
  nlohmann::json j{{"garment", r.run.garment.stem().string()},
                   {"spacing_m", r.run.spacing},
                   {"size", r.run.size},
                   {"material", r.run.material.empty() ? "own" : r.run.material},
                   {"model", scene::to_string(r.run.model)},
                   {"jitter_m", r.run.jitter},
                   {"seed", r.run.seed},
                   {"stop", c.stop_reason},
                   {"simulated_s", c.simulated_s},
                   {"wall_s", c.wall_s},
                   {"seams_closed", closed},
                   {"seam_pairs", pairs},
                   {"max_penetration_m", c.max_penetration},
                   {"crossing_triangle_pairs", c.triangle_intersections},
                   {"strain_p95_max", r.max_strain},
                   {"displacement_max_m", r.max_moved},
                   {"clean", r.clean},
                   {"failure", r.failure},
                   {"message", c.stop_message}};
  if (r.spread >= 0.0) j["spread_m"] = r.spread;
  return j;
}

// "lo–hi unit" (one figure when they are equal; "–" when there is none).
std::string range(double lo, double hi, double scale, int digits, const char* unit) {
  if (lo > hi) return "–";
  const std::string a = vgd::format_fixed(lo * scale, digits), b = vgd::format_fixed(hi * scale, digits);
  return (a == b ? a : a + "–" + b) + " " + unit;
}

// Per garment, mesh, fabric and cloth model, as a Markdown table (docs/drape.md, "Robustness").
void print_summary(const std::vector<study::RobustnessRow>& rows) {
  std::printf(
      "\n| garment | mesh | fabric | model | clean runs | failures (runs) | rest after (clean) | wall | "
      "jittered run from its case's |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& w : rows) {
    std::string failures;
    for (const auto& [kind, n] : w.failures)
      failures += (failures.empty() ? "" : ", ") + kind + " " + std::to_string(n);
    std::printf("| %s | %scm | %s | %s | %d of %d | %s | %s | %s | %s |\n", w.garment.c_str(),
                vgd::format_fixed(w.spacing * 100, 1).c_str(),
                w.material.empty() ? "own" : w.material.c_str(), scene::to_string(w.model), w.clean, w.runs,
                failures.empty() ? "–" : failures.c_str(), range(w.rest_lo, w.rest_hi, 1, 2, "s").c_str(),
                range(w.wall_lo, w.wall_hi, 1, 1, "s").c_str(),
                range(w.spread_lo, w.spread_hi, 1000, 0, "mm").c_str());
  }
}

}  // namespace

int bench_robustness(const RobustnessArgs& a) {
  study::RobustnessOptions o = study::robustness_sweep(a.quick);
  o.time_limit = a.time_limit;
  o.between_particles = a.between_particles;
  o.sleeves_first = a.sleeves_first;
  if (!a.garments.empty()) o.garments.assign(a.garments.begin(), a.garments.end());
  if (!a.spacings.empty()) o.spacings = a.spacings;
  if (!a.sizes.empty()) o.sizes = a.sizes;
  if (!a.fabrics.empty()) {
    o.materials.clear();
    for (const auto& f : a.fabrics) o.materials.push_back(f == "own" ? "" : f);
  }
  if (!a.models.empty()) {
    o.models.clear();
    for (const auto& m : a.models) o.models.push_back(scene::parse_cloth_model(m));
  }
  if (a.jitters >= 0) o.jitters = a.jitters;
  study::check_robustness(o);
  const bool json = a.json, between_particles = a.between_particles;
  const double time_limit = a.time_limit;
  const std::size_t runs = o.garments.size() * o.spacings.size() * o.sizes.size() * o.materials.size() *
                           o.models.size() * static_cast<std::size_t>(o.jitters + 1);
  if (!json) {
    std::printf("%zu runs, 1 thread, %s s simulated at most%s%s\n", runs,
                vgd::format_fixed(time_limit, 1).c_str(), between_particles ? "" : ", --no-between-particles",
                o.sleeves_first ? ", --sleeves-first" : "");
    std::printf("%-13s %6s %5s %-18s %-15s %8s %7s %7s %8s %7s %6s %7s %7s %9s  %s\n", "garment", "mesh", "size",
                "fabric", "model", "jitter", "rest s", "wall s", "seams", "pen mm", "cross", "strain", "moved",
                "spread", "outcome");
  }
  int done = 0, clean = 0;
  double widest = 0.0;
  const auto records = study::robustness_study(o, [&](const study::RobustnessRecord& r) {
    ++done;
    clean += r.clean;
    if (r.spread > widest) widest = r.spread;
    if (json) return;
    const auto& c = r.certificate;
    const auto [closed, pairs] = c.seam_totals();
    std::printf("%-13s %6s %5s %-18s %-15s %8s %7s %7.1f %8s %7.2f %6d %6.0f%% %5.1fcm %9s  %s%s\n",
                r.run.garment.stem().string().c_str(), (vgd::format_fixed(r.run.spacing * 100, 1) + "cm").c_str(),
                r.run.size.empty() ? "-" : r.run.size.c_str(),
                r.run.material.empty() ? "own" : r.run.material.c_str(), scene::to_string(r.run.model),
                r.run.jitter > 0 ? ("1e-6#" + std::to_string(r.run.seed)).c_str() : "-",
                c.stop_reason == "rest" ? vgd::format_fixed(c.simulated_s, 2).c_str() : "-", c.wall_s,
                (std::to_string(closed) + "/" + std::to_string(pairs)).c_str(), c.max_penetration * 1000,
                c.triangle_intersections, r.max_strain * 100, r.max_moved * 100,
                r.spread >= 0 ? (vgd::format_fixed(r.spread * 1000, 2) + "mm").c_str() : "-",
                r.clean ? "clean" : r.failure.c_str(),
                c.stop_reason == "error" ? (" (" + c.stop_message.substr(0, 100) + ")").c_str() : "");
    std::fflush(stdout);
  });
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& r : records) list.push_back(to_json(r));
    print_json(list);
  } else {
    std::printf("clean: %d of %d runs (%s %%; target %s %%); jittered runs ended within %s mm of their case's run\n",
                clean, done, vgd::format_fixed(done ? 100.0 * clean / done : 0.0, 1).c_str(),
                vgd::format_fixed(100 * kTargetClean, 0).c_str(), vgd::format_fixed(widest * 1000, 2).c_str());
    print_summary(study::summarise_robustness(records));
  }
  return clean == done ? kOk : kCheckFailed;
}

}  // namespace vgd::cli
