// vgd bench accuracy [--quick] (issue 7): what accuracy costs in time.
//
// Problems with a known answer, every integrator at several steps (fixed-step
// methods) or tolerances (BDF), both cloth models, one or two resolutions:
//
//   flag        the seed's flag in its gusty wind (data/scenes/flag.json) for 0.5 s
//               (over 2 s the flapping flag forgets its start: every method ends
//               hundreds of mm from any other, docs/accuracy-vs-time.md);
//               reference: RK4 at 1/32 of its stability limit
//   hanging     a square hanging from two corners (data/scenes/hanging-cloth.json)
//               settling towards its static equilibrium for 4 s; reference: BDF
//               of order 5 at rtol 1e-8 (a converged fine-tolerance solve)
//   cantilever  the lab's tip-loaded strip (vgd lab tip-cantilever): 50 × 10 mm
//               of denim with ν = 0, clamped, a dead tip load k = P L²/B = 2,
//               released straight and damped to rest in 0.5 s; reference: the
//               elastica (scene::lab::tip_load_elastica, no ../shared at run
//               time); strain rosette only (the mass-spring strip has no linear
//               bending stiffness: no elastica to compare with)
//   drape       data/scenes/drape-sphere.json on a coarse grid, the first 0.32 s
//               (falls 0.3 m, lands, its sides still falling); reference: RK4 at
//               1/512 of its stability limit (quick run: 1/128; BDF refuses
//               contact), its own error estimated from RK4 at twice its step
//               (contact makes it first order) and reported as the reference
//               row's error; a row whose error is below twice that estimate is
//               marked unresolved (resolved = 0)
//
// Error: the largest distance (mm) of any particle from the reference at the
// final time; for the cantilever, the distance (mm) of the strip's tip (mean
// of its end column, as the lab measures it) from the elastica's tip.
// CPU time: std::clock of the run (1 thread). Counts: IntegratorStats.
// A run the engine refuses before it starts (an explicit step above the
// stability limit, BDF with contact) is marked refused; one stopped by a
// blow-up, failed.
//
// accuracy.csv's last column, resolved: 1 or 0 where the reference's error is
// estimated (drape), empty elsewhere; the diagrams draw unresolved rows hollow
// below a dashed line at twice the reference's estimated error.
//
// Writes accuracy.csv and one work-precision diagram (error against CPU time,
// log–log, one curve per method, the Pareto front ringed) per problem × model
// × resolution: work-precision-<problem>-<model>-<resolution>.png.
// --problems cantilever,drape runs only the problems listed: regenerating some
// diagrams without the full run's 20 minutes.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
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
#include "vgd/scene/lab.hpp"
#include "vgd/scene/quality.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/bending.hpp"
#include "vgd/sim/effects/strain_rosette.hpp"
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
  // Whether the error exceeds twice the reference's own estimated error
  // (drape): 1 resolved, 0 not, -1 not judged (no estimate, run not finished,
  // the reference itself).
  int resolved = -1;
};

