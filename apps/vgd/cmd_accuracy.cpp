// vgd bench accuracy [--quick] (issue 7): what accuracy costs in time.
//
// Problems with a known answer, every integrator at several steps (fixed-step
// methods) or tolerances (BDF), both cloth models, one or two resolutions:
//
//   flag     the seed's flag in its gusty wind (data/scenes/flag.json) for 0.5 s
//            (over 2 s the flapping flag forgets its start: every method ends
//            hundreds of mm from any other, docs/accuracy-vs-time.md);
//            reference: RK4 at 1/32 of its stability limit
//   hanging  a square hanging from two corners (data/scenes/hanging-cloth.json)
//            settling towards its static equilibrium for 4 s; reference: BDF
//            of order 5 at rtol 1e-8 (a converged fine-tolerance solve)
//
// Error: the largest distance (mm) of any particle from the reference at the
// final time. CPU time: std::clock of the run (1 thread). Counts: IntegratorStats.
// A run the engine refuses before it starts (an explicit step above the
// stability limit) is marked refused; one stopped by a blow-up, failed.
//
// Writes accuracy.csv and one work-precision diagram (error against CPU time,
// log–log, one curve per method, the Pareto front ringed) per problem × model
// × resolution: work-precision-<problem>-<model>-<resolution>.png.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/render/image.hpp"
#include "vgd/scene/build.hpp"
#include "vgd/scene/data.hpp"
#include "vgd/scene/json.hpp"
#include "vgd/scene/quality.hpp"
#include "vgd/sim/run.hpp"

