#pragma once
// Work-precision diagrams as PNG: error against CPU time, log–log, one curve
// per method, the Pareto front ringed. Drawn with a 3 × 5 pixel font into a
// render::Image, so the studies need neither a plotting library nor OpenGL.
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace vgd::study {

struct PlotPoint {
  std::string method;    // one curve per method, in the order of step_or_tol (largest first)
  double step_or_tol = 0;
  double cpu_s = 0;      // x (log); values below 1e-4 s are drawn at 1e-4
  double error_mm = 0;   // y (log), > 0
  bool hollow = false;   // drawn hollow (an unresolved point)
};

// Writes the diagram of `points` to `file` (PNG, 900 × 620). `floor` (mm, NaN:
// none) is drawn as a dashed line labelled "2x reference error".
void plot_work_precision(const std::string& title, const std::vector<PlotPoint>& points,
                         const std::filesystem::path& file,
                         double floor = std::numeric_limits<double>::quiet_NaN());

}  // namespace vgd::study
