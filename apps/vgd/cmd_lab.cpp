// vgd lab: one virtual textile test on a fabric (docs/fabric-lab.md):
// builds the specimen, runs it to static equilibrium with the chosen cloth
// model, prints measured against the analytic reference, writes a CSV.
// `vgd lab all` runs every test and writes a Markdown report; `vgd lab fit`
// fits a model's parameters to measurements and writes a MATERIAL.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <chrono>
#include <memory>

#include "cli.hpp"
#include "vgd/core/file.hpp"
#include "vgd/render/image.hpp"
#include "vgd/lab/lab.hpp"
#include "vgd/lab/fit.hpp"

namespace cmd_lab {
namespace {

struct Options {
  std::string test, measurements, material, model = "rosette", out_dir;
  double angle = 0.0, resolution_mm = 5.0, drape_resolution_mm = 0.0;
  bool json = false, no_poisson = false;
  std::size_t max_rows = vgd::lab::kMaxMeasurements;
  CLI::Option* angle_opt = nullptr;
};

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json to_json(const vgd::lab::LabResult& r, const vgd::lab::LabSpec& spec) {
  auto points = nlohmann::json::array();
  for (const auto& p : r.points)
    points.push_back({{"quantity", p.quantity},
                      {"x", p.x},
                      {"measured", number(p.measured)},
                      {"expected", number(p.expected)},
                      {"rel_error", number(p.rel_error)}});
  return {{"test", r.test},
          {"material", r.material},
          {"model", r.model},
          {"x", r.x_name},
          {"resolution_m", spec.resolution},
          {"poisson_free", spec.poisson_free},
          {"cells_along", r.cells_along},
          {"cells_across", r.cells_across},
          {"points", points},
          {"max_rel_error", number(r.max_rel_error)},
          {"wall_s", r.wall_s},
          {"notes", r.notes}};
}

// A plain plot, one panel per quantity: the reference as a grey polyline
// through the expected values, the measurements as coloured squares. No text:
// the CSV beside it holds the numbers.
vgd::render::Image plot(const vgd::lab::LabResult& r) {
  std::vector<std::string> quantities;
  for (const auto& p : r.points)
    if (std::find(quantities.begin(), quantities.end(), p.quantity) == quantities.end())
      quantities.push_back(p.quantity);
  constexpr int kWidth = 640, kPanel = 240, kMargin = 24;
  vgd::render::Image img(kWidth, kPanel * static_cast<int>(quantities.size()), {255, 255, 255, 255});
  auto put = [&](int x, int y, std::array<std::uint8_t, 3> c) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    auto* px = img.pixel(x, y);
    px[0] = c[0], px[1] = c[1], px[2] = c[2], px[3] = 255;
  };
  auto line = [&](int x0, int y0, int x1, int y1, std::array<std::uint8_t, 3> c) {
    const int n = std::max({std::abs(x1 - x0), std::abs(y1 - y0), 1});
    for (int i = 0; i <= n; ++i) put(x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * i / n, c);
  };
  const std::array<std::array<std::uint8_t, 3>, 4> colours{{{200, 40, 40}, {40, 90, 200}, {30, 150, 60}, {170, 90, 20}}};
  for (std::size_t q = 0; q < quantities.size(); ++q) {
    std::vector<const vgd::lab::LabPoint*> pts;
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto& p : r.points) {
      if (p.quantity != quantities[q]) continue;
      pts.push_back(&p);
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
      for (double y : {p.expected, p.measured})
        if (std::isfinite(y)) y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    if (!(x1 > x0)) x0 -= 1, x1 += 1;
    if (!(y1 > y0)) y0 -= 1, y1 += 1;
    const int top = static_cast<int>(q) * kPanel + kMargin, bottom = (static_cast<int>(q) + 1) * kPanel - kMargin;
    auto px = [&](double x) { return kMargin + static_cast<int>(std::lround((x - x0) / (x1 - x0) * (kWidth - 2 * kMargin))); };
    auto py = [&](double y) { return bottom - static_cast<int>(std::lround((y - y0) / (y1 - y0) * (bottom - top))); };
    const std::array<std::uint8_t, 3> grey{160, 160, 160}, dark{60, 60, 60};
    line(kMargin, top, kMargin, bottom, grey), line(kMargin, bottom, kWidth - kMargin, bottom, grey);
    for (std::size_t i = 1; i < pts.size(); ++i)
      if (std::isfinite(pts[i - 1]->expected) && std::isfinite(pts[i]->expected))
        line(px(pts[i - 1]->x), py(pts[i - 1]->expected), px(pts[i]->x), py(pts[i]->expected), dark);
    for (const auto* p : pts) {
      if (!std::isfinite(p->measured)) continue;
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) put(px(p->x) + dx, py(p->measured) + dy, colours[q % colours.size()]);
    }
  }
  return img;
}