namespace vgd::cli {

namespace {

namespace scene = vgd::scene;
namespace sim = vgd::sim;

struct Row {
  std::string problem, model, integrator;
  double step_or_tol = 0;  // s for fixed-step methods, rtol for BDF
  int resolution = 0;      // particles along the cloth's first grid direction
  double error_mm = std::numeric_limits<double>::quiet_NaN();
  double cpu_s = 0;
  long rhs = 0, jac = 0;
  bool refused = false;
  std::string status = "ok", message;  // ok, refused, failed, unavailable
};

// The problem `name` with `model` at `resolution` particles along u.
scene::SceneDef problem(const std::string& name, scene::ClothModel model, int resolution, double duration) {
  scene::SceneDef def = scene::load_scene(scene::shipped_scene(name == "flag" ? "flag" : "hanging-cloth"));
  def.outputs.clear();
  def.run.duration = duration;
  auto& c = def.cloth.front();
  c.model = model;
  const double ratio = static_cast<double>(c.grid->nv) / c.grid->nu;
  c.grid->nv = std::max(2, static_cast<int>(std::lround(resolution * ratio)));
  c.grid->nu = resolution;
  if (name == "flag") {
    // The seed's flag material without its Provot limit: a projection after
    // every step makes the trajectory depend on the step, so no step size
    // converges to a reference (docs/accuracy-vs-time.md).
    scene::MaterialDef m = scene::load_xvc_material(scene::data_file("materials/seed-flag.xvc"), "seed-flag");
    m.mass_spring->max_strain = 0.0;
    def.materials[c.material] = scene::MaterialSource{{}, {}, m};
  }
  return def;
}

struct Outcome {
  sim::VecX x;  // final positions (m), full particle set
  Row row;
};

// One run of `def` with `settings`, 1 thread; the integrator's step for
// fixed-step methods is settings.step as given (no sub-stepping).
Outcome run_once(const scene::SceneDef& def, sim::IntegratorSettings settings) {
  Outcome out;
  out.row.integrator = sim::to_string(settings.method);
  out.row.step_or_tol = settings.method == sim::Method::bdf ? settings.rtol : settings.step;
  scene::Scene s = scene::build(def);
  auto& sys = *s.system;
  settings.auto_substep = false;
  std::unique_ptr<sim::Integrator> integ;
  sim::State st = sim::initial_state(sys.model());
  const std::clock_t c0 = std::clock();
  try {
    integ = sim::make_integrator(settings);
    sys.apply_prescribed(st);
    integ->prepare(sys, st);
  } catch (const sim::SimulationError& e) {
    out.row.refused = true;
    out.row.status = "refused";
    out.row.message = e.what();
    return out;
  }
  try {
    const int frames = static_cast<int>(std::floor(def.run.duration * def.run.fps + 1e-9));
    for (int k = 1; k <= frames; ++k) integ->advance(sys, st, k / def.run.fps);
    out.x = sys.expand(st.x);
  } catch (const sim::SimulationError& e) {
    out.row.status = "failed";
    out.row.message = e.what();
  }
  out.row.cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  out.row.rhs = integ->stats().rhs_evaluations;
  out.row.jac = integ->stats().jacobian_evaluations;
  return out;
}

double max_distance_mm(const sim::VecX& a, const sim::VecX& b) {
  double d = 0.0;
  for (int i = 0; i < a.size() / 3; ++i) d = std::max(d, (sim::at(a, i) - sim::at(b, i)).norm());
  return 1000.0 * d;
}

// ---- a small PNG plotter (log–log work-precision diagrams) -----------------------

// A 3 × 5 pixel font: rows top to bottom, '1' = ink.
const std::map<char, const char*>& font() {
  static const std::map<char, const char*> f{
      {'0', "111101101101111"}, {'1', "010110010010111"}, {'2', "111001111100111"}, {'3', "111001111001111"},
      {'4', "101101111001001"}, {'5', "111100111001111"}, {'6', "111100111101111"}, {'7', "111001001001001"},
      {'8', "111101111101111"}, {'9', "111101111001111"}, {'A', "010101111101101"}, {'B', "110101110101110"},
      {'C', "011100100100011"}, {'D', "110101101101110"}, {'E', "111100110100111"}, {'F', "111100110100100"},
      {'G', "011100101101011"}, {'H', "101101111101101"}, {'I', "111010010010111"}, {'J', "001001001101010"},
      {'K', "101101110101101"}, {'L', "100100100100111"}, {'M', "101111111101101"}, {'N', "110101101101101"},
      {'O', "010101101101010"}, {'P', "110101110100100"}, {'Q', "010101101110011"}, {'R', "110101110101101"},
      {'S', "011100010001110"}, {'T', "111010010010010"}, {'U', "101101101101111"}, {'V', "101101101101010"},
      {'W', "101101111111101"}, {'X', "101101010101101"}, {'Y', "101101010010010"}, {'Z', "111001010100111"},
      {'-', "000000111000000"}, {'.', "000000000000010"}, {'+', "000010111010000"}, {'(', "001010010010001"},
      {')', "100010010010100"}, {'/', "001001010100100"}, {'=', "000111000111000"}, {':', "000010000010000"},
      {'x', "000101010101000"}};
  return f;
}

using Rgb = std::array<std::uint8_t, 3>;

struct Canvas {
  render::Image img;
  explicit Canvas(int w, int h) : img(w, h, {255, 255, 255, 255}) {}
  void dot(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    auto* p = img.pixel(x, y);
    p[0] = c[0], p[1] = c[1], p[2] = c[2];
  }
  void box(int x, int y, int r, Rgb c) {
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) dot(x + dx, y + dy, c);
  }
  void line(int x0, int y0, int x1, int y1, Rgb c, int width = 1) {
    const int n = std::max({std::abs(x1 - x0), std::abs(y1 - y0), 1});
    for (int k = 0; k <= n; ++k) {
      const int x = x0 + (x1 - x0) * k / n, y = y0 + (y1 - y0) * k / n;
      box(x, y, width / 2, c);
    }
  }
  void ring(int x, int y, int r, Rgb c) {
    for (int a = 0; a < 360; a += 3) {
      const double t = a * 3.14159265358979 / 180;
      box(x + static_cast<int>(std::lround(r * std::cos(t))), y + static_cast<int>(std::lround(r * std::sin(t))), 0, c);
    }
  }
  // Text in the 3 × 5 font at `scale` pixels per font pixel; lower case drawn as upper.
  void text(int x, int y, const std::string& s, Rgb c, int scale = 2) {
    for (char ch : s) {
      const char u = ch == 'x' ? 'x' : static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      const auto it = font().find(u);
      if (it != font().end())
        for (int r = 0; r < 5; ++r)
          for (int q = 0; q < 3; ++q)
            if (it->second[3 * r + q] == '1')
              for (int dy = 0; dy < scale; ++dy)
                for (int dx = 0; dx < scale; ++dx) dot(x + q * scale + dx, y + r * scale + dy, c);
      x += 4 * scale;
    }
  }
};

Rgb colour(const std::string& method) {
  if (method == "symplectic-euler") return {213, 94, 0};
  if (method == "midpoint") return {0, 158, 115};
  if (method == "rk4") return {0, 114, 178};
  if (method == "implicit-euler") return {204, 121, 167};
  return {230, 159, 0};  // bdf
}

// True for the rows no other row beats in both error and CPU time.
std::vector<bool> pareto(const std::vector<const Row*>& rows) {
  std::vector<bool> front(rows.size(), true);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows.size(); ++j)
      if (i != j && rows[j]->cpu_s <= rows[i]->cpu_s && rows[j]->error_mm <= rows[i]->error_mm &&
          (rows[j]->cpu_s < rows[i]->cpu_s || rows[j]->error_mm < rows[i]->error_mm))
        front[i] = false;
  return front;
}

