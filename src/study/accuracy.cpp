// The accuracy study (study/accuracy.hpp, docs/accuracy-vs-time.md).
#include "vgd/study/accuracy.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <sstream>

#include "vgd/core/data.hpp"
#include "vgd/core/file.hpp"
#include "vgd/lab/lab.hpp"
#include "vgd/scene/build.hpp"
#include "vgd/scene/json.hpp"
#include "vgd/scene/quality.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/bending.hpp"
#include "vgd/sim/effects/strain_rosette.hpp"
#include "vgd/sim/run.hpp"
#include "vgd/study/plot.hpp"

namespace vgd::study {

namespace {

// The shipped-scene problem `name` (flag, hanging, drape) with `model` at
// `resolution` particles along u.
scene::SceneDef problem(const std::string& name, scene::ClothModel model, int resolution, double duration) {
  const std::string file = name == "flag" ? "flag" : name == "drape" ? "drape-sphere" : "hanging-cloth";
  scene::SceneDef def = scene::load_scene(vgd::shipped_scene(file));
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
    scene::MaterialDef m = scene::load_xvc_material(vgd::data_file("materials/seed-flag.xvc"), "seed-flag");
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
  scene::MaterialDef mat = scene::load_xvc_material(vgd::data_file("materials/denim.xvc"), "denim");
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
  const lab::Elastica e = lab::tip_load_elastica(kCantileverK);
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
  AccuracyRow row;
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

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace

AccuracyStudy run_accuracy(const AccuracyOptions& options, const std::function<void(const AccuracyRow&)>& on_row) {
  const bool quick = options.quick;
  const std::vector<std::string>& problems = options.problems;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  AccuracyStudy study;
  std::vector<AccuracyRow>& rows = study.rows;
  std::map<std::string, double>& ref_errors = study.reference_errors;
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
  for (const auto& cs : cases)
    for (const auto model : cs.models)
      for (const int res : cs.resolutions) {
        const Setup setup = cs.name == "cantilever" ? cantilever_setup(res - 2, cs.duration)
                                                    : scene_setup(problem(cs.name, model, res, cs.duration));
        const std::string model_name = scene::to_string(model);
        // The reference's own estimated error (mm), where estimated (drape).
        double ref_error = std::numeric_limits<double>::quiet_NaN();
        auto finish = [&](AccuracyRow r) {
          r.problem = cs.name, r.model = model_name, r.resolution = res;
          if (std::isfinite(ref_error) && r.status == "ok" && std::isfinite(r.error_mm) &&
              r.integrator.rfind("reference", 0) != 0)
            r.resolved = r.error_mm >= 2 * ref_error ? 1 : 0;
          if (on_row) on_row(r);
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
          AccuracyRow rr = reference.row;
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
  omp_set_num_threads(threads);
  return study;
}

std::string accuracy_csv(const AccuracyStudy& study) {
  std::ostringstream csv;
  csv << "problem,model,integrator,step_or_tol,resolution,error_mm,cpu_s,rhs_evals,jac_evals,refused,status,resolved\n";
  for (const auto& r : study.rows)
    csv << r.problem << ',' << r.model << ',' << r.integrator << ',' << csv_number(r.step_or_tol) << ',' << r.resolution
        << ',' << csv_number(r.error_mm) << ',' << csv_number(r.cpu_s) << ',' << r.rhs << ',' << r.jac << ','
        << (r.refused ? 1 : 0) << ',' << r.status << ',' << (r.resolved < 0 ? "" : std::to_string(r.resolved)) << '\n';
  return csv.str();
}

std::vector<std::filesystem::path> write_accuracy(const AccuracyStudy& study, const std::filesystem::path& out_dir) {
  std::filesystem::create_directories(out_dir);
  vgd::write_file_atomic(out_dir / "accuracy.csv", accuracy_csv(study));
  // One diagram per problem × model × resolution, of the runs that finished.
  std::map<std::string, std::vector<PlotPoint>> groups;
  for (const auto& r : study.rows)
    if (r.status == "ok" && r.error_mm > 0 && r.integrator.rfind("reference", 0) != 0 &&
        r.integrator.rfind("preset", 0) != 0)  // a preset is one of the methods' points
      groups[r.problem + "-" + r.model + "-" + std::to_string(r.resolution)].push_back(
          {r.integrator, r.step_or_tol, r.cpu_s, r.error_mm, r.resolved == 0});
  std::vector<std::filesystem::path> files;
  for (const auto& [key, list] : groups) {
    const auto file = out_dir / ("work-precision-" + key + ".png");
    const auto e = study.reference_errors.find(key);
    plot_work_precision(key, list, file,
                        e == study.reference_errors.end() ? std::numeric_limits<double>::quiet_NaN() : 2 * e->second);
    files.push_back(file);
  }
  return files;
}

std::vector<std::string> accuracy_problems() { return {"flag", "hanging", "cantilever", "drape"}; }
}  // namespace vgd::study
