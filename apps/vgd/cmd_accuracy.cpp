// vgd bench accuracy: error against CPU time for every integrator on problems
// with a known answer (the study is study/accuracy.hpp; this prints it).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli.hpp"
#include "vgd/study/accuracy.hpp"

namespace vgd::cli {

// `vgd bench accuracy`. Returns an exit code.
int bench_accuracy(bool quick, bool json, const std::filesystem::path& out_dir, const std::vector<std::string>& problems) {
  if (!json)
    std::printf("%-10s %-15s %4s %-17s %10s %12s %9s %9s %8s  %s\n", "problem", "model", "res", "integrator", "step/tol",
                "error mm", "cpu s", "RHS", "Jac", "status");
  auto print_row = [&](const study::AccuracyRow& r) {
    if (json) return;
    std::printf("%-10s %-15s %4d %-17s %10.3g %12.4g %9.3f %9ld %8ld  %s%s%s%s\n", r.problem.c_str(), r.model.c_str(),
                r.resolution, r.integrator.c_str(), r.step_or_tol, r.error_mm, r.cpu_s, r.rhs, r.jac, r.status.c_str(),
                r.resolved == 0 ? " unresolved (< 2x the reference's error)" : "", r.message.empty() ? "" : ": ",
                r.message.substr(0, 70).c_str());
    std::fflush(stdout);
  };
  const study::AccuracyStudy s = study::run_accuracy({quick, problems}, print_row);
  const auto files = study::write_accuracy(s, out_dir);
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& r : s.rows)
      list.push_back({{"problem", r.problem}, {"model", r.model}, {"integrator", r.integrator},
                      {"step_or_tol", r.step_or_tol}, {"resolution", r.resolution},
                      {"error_mm", std::isfinite(r.error_mm) ? nlohmann::json(r.error_mm) : nlohmann::json()},
                      {"cpu_s", r.cpu_s}, {"rhs_evals", r.rhs}, {"jac_evals", r.jac}, {"refused", r.refused},
                      {"status", r.status}, {"message", r.message},
                      {"resolved", r.resolved < 0 ? nlohmann::json() : nlohmann::json(r.resolved == 1)}});
    print_json(list);
  } else {
    std::printf("\nwrote %s\n", (out_dir / "accuracy.csv").string().c_str());
    for (const auto& f : files) std::printf("wrote %s\n", f.string().c_str());
  }
  return kOk;
}

}  // namespace vgd::cli