// One work-precision diagram of finished runs (error > 0).
void plot(const std::string& title, const std::vector<const Row*>& rows, const std::filesystem::path& file) {
  const int W = 900, H = 620, left = 90, right = 220, top = 50, bottom = 70;
  Canvas cv(W, H);
  const int pw = W - left - right, ph = H - top - bottom;
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const Row* r : rows) {
    xmin = std::min(xmin, std::log10(std::max(r->cpu_s, 1e-4))), xmax = std::max(xmax, std::log10(std::max(r->cpu_s, 1e-4)));
    ymin = std::min(ymin, std::log10(r->error_mm)), ymax = std::max(ymax, std::log10(r->error_mm));
  }
  xmin = std::floor(xmin), xmax = std::max(std::ceil(xmax), xmin + 1);
  ymin = std::floor(ymin), ymax = std::max(std::ceil(ymax), ymin + 1);
  auto px = [&](double cpu) {
    return left + static_cast<int>(std::lround((std::log10(std::max(cpu, 1e-4)) - xmin) / (xmax - xmin) * pw));
  };
  auto py = [&](double err) { return top + ph - static_cast<int>(std::lround((std::log10(err) - ymin) / (ymax - ymin) * ph)); };
  const Rgb ink{0, 0, 0}, grid{220, 220, 220};
  // Decade grid and labels.
  for (int e = static_cast<int>(xmin); e <= static_cast<int>(xmax); ++e) {
    const int x = left + static_cast<int>(std::lround((e - xmin) / (xmax - xmin) * pw));
    cv.line(x, top, x, top + ph, grid);
    cv.text(x - 14, top + ph + 8, "1E" + std::to_string(e), ink);
  }
  for (int e = static_cast<int>(ymin); e <= static_cast<int>(ymax); ++e) {
    const int y = top + ph - static_cast<int>(std::lround((e - ymin) / (ymax - ymin) * ph));
    cv.line(left, y, left + pw, y, grid);
    cv.text(left - 50, y - 5, "1E" + std::to_string(e), ink);
  }
  cv.line(left, top, left, top + ph, ink);
  cv.line(left, top + ph, left + pw, top + ph, ink);
  cv.text(left, 15, title, ink, 3);
  cv.text(left + pw / 2 - 60, H - 30, "CPU TIME (S)", ink);
  cv.text(8, top - 25, "ERROR (MM)", ink);
  // One curve per method, in the order of its step or tolerance.
  std::map<std::string, std::vector<const Row*>> by_method;
  for (const Row* r : rows) by_method[r->integrator].push_back(r);
  int legend = top + 10;
  for (auto& [method, list] : by_method) {
    std::sort(list.begin(), list.end(), [](const Row* a, const Row* b) { return a->step_or_tol > b->step_or_tol; });
    const Rgb c = colour(method);
    for (std::size_t k = 0; k + 1 < list.size(); ++k)
      cv.line(px(list[k]->cpu_s), py(list[k]->error_mm), px(list[k + 1]->cpu_s), py(list[k + 1]->error_mm), c, 2);
    for (const Row* r : list) cv.box(px(r->cpu_s), py(r->error_mm), 3, c);
    cv.line(left + pw + 20, legend + 4, left + pw + 45, legend + 4, c, 3);
    cv.text(left + pw + 52, legend, method, ink);
    legend += 22;
  }
  const auto front = pareto(rows);
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (front[i]) cv.ring(px(rows[i]->cpu_s), py(rows[i]->error_mm), 8, ink);
  cv.ring(left + pw + 32, legend + 6, 8, ink);
  cv.text(left + pw + 52, legend + 1, "PARETO FRONT", ink);
  render::write_png(cv.img, file);
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace

