// vgd bench dress: the project's two garments, the A-line skirt and the
// T-shirt over it, from flat pieces to rest on the size-38 mannequin, with 1
// thread and with every core, or only the --threads given (study::dress_study). At the default 1.9 cm
// spacing the two hold about 5 000 particles, the scene seed 000 sewed in ten
// minutes (a shirt and a skirt of 2 500 particles each on a 5 000-triangle
// body); the target is under 10 s wall on a 2-core machine. Prints the wall
// time per stage (placing, sewing, settling) and per effect, with the drape's
// checks (rest, seams, penetration, crossings): a fast drape that fails them
// is no result (exit code 3).
#include <cstdio>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/study/bench.hpp"

namespace vgd::cli {

namespace {

constexpr double kTargetWallS = 10.0;  // flat pieces to rest, ≈5 000 particles, two garments

nlohmann::json to_json(const study::DressRecord& r) {
  nlohmann::json stages = nlohmann::json::object(), effects = nlohmann::json::object();
  for (const auto& s : r.certificate.stages) stages[s.name] = {{"wall_s", s.wall_s}, {"simulated_s", s.simulated_s}};
  for (const auto& [name, sec] : r.certificate.effect_seconds) effects[name] = sec;
  const auto [closed, pairs] = r.certificate.seam_totals();
  return {{"threads", r.threads},
          {"particles", r.certificate.particles},
          {"body_triangles", r.body_triangles},
          {"stop", r.certificate.stop_reason},
          {"simulated_s", r.certificate.simulated_s},
          {"wall_s", r.certificate.wall_s},
          {"stages", stages},
          {"effect_seconds", effects},
          {"seams_closed", closed},
          {"seam_pairs", pairs},
          {"max_penetration_m", r.certificate.max_penetration},
          {"crossing_triangle_pairs", r.certificate.triangle_intersections},
          {"passed", r.certificate.passed()},
          {"target_wall_s", kTargetWallS}};
}

}  // namespace

int bench_dress(double spacing, const std::string& size, double time_limit, bool between_particles, bool json,
                int threads) {
  if (!json)
    std::printf("dress: a-line-skirt.xvc + t-shirt.xvc, size %s, spacing %s m, to rest or %s s simulated%s; target < %s s wall\n",
                size.c_str(), format_fixed(spacing, 3).c_str(), format_fixed(time_limit, 1).c_str(),
                between_particles ? "" : ", --no-between-particles", format_fixed(kTargetWallS, 0).c_str());
  bool all_passed = true;
  const auto records = study::dress_study(spacing, size, time_limit, between_particles, [&](const study::DressRecord& rec) {
    all_passed = all_passed && rec.certificate.passed();
    if (json) return;
    const auto& c = rec.certificate;
    const int t = rec.threads;
    const auto [closed, pairs] = c.seam_totals();
    std::printf("\n%d thread%s: %d particles on a %d-triangle body; %s after %s s simulated, %s s wall (%s)\n", t,
                t == 1 ? "" : "s", c.particles, rec.body_triangles, c.stop_reason.c_str(),
                format_fixed(c.simulated_s, 2).c_str(), format_fixed(c.wall_s, 2).c_str(),
                c.wall_s < kTargetWallS ? "under the target" : "over the target");
    for (const auto& s : c.stages)
      std::printf("  %-9s %7s s wall %6s s simulated\n", s.name.c_str(), format_fixed(s.wall_s, 2).c_str(),
                  format_fixed(s.simulated_s, 2).c_str());
    std::string prof;
    for (const auto& [name, sec] : c.effect_seconds) prof += "  " + name + " " + format_fixed(sec, 2);
    std::printf("  per effect (s):%s\n", prof.c_str());
    std::printf("  seams %d/%d, penetration %s mm, %d crossing triangle pairs: %s\n", closed, pairs,
                format_fixed(c.max_penetration * 1000, 2).c_str(), c.triangle_intersections,
                c.passed() ? "passed" : "FAILED");
    std::fflush(stdout);
  }, threads);
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& r : records) list.push_back(to_json(r));
    print_json(list);
  }
  return all_passed ? kOk : kCheckFailed;
}

}  // namespace vgd::cli