// The shipped-scene problem `name` (flag, hanging, drape) with `model` at
// `resolution` particles along u.
scene::SceneDef problem(const std::string& name, scene::ClothModel model, int resolution, double duration) {
  const std::string file = name == "flag" ? "flag" : name == "drape" ? "drape-sphere" : "hanging-cloth";
  scene::SceneDef def = scene::load_scene(scene::shipped_scene(file));
  def.outputs.clear();
  def.run.duration = duration;
  auto& c = def.cloth.front();
  c.model = model;
  const double ratio = static_cast<double>(c.grid->nv) / c.grid->nu;
  c.grid->nv = std::max(2, static_cast<int>(std::lround(resolution * ratio)));
  c.grid->nu = resolution;
  // The sphere's distance grid at 9.3 mm instead of 5: every run builds its
  // own, and at 5 mm the builds took longer than the quick run's drape runs.
  // Not 10 mm: the grid starts 40 mm (band and two cells) beyond the sphere,
  // so at 10 mm (and 5) its node planes pass through the cloth's x and z of 0,
  // ±150 and ±300 mm, where particles fall straight down and land exactly on
  // a cell face, at which the interpolated normal jumps. Rounding then picked
  // the cell: a start moved by 1e-15 m ended 0.015 mm (9 × 9) and 0.08 mm
  // (17 × 17, mass-spring) away, and RK4 at 1/128, 1/256, 1/512 and 1/1024 of
  // its limit did not converge (successive runs 0.22, 0.08, 0.19 mm apart at
  // 17 × 17, mass-spring; 0.22, 0.23, 0.006 strain rosette). At 9.3 mm every
  // particle of both grids falls at least 0.15 cell from a node plane, a
  // 1e-15 m change of the start moves the end by < 1e-5 mm, and the same
  // steps converge at first order (0.009, 0.005, 0.002 mm; 0.033, 0.016,
  // 0.008 mm).
  if (name == "drape") def.effects.collision->grid.spacing = 0.0093;
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

// A problem at one model and resolution, ready to run: a fresh system per run.
struct Setup {
  std::function<std::unique_ptr<sim::System>()> make;
  double duration = 0.0, fps = 25.0;  // s simulated; frames per s (BDF runs after-step hooks once a frame)
  sim::IntegratorSettings base;       // the scene's settings (tolerances, CG), which every run starts from
  bool contact = false;               // body or self-collision, seams: the presets' contact branch
  // Error (mm) of final positions against a known answer; empty: against the reference run.
  std::function<double(const sim::VecX&)> known_error;
};

Setup scene_setup(const scene::SceneDef& def) {
  Setup s;
  s.make = [def] { return std::move(scene::build(def).system); };
  s.duration = def.run.duration, s.fps = def.run.fps;
  s.base = def.integrator.settings;
  s.contact = scene::has_contact(def.effects);
  return s;
}

// The cantilever's dead tip load: constant forces on the tip column, no
// Jacobian (they do not depend on x or v).
class TipLoad final : public sim::Effect {
 public:
  explicit TipLoad(std::vector<std::pair<int, sim::Vec3>> loads) : loads_(std::move(loads)) {}
  const char* name() const override { return "tip-load"; }
  void add_forces(const sim::Eval&, sim::VecX& f) override {
    for (const auto& [p, force] : loads_) f.segment<3>(3 * p) += force;
  }
  bool add_jacobian(const sim::Eval&, sim::Triplets&, sim::Triplets&) override { return true; }

 private:
  std::vector<std::pair<int, sim::Vec3>> loads_;
};

// The tip-loaded cantilever of `vgd lab tip-cantilever` (scene/lab.cpp builds
// its specimen internally, so it is rebuilt here the same way): a strip along
// the warp, 10 mm wide in two cells, clamped by two held columns (the clamp
// acts mid-cell: `cells` cells of L/(cells + ½) beyond it), ν = 0 so that the
// strip's rigidity is B_warp and the elastica's single EI holds, a dead tip
// load k = P L²/B = 2 (the tip 25 mm down) on the straight strip at t = 0, no
// gravity. Denim and L = 50 mm, half the lab's length (the elastica depends
// only on k): its first mode is ~12× faster than shirting's at 100 mm, so it
// settles within the run at an explicit cost the quick run can afford; the
// mass-proportional drag α = 50/s is about critical for that mode.
constexpr double kCantileverL = 0.05, kCantileverWidth = 0.01, kCantileverK = 2.0, kCantileverAlpha = 50.0;

Setup cantilever_setup(int cells, double duration) {
  scene::MaterialDef mat = scene::load_xvc_material(scene::data_file("materials/denim.xvc"), "denim");
  mat.orthotropic->nu_warp_weft = 0.0;
  mat.orthotropic->nu_weft_warp = sim::kDerived;
  const sim::OrthotropicMaterial o = scene::orthotropic_of(mat);
  const double L = kCantileverL, w = kCantileverWidth, h = L / (cells + 0.5);
  const double B = sim::bending_rigidity_strip(o, 0.0), P = kCantileverK * B / (L * L);  // N/m of width
  const int nu = cells + 2, nv = 3;
  Setup s;
  s.make = [=] {
    sim::Model m = sim::make_grid(nu, nv, h, w / (nv - 1), sim::Vec3(-0.5 * h, 0, 0), sim::Vec3::UnitX(),
                                  sim::Vec3::UnitZ(), 1e-6);
    m.mass = sim::lump_masses(m.uv, m.triangles, mat.density);
    std::vector<std::unique_ptr<sim::Effect>> effects;
    effects.push_back(sim::make_strain_rosette(m, {o}));
    effects.push_back(sim::make_bending(m, {o}));
    effects.push_back(sim::make_viscosity({0.0, kCantileverAlpha}));
    sim::PinDef clamp;
    std::vector<std::pair<int, sim::Vec3>> loads;
    for (int j = 0; j < nv; ++j) {
      clamp.particles.push_back(j * nu), clamp.particles.push_back(j * nu + 1);
      const double share = (j == 0 || j == nv - 1) ? 0.5 : 1.0;  // half at the corners, as the lab
      loads.emplace_back(j * nu + nu - 1, sim::Vec3(0, -P * w / (nv - 1) * share, 0));
    }
    effects.push_back(sim::make_pins(m, clamp));
    effects.push_back(std::make_unique<TipLoad>(std::move(loads)));
    return std::make_unique<sim::System>(std::move(m), std::move(effects));
  };
  s.duration = duration;  // base: the default settings
  const scene::lab::Elastica e = scene::lab::tip_load_elastica(kCantileverK);
  s.known_error = [=](const sim::VecX& x) {
    double u = 0.0, dw = 0.0;  // mean tip shortening and deflection (m)
    for (int j = 0; j < nv; ++j) {
      const int p = j * nu + nu - 1;
      u += (L - x[3 * p]) / nv, dw += -x[3 * p + 1] / nv;
    }
    return 1000.0 * std::hypot(u - e.u_over_L * L, dw - e.w_over_L * L);
  };
  return s;
}

struct Outcome {
  sim::VecX x;  // final positions (m), full particle set
  Row row;
};

// One run of `setup` with `settings`, 1 thread; the integrator's step for
// fixed-step methods is settings.step as given (no sub-stepping).
Outcome run_once(const Setup& setup, sim::IntegratorSettings settings) {
  Outcome out;
  out.row.integrator = sim::to_string(settings.method);
  out.row.step_or_tol = settings.method == sim::Method::bdf ? settings.rtol : settings.step;
  const std::unique_ptr<sim::System> system = setup.make();
  auto& sys = *system;
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
    const int frames = static_cast<int>(std::floor(setup.duration * setup.fps + 1e-9));
    for (int k = 1; k <= frames; ++k) integ->advance(sys, st, k / setup.fps);
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

// One work-precision diagram of finished runs (error > 0). `floor`: twice the
// reference's estimated error (mm, NaN: none), drawn as a dashed line; the
// rows below it (unresolved) as hollow squares.
void plot(const std::string& title, const std::vector<const Row*>& rows, const std::filesystem::path& file,
          double floor = std::numeric_limits<double>::quiet_NaN()) {
  const int W = 900, H = 620, left = 90, right = 220, top = 50, bottom = 70;
  Canvas cv(W, H);
  const int pw = W - left - right, ph = H - top - bottom;
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const Row* r : rows) {
    xmin = std::min(xmin, std::log10(std::max(r->cpu_s, 1e-4))), xmax = std::max(xmax, std::log10(std::max(r->cpu_s, 1e-4)));
    ymin = std::min(ymin, std::log10(r->error_mm)), ymax = std::max(ymax, std::log10(r->error_mm));
  }
  if (floor > 0) ymin = std::min(ymin, std::log10(floor)), ymax = std::max(ymax, std::log10(floor));
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
  if (floor > 0) {
    const Rgb grey{120, 120, 120};
    for (int x = left; x < left + pw; x += 12) cv.line(x, py(floor), std::min(x + 6, left + pw), py(floor), grey);
    cv.text(left + pw - 160, py(floor) - 16, "2X REFERENCE ERROR", grey);
  }
  // One curve per method, in the order of its step or tolerance.
  std::map<std::string, std::vector<const Row*>> by_method;
  for (const Row* r : rows) by_method[r->integrator].push_back(r);
  int legend = top + 10;
  for (auto& [method, list] : by_method) {
    std::sort(list.begin(), list.end(), [](const Row* a, const Row* b) { return a->step_or_tol > b->step_or_tol; });
    const Rgb c = colour(method);
    for (std::size_t k = 0; k + 1 < list.size(); ++k)
      cv.line(px(list[k]->cpu_s), py(list[k]->error_mm), px(list[k + 1]->cpu_s), py(list[k + 1]->error_mm), c, 2);
    for (const Row* r : list) {
      cv.box(px(r->cpu_s), py(r->error_mm), 3, c);
      if (r->resolved == 0) cv.box(px(r->cpu_s), py(r->error_mm), 1, {255, 255, 255});  // hollow: unresolved
    }
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
int bench_accuracy(bool quick, bool json, const std::filesystem::path& out_dir, const std::vector<std::string>& problems) {
  omp_set_num_threads(1);
  std::filesystem::create_directories(out_dir);
  std::vector<Row> rows;
  std::map<std::string, double> ref_errors;  // problem-model-resolution -> the reference's estimated error (mm)
  using Models = std::vector<scene::ClothModel>;
  const Models both{scene::ClothModel::mass_spring, scene::ClothModel::strain_rosette};
  struct Case {
    std::string name;
    double duration;
    std::vector<int> resolutions;  // particles along u (cantilever: along the strip, the two held columns included)
    Models models;
    std::vector<double> fractions;  // of the explicit limits; empty: the default below
  };
  // The cantilever ends at rest, where every stable run sits on the same
  // discrete equilibrium: smaller explicit steps only cost (midpoint at ¼ of
  // its limit would be most of the quick run), so it runs fewer.
  std::vector<Case> cases{
      {"flag", 0.5, quick ? std::vector<int>{10} : std::vector<int>{15, 30}, both, {}},
      {"hanging", quick ? 1.0 : 4.0, quick ? std::vector<int>{7} : std::vector<int>{9, 17}, both, {}},
      // 5, 10 and 20 cells along the strip.
      {"cantilever", 0.5, quick ? std::vector<int>{7} : std::vector<int>{7, 12, 22}, {scene::ClothModel::strain_rosette},
       quick ? std::vector<double>{2.0, 1.0} : std::vector<double>{2.0, 1.0, 0.25}},
      // 0.32 s: landed, the sides still falling. By 0.48 s folds make it as
      // sensitive as the flag (RK4 at 1/64 of its limit 5 mm from 1/256).
      {"drape", 0.32, quick ? std::vector<int>{9} : std::vector<int>{9, 17}, both, {}}};
  if (!problems.empty())
    std::erase_if(cases, [&](const Case& c) { return std::find(problems.begin(), problems.end(), c.name) == problems.end(); });
  const std::vector<double> fractions = quick ? std::vector<double>{2.0, 1.0, 0.25} : std::vector<double>{2.0, 1.0, 0.5, 0.25, 0.125};
  const std::vector<double> implicit_steps = quick ? std::vector<double>{0.01, 0.0025} : std::vector<double>{0.02, 0.01, 0.005, 0.0025, 0.00125};
  const std::vector<double> tolerances = quick ? std::vector<double>{1e-3, 1e-5} : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
  if (!json)
    std::printf("%-10s %-15s %4s %-17s %10s %12s %9s %9s %8s  %s\n", "problem", "model", "res", "integrator", "step/tol",
                "error mm", "cpu s", "RHS", "Jac", "status");
  for (const auto& cs : cases)
    for (const auto model : cs.models)
      for (const int res : cs.resolutions) {
        const Setup setup = cs.name == "cantilever" ? cantilever_setup(res - 2, cs.duration)
                                                    : scene_setup(problem(cs.name, model, res, cs.duration));
        const std::string model_name = scene::to_string(model);
        // The reference's own estimated error (mm), where estimated (drape).
        double ref_error = std::numeric_limits<double>::quiet_NaN();
        auto finish = [&](Row r) {
          r.problem = cs.name, r.model = model_name, r.resolution = res;
          if (std::isfinite(ref_error) && r.status == "ok" && std::isfinite(r.error_mm) &&
              r.integrator.rfind("reference", 0) != 0)
            r.resolved = r.error_mm >= 2 * ref_error ? 1 : 0;
          if (!json) {
            std::printf("%-10s %-15s %4d %-17s %10.3g %12.4g %9.3f %9ld %8ld  %s%s%s%s\n", r.problem.c_str(),
                        r.model.c_str(), r.resolution, r.integrator.c_str(), r.step_or_tol, r.error_mm, r.cpu_s, r.rhs,
                        r.jac, r.status.c_str(), r.resolved == 0 ? " unresolved (< 2x the reference's error)" : "",
                        r.message.empty() ? "" : ": ", r.message.substr(0, 70).c_str());
            std::fflush(stdout);
          }
          rows.push_back(std::move(r));
        };
        // The explicit stability limits of this system.
        const sim::Stiffness stiff = setup.make()->stiffness();
        // The reference: a known answer, or a fine solve.
        Outcome reference;
        if (setup.known_error) {
          reference.row.integrator = "reference-elastica";
          reference.row.error_mm = 0.0;
          finish(reference.row);
        } else {
          sim::IntegratorSettings ref = setup.base;
          if (cs.name == "hanging") {
            ref.method = sim::Method::bdf;
            ref.rtol = 1e-8;
            ref.atol = 1e-10;
            // Order 5 for the reference: the settling cloth is smooth, and at
            // 1e-8 the default order 2 (kept for stability) is itself off by
            // more than the errors measured against it.
            ref.max_order = 5;
          } else {
            // flag: 1/32 of the limit. drape (BDF refuses contact): 1/128 of
            // it in the quick run, 1/512 in the full one (see below).
            ref.method = sim::Method::rk4;
            ref.step = sim::stability_limit(sim::Method::rk4, stiff) / (cs.name == "drape" ? (quick ? 128 : 512) : 32);
          }
          reference = run_once(setup, ref);
          Row rr = reference.row;
          rr.integrator = "reference-" + rr.integrator;
          rr.error_mm = 0.0;
          if (cs.name == "drape" && reference.row.status == "ok") {
            // Contact makes every method first order (a projection after
            // each step), the reference too: x(h) − x* ≈ C h, so its own error
            // is about its distance from a run at twice its step (Richardson,
            // order 1). Measured at 17 × 17: each halving of the step from
            // 1/128 to 1/1024 of the limit halves that distance (÷1.8–2.4
            // mass-spring, ÷2.0 strain rosette); at 9 × 9 the strain
            // rosette's 1/128 lies 0.008 mm from every finer run, which lie
            // within 0.002 mm of each other: there the estimate is an upper
            // bound. A row whose error is below twice the estimate is
            // marked unresolved: its true error could be anything from
            // nearly 0 to three times the estimate.
            sim::IntegratorSettings coarse = ref;
            coarse.step = 2 * ref.step;
            const Outcome check = run_once(setup, coarse);
            if (check.row.status == "ok") {
              ref_error = max_distance_mm(check.x, reference.x);
              rr.error_mm = ref_error;
              ref_errors[cs.name + "-" + model_name + "-" + std::to_string(res)] = ref_error;
              char m[96];
              std::snprintf(m, sizeof m, "its error estimated from RK4 at twice its step (%.3g s CPU)", check.row.cpu_s);
              rr.message = m;
            }
          }
          finish(rr);
          if (reference.row.status != "ok") continue;
        }
        auto error_of = [&](const Outcome& o) {
          return setup.known_error ? setup.known_error(o.x) : max_distance_mm(o.x, reference.x);
        };
        // Every method at its steps or tolerances.
        for (const auto method : {sim::Method::symplectic_euler, sim::Method::midpoint, sim::Method::rk4,
                                  sim::Method::implicit_euler, sim::Method::bdf}) {
          std::vector<sim::IntegratorSettings> runs;
          sim::IntegratorSettings st = setup.base;
          st.method = method;
          if (sim::is_explicit(method)) {
            const double limit = sim::stability_limit(method, stiff) * st.safety;
            // 2× the raw limit (to be refused), then fractions of the safe limit.
            const auto& fs = cs.fractions.empty() ? fractions : cs.fractions;
            for (const double f : fs) st.step = f > 1 ? limit / st.safety * f : limit * f, runs.push_back(st);
          } else if (method == sim::Method::implicit_euler) {
            st.cg_tolerance = 1e-8;
            st.cg_max_iterations = std::max(st.cg_max_iterations, 1000);  // the drape scene caps it at 100
            for (const double h : implicit_steps) st.step = h, runs.push_back(st);
          } else {
            for (const double tol : tolerances) st.rtol = tol, st.atol = tol * 1e-2, runs.push_back(st);
          }
          for (const auto& settings : runs) {
            Outcome o = run_once(setup, settings);
            if (o.row.status == "ok") o.row.error_mm = error_of(o);
            finish(std::move(o.row));
          }
        }
        // The quality presets (scene/quality.hpp) as a scene or --quality
        // would run them: an explicit preset's step is its fraction of the
        // limit, an implicit one's its steps per frame.
        for (const auto q : {scene::Quality::preview, scene::Quality::standard, scene::Quality::precise}) {
          const scene::IntegratorDef preset = scene::quality_integrator(q, setup.contact);
          sim::IntegratorSettings st = preset.settings;
          st.step = sim::is_explicit(st.method) ? sim::stability_limit(st.method, stiff) * st.safety
                                                : 1.0 / (setup.fps * std::max(1, preset.iterations_per_frame));
          Outcome o = run_once(setup, st);
          if (o.row.status == "ok") o.row.error_mm = error_of(o);
          o.row.integrator = std::string("preset-") + scene::to_string(q);
          finish(std::move(o.row));
        }
      }
  omp_set_num_threads(std::max(1, omp_get_num_procs()));

  // CSV: one row per run.
  std::ostringstream csv;
  csv << "problem,model,integrator,step_or_tol,resolution,error_mm,cpu_s,rhs_evals,jac_evals,refused,status,resolved\n";
  for (const auto& r : rows)
    csv << r.problem << ',' << r.model << ',' << r.integrator << ',' << csv_number(r.step_or_tol) << ',' << r.resolution
        << ',' << csv_number(r.error_mm) << ',' << csv_number(r.cpu_s) << ',' << r.rhs << ',' << r.jac << ','
        << (r.refused ? 1 : 0) << ',' << r.status << ',' << (r.resolved < 0 ? "" : std::to_string(r.resolved)) << '\n';
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
    const auto e = ref_errors.find(key);
    plot(key, list, file, e == ref_errors.end() ? std::numeric_limits<double>::quiet_NaN() : 2 * e->second);
    files.push_back(file.string());
  }
  if (json) {
    auto list = nlohmann::json::array();
    for (const auto& r : rows)
      list.push_back({{"problem", r.problem}, {"model", r.model}, {"integrator", r.integrator},
                      {"step_or_tol", r.step_or_tol}, {"resolution", r.resolution},
                      {"error_mm", std::isfinite(r.error_mm) ? nlohmann::json(r.error_mm) : nlohmann::json()},
                      {"cpu_s", r.cpu_s}, {"rhs_evals", r.rhs}, {"jac_evals", r.jac}, {"refused", r.refused},
                      {"status", r.status}, {"message", r.message},
                      {"resolved", r.resolved < 0 ? nlohmann::json() : nlohmann::json(r.resolved == 1)}});
    print_json(list);
  } else {
    std::printf("\nwrote %s\n", (out_dir / "accuracy.csv").string().c_str());
    for (const auto& f : files) std::printf("wrote %s\n", f.c_str());
  }
  return kOk;
}

}  // namespace vgd::cli