// `vgd bench accuracy`: see the top of this file. Returns an exit code.
int bench_accuracy(bool quick, bool json, const std::filesystem::path& out_dir) {
  omp_set_num_threads(1);
  std::filesystem::create_directories(out_dir);
  std::vector<Row> rows;
  struct Case {
    std::string name;
    double duration;
    std::vector<int> resolutions;
  };
  std::vector<Case> cases(2);
  cases[0].name = "flag", cases[1].name = "hanging";
  cases[0].duration = 0.5, cases[1].duration = quick ? 1.0 : 4.0;
  cases[0].resolutions = quick ? std::vector<int>{10} : std::vector<int>{15, 30};
  cases[1].resolutions = quick ? std::vector<int>{7} : std::vector<int>{9, 17};
  const std::vector<double> fractions = quick ? std::vector<double>{2.0, 1.0, 0.25} : std::vector<double>{2.0, 1.0, 0.5, 0.25, 0.125};
  const std::vector<double> implicit_steps = quick ? std::vector<double>{0.01, 0.0025} : std::vector<double>{0.02, 0.01, 0.005, 0.0025, 0.00125};
  const std::vector<double> tolerances = quick ? std::vector<double>{1e-3, 1e-5} : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
  if (!json)
    std::printf("%-8s %-15s %4s %-17s %10s %12s %9s %9s %8s  %s\n", "problem", "model", "res", "integrator", "step/tol",
                "error mm", "cpu s", "RHS", "Jac", "status");
  for (const auto& cs : cases)
    for (const auto model : {scene::ClothModel::mass_spring, scene::ClothModel::strain_rosette})
      for (const int res : cs.resolutions) {
        const scene::SceneDef def = problem(cs.name, model, res, cs.duration);
        const std::string model_name = scene::to_string(model);
        auto finish = [&](Row r) {
          r.problem = cs.name, r.model = model_name, r.resolution = res;
          if (!json) {
            std::printf("%-8s %-15s %4d %-17s %10.3g %12.4g %9.3f %9ld %8ld  %s%s%s\n", r.problem.c_str(),
                        r.model.c_str(), r.resolution, r.integrator.c_str(), r.step_or_tol, r.error_mm, r.cpu_s, r.rhs,
                        r.jac, r.status.c_str(), r.message.empty() ? "" : ": ", r.message.substr(0, 70).c_str());
            std::fflush(stdout);
          }
          rows.push_back(std::move(r));
        };
        // The explicit stability limits of this system.
        scene::Scene probe = scene::build(def);
        const sim::Stiffness stiff = probe.system->stiffness();
        // The reference.
        sim::IntegratorSettings ref = probe.integrator;
        if (cs.name == "flag") {
          ref.method = sim::Method::rk4;
          ref.step = sim::stability_limit(sim::Method::rk4, stiff) / 32;
        } else {
          ref.method = sim::Method::bdf;
          ref.rtol = 1e-8;
          ref.atol = 1e-10;
          // Order 5 for the reference: the settling cloth is smooth, and at
          // 1e-8 the default order 2 (kept for stability) is itself off by
          // more than the errors measured against it.
          ref.max_order = 5;
        }
        const Outcome reference = run_once(def, ref);
        Row rr = reference.row;
        rr.integrator = "reference-" + rr.integrator;
        rr.error_mm = 0.0;
        const bool have_ref = reference.row.status == "ok";
        finish(rr);
        if (!have_ref) continue;
        // Every method at its steps or tolerances.
        for (const auto method : {sim::Method::symplectic_euler, sim::Method::midpoint, sim::Method::rk4,
                                  sim::Method::implicit_euler, sim::Method::bdf}) {
          std::vector<sim::IntegratorSettings> runs;
          sim::IntegratorSettings st = probe.integrator;
          st.method = method;
          if (sim::is_explicit(method)) {
            const double limit = sim::stability_limit(method, stiff) * st.safety;
            // 2× the raw limit (to be refused), then fractions of the safe limit.
            for (const double f : fractions) st.step = f > 1 ? limit / st.safety * f : limit * f, runs.push_back(st);
          } else if (method == sim::Method::implicit_euler) {
            st.cg_tolerance = 1e-8;
            for (const double h : implicit_steps) st.step = h, runs.push_back(st);
          } else {
            for (const double tol : tolerances) st.rtol = tol, st.atol = tol * 1e-2, runs.push_back(st);
          }
          for (const auto& settings : runs) {
            Outcome o = run_once(def, settings);
            if (o.row.status == "ok") o.row.error_mm = max_distance_mm(o.x, reference.x);
            finish(std::move(o.row));
          }
        }
        // The quality presets (scene/quality.hpp) as a scene or --quality
        // would run them: an explicit preset's step is its fraction of the limit.
        for (const auto q : {scene::Quality::preview, scene::Quality::standard, scene::Quality::precise}) {
          sim::IntegratorSettings st = scene::quality_integrator(q, scene::has_contact(def.effects)).settings;
          st.step = sim::is_explicit(st.method) ? sim::stability_limit(st.method, stiff) * st.safety
                                                : 1.0 / (def.run.fps * 4);
          Outcome o = run_once(def, st);
          if (o.row.status == "ok") o.row.error_mm = max_distance_mm(o.x, reference.x);
          o.row.integrator = std::string("preset-") + scene::to_string(q);
          finish(std::move(o.row));
        }
      }
  omp_set_num_threads(std::max(1, omp_get_num_procs()));

  // CSV: one row per run.
  std::ostringstream csv;
  csv << "problem,model,integrator,step_or_tol,resolution,error_mm,cpu_s,rhs_evals,jac_evals,refused,status\n";
  for (const auto& r : rows)
    csv << r.problem << ',' << r.model << ',' << r.integrator << ',' << csv_number(r.step_or_tol) << ',' << r.resolution
        << ',' << csv_number(r.error_mm) << ',' << csv_number(r.cpu_s) << ',' << r.rhs << ',' << r.jac << ','
        << (r.refused ? 1 : 0) << ',' << r.status << '\n';
  vgd::write_file_atomic(out_dir / "accuracy.csv", csv.str());

  // One diagram per problem × model × resolution, of the runs that finished.
  std::map<std::string, std::vector<const Row*>> groups;
  for (const auto& r : rows)
    if (r.status == "ok" && r.error_mm > 0 && r.integrator.rfind("reference", 0) != 0 &&
        r.integrator.rfind("preset", 0) != 0)  // a preset is one of the methods' points
      groups[r.problem + "-" + r.model + "-" + std::to_string(r.resolution)].push_back(&r);
  std::vector<std::string> files;
  for (const auto& [key, list] : groups) {
    const auto file = out_dir / ("work-precision-" + key + ".png");
    plot(key, list, file);
    files.push_back(file.string());
  }
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& r : rows)
      list.push_back({{"problem", r.problem}, {"model", r.model}, {"integrator", r.integrator},
                      {"step_or_tol", r.step_or_tol}, {"resolution", r.resolution},
                      {"error_mm", std::isfinite(r.error_mm) ? nlohmann::json(r.error_mm) : nlohmann::json()},
                      {"cpu_s", r.cpu_s}, {"rhs_evals", r.rhs}, {"jac_evals", r.jac}, {"refused", r.refused},
                      {"status", r.status}, {"message", r.message}});
    print_json(list);
  } else {
    std::printf("\nwrote %s\n", (out_dir / "accuracy.csv").string().c_str());
    for (const auto& f : files) std::printf("wrote %s\n", f.c_str());
  }
  return kOk;
}

}  // namespace vgd::cli