// The drape's view from above (LabResult::top_view), grey.
vgd::render::Image top_view(const vgd::lab::LabResult& r) {
  vgd::render::Image img(r.top_view_size, r.top_view_size, {255, 255, 255, 255});
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      auto* px = img.pixel(x, y);
      px[0] = px[1] = px[2] = r.top_view[std::size_t(y) * r.top_view_size + x];
    }
  return img;
}

// Writes DIR/TEST.csv and DIR/TEST.png (a plot; drape: the view from above).
void write_outputs(const vgd::lab::LabResult& r, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  vgd::lab::write_csv(r, dir / (r.test + ".csv"));
  vgd::render::write_png(r.top_view.empty() ? plot(r) : top_view(r), dir / (r.test + ".png"));
}

int usage(const std::string& problem) {
  std::fprintf(stderr, "vgd lab: %s (see vgd lab --help)\n", problem.c_str());
  return vgd::cli::kUsage;
}

std::string fixed(double v, int decimals) {
  char b[48];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

// vgd lab all: every test, each test's CSV and PNG and DIR/report.md.
int run_all(const Options& o, const vgd::cli::Common& common) {
  namespace lab = vgd::lab;
  if (o.out_dir.empty()) return usage("'all' needs -o DIR for its report");
  const auto model = o.model == "mass-spring" ? vgd::scene::ClothModel::mass_spring
                                              : vgd::scene::ClothModel::strain_rosette;
  // The drape costs about resolution^-3 (shirting: 116 s at 5 mm, 7 s at 10 mm):
  // by default no finer than 10 mm.
  const double drape_mm = o.drape_resolution_mm > 0.0 ? o.drape_resolution_mm : std::max(10.0, o.resolution_mm);
  const auto material = lab::lab_material(o.material);
  const std::filesystem::path dir(o.out_dir);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<lab::ReportEntry> runs;
  for (const auto& spec : lab::all_specs(model, o.resolution_mm / 1000.0, drape_mm / 1000.0, o.no_poisson)) {
    lab::ReportEntry e{spec, lab::run(spec, material), "", ""};
    write_outputs(e.result, dir);
    e.csv = e.result.test + ".csv", e.png = e.result.test + ".png";
    vgd::cli::say(common, e.result.test + ": " + fixed(e.result.wall_s, 2) + " s");
    runs.push_back(std::move(e));
  }
  std::string command = "vgd lab all --material " + o.material + " --model " + o.model + " --resolution " +
                        fixed(o.resolution_mm, 2) + " --drape-resolution " + fixed(drape_mm, 2) +
                        (o.no_poisson ? " --no-poisson" : "") + " -o " + o.out_dir;
  std::vector<std::string> notes{"The drape runs at " + fixed(drape_mm, 2) + " mm, the other tests at " +
                                 fixed(o.resolution_mm, 2) + " mm: the Cusick drape's cost grows about as "
                                 "resolution^-3 (shirting: 7 s at 10 mm, 116 s at 5 mm; docs/fabric-lab.md)."};
  if (model != vgd::scene::ClothModel::strain_rosette)
    notes.push_back("buckling is left out: the mass-spring strip has no bending stiffness at the straight state.");
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  vgd::write_file_atomic(dir / "report.md", lab::report_markdown(runs, command, notes, total));
  if (o.json) {
    auto tests = nlohmann::json::array();
    for (const auto& e : runs) tests.push_back(to_json(e.result, e.spec));
    vgd::cli::print_json({{"tests", tests}, {"total_wall_s", total}, {"report", (dir / "report.md").string()}});
    return vgd::cli::kOk;
  }
  std::printf("%s, %s model: %zu tests, report %s\n", material.name.c_str(), o.model.c_str(), runs.size(),
              (dir / "report.md").string().c_str());
  std::printf("%-16s %15s %9s\n", "test", "max rel error", "wall s");
  for (const auto& e : runs)
    std::printf("%-16s %15.3e %9.2f\n", e.result.test.c_str(), e.result.max_rel_error, e.result.wall_s);
  std::printf("%-16s %15s %9.2f\n", "total", "", total);
  return vgd::cli::kOk;
}

// vgd lab fit: measurements -> fitted MATERIAL, with the residuals.
int run_fit(const Options& o, const vgd::cli::Common& common) {
  namespace lab = vgd::lab;
  if (o.measurements.empty()) return usage("'fit' needs the measurements CSV");
  if (o.out_dir.empty()) return usage("'fit' needs -o FILE.xvc for the fitted MATERIAL");
  const auto model = o.model == "mass-spring" ? vgd::scene::ClothModel::mass_spring
                                              : vgd::scene::ClothModel::strain_rosette;
  const std::filesystem::path out(o.out_dir);
  const auto measurements = lab::read_measurements(o.measurements, o.max_rows);
  const lab::FitResult f = lab::fit(measurements, model, out.stem().string(), o.measurements);
  lab::write_material_xvc(f, out, o.measurements);
  vgd::cli::say(common, "wrote " + out.string() + " (MATERIAL " + out.stem().string() + ")");
  if (o.json) {
    auto residuals = nlohmann::json::array();
    for (const auto& r : f.residuals)
      residuals.push_back({{"line", r.measurement.line},
                           {"quantity", lab::to_string(r.measurement.kind)},
                           {"angle_deg", r.measurement.angle_deg},
                           {"x", r.measurement.x},
                           {"measured", r.measurement.value},
                           {"fitted", number(r.fitted)},
                           {"rel_residual", number(r.rel_residual)}});
    vgd::cli::print_json({{"material", out.stem().string()},
                          {"model", vgd::scene::to_string(model)},
                          {"fitted", f.fitted},
                          {"residuals", residuals},
                          {"rms_rel_residual", f.rms_rel_residual},
                          {"iterations", f.iterations},
                          {"notes", f.notes}});
    return vgd::cli::kOk;
  }
  std::printf("%s fitted to %s (%s model, %d iterations): ", out.string().c_str(), o.measurements.c_str(),
              vgd::scene::to_string(model), f.iterations);
  for (std::size_t k = 0; k < f.fitted.size(); ++k) std::printf("%s%s", k ? ", " : "", f.fitted[k].c_str());
  std::printf("\n");
  for (const auto& n : f.notes) std::printf("  %s\n", n.c_str());
  std::printf("residuals (fitted / measured - 1), SI, by line:\n");
  for (const auto& r : f.residuals) std::printf("  %s\n", lab::describe(r).c_str());
  std::printf("rms relative residual %.3e\n", f.rms_rel_residual);
  return vgd::cli::kOk;
}

vgd::cli::Registrar reg{"lab", 70, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("lab", "Run a virtual textile test on a fabric and compare it with mechanics");
  auto o = std::make_shared<Options>();
  sub->add_option("TEST", o->test,
                  "tip-cantilever, tensile, cantilever, buckling, shear, bending, drape; all (every test and a "
                  "report); fit (fit a MATERIAL to measurements)")
      ->required()
      ->check(CLI::IsMember({"tip-cantilever", "tensile", "cantilever", "buckling", "shear", "bending", "drape", "all",
                             "fit"}));
  sub->add_option("MEASUREMENTS", o->measurements, "fit: the measurements CSV (docs/fabric-lab.md)");
  sub->add_option("--max-rows", o->max_rows, "fit: refuse a CSV with more measurements than this")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--material", o->material, "Fabric: a name in data/materials (shirting) or an XVC file");
  sub->add_option("--model", o->model, "Cloth model: rosette (strain rosette + bending) or mass-spring")
      ->check(CLI::IsMember({"rosette", "strain-rosette", "mass-spring"}));
  o->angle_opt = sub->add_option("--angle", o->angle,
                                 "Specimen axis from the warp, deg (default 0; tensile: every 15 deg from 0 to 90; bending: 0 and 90)")
                     ->check(CLI::Range(0.0, 90.0));
  sub->add_option("--resolution", o->resolution_mm, "Grid spacing along the specimen, mm (default 5)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--drape-resolution", o->drape_resolution_mm,
                  "all: the drape's mesh spacing, mm (default 10, or --resolution when coarser)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--no-poisson", o->no_poisson,
                "Bend the fabric with nu_xy = 0, where strip and plate rigidity agree (docs/fabric-lab.md)");
  sub->add_flag("--json", o->json, "Print the result as JSON on stdout");
  sub->add_option("-o,--output", o->out_dir,
                  "Write TEST.csv (measured vs expected) and TEST.png (a plot; drape: the view from above) into this "
                  "directory; all: also report.md; fit: the fitted MATERIAL's XVC file");
  sub->footer("Exit codes: 0 the test ran (its errors are in the output), 1 bad material, measurements or failed run, "
              "2 usage.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    namespace lab = vgd::lab;
    if (o->test == "fit") return run_fit(*o, common);
    if (o->material.empty()) return usage("--material is required for '" + o->test + "'");
    if (!o->measurements.empty()) return usage("unexpected argument '" + o->measurements + "'");
    if (o->test == "all") {
      if (o->angle_opt->count() > 0) return usage("'all' runs each test at its own angles; --angle is for one test");
      return run_all(*o, common);
    }
    lab::LabSpec spec;
    spec.test = lab::parse_test(o->test);
    spec.model = o->model == "mass-spring" ? vgd::scene::ClothModel::mass_spring
                                           : vgd::scene::ClothModel::strain_rosette;
    spec.resolution = o->resolution_mm / 1000.0;
    spec.poisson_free = o->no_poisson;
    if (o->angle_opt->count() > 0) spec.angle_deg = o->angle;
    else if (spec.test == lab::Test::tensile || spec.test == lab::Test::bending) spec.angle_deg = -1.0;
    const auto material = lab::lab_material(o->material);
    const lab::LabResult r = lab::run(spec, material);
    if (!o->out_dir.empty()) {
      write_outputs(r, o->out_dir);
      vgd::cli::say(common, "wrote " + (std::filesystem::path(o->out_dir) / (r.test + ".csv")).string() + " and " +
                                (std::filesystem::path(o->out_dir) / (r.test + ".png")).string());
    }
    if (o->json) {
      vgd::cli::print_json(to_json(r, spec));
      return vgd::cli::kOk;
    }
    std::printf("%s, %s, %s model, %d x %d cells (%.2f mm)\n", r.test.c_str(), r.material.c_str(), r.model.c_str(),
                r.cells_along, r.cells_across, spec.resolution * 1000);
    for (const auto& n : r.notes) std::printf("  %s\n", n.c_str());
    std::printf("%-18s %10s %14s %14s %11s\n", "quantity", r.x_name.c_str(), "measured", "expected", "rel error");
    for (const auto& p : r.points)
      if (std::isfinite(p.expected))
        std::printf("%-18s %10g %14.7g %14.7g %+10.3e\n", p.quantity.c_str(), p.x, p.measured, p.expected, p.rel_error);
      else  // no reference (a wrinkle count, the drape coefficient)
        std::printf("%-18s %10g %14.7g %14s %10s\n", p.quantity.c_str(), p.x, p.measured, "-", "-");
    std::printf("max |rel error| %.3e, %.3f s\n", r.max_rel_error, r.wall_s);
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_lab
