// The benchmarks `vgd bench` prints (study/bench.hpp, docs/performance.md).
#include "vgd/study/bench.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <span>

#include "vgd/core/data.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/dress/drape.hpp"
#include "vgd/dress/dress.hpp"
#include "vgd/mesh/surface_checks.hpp"
#include "vgd/scene/build.hpp"
#include "vgd/scene/json.hpp"
#include "vgd/sim/run.hpp"

namespace vgd::study {

std::vector<int> thread_counts(int only) {
  if (only > 0) return {only};
  const int cores = std::max(1, omp_get_num_procs());
  std::vector<int> t{1};
  if (cores > 1) t.push_back(cores);
  return t;
}

EngineRecord run_engine(const scene::SceneDef& def, sim::Method method, int threads, double budget_s) {
  EngineRecord r;
  r.scene = def.name;
  r.model = scene::to_string(def.cloth.front().model);
  r.integrator = sim::to_string(method);
  r.threads = threads;
  r.effects = scene::effect_names(def);
  if (!scene::model_available(def.cloth.front().model)) {
    r.status = "unavailable";
    r.message = "this build has no " + r.model + " model";
    return r;
  }
  omp_set_num_threads(threads);
  scene::Scene s = dress::build(def);  // a --scene file may hold garments
  sim::IntegratorSettings settings = s.integrator;
  settings.method = method;
  settings.auto_substep = sim::is_explicit(method);  // each explicit method at its own stable step
  std::unique_ptr<sim::Integrator> integ;
  try {
    integ = sim::make_integrator(settings);
  } catch (const sim::SimulationError& e) {
    r.status = "unavailable";
    r.message = e.what();
    return r;
  }
  auto& sys = *s.system;
  r.particles = sys.model().num_particles();
  // What was built: a fabric read from a garment's document may add effects
  // (its strain limit) that the scene file does not list.
  r.effects.clear();
  for (const auto& e : sys.effects()) r.effects.emplace_back(e->name());
  sim::State st = sim::initial_state(sys.model());
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto wall = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  try {
    sys.apply_prescribed(st);
    integ->prepare(sys, st);
    const int frames = static_cast<int>(std::floor(s.run.duration * s.run.fps + 1e-9));
    for (int k = 1; k <= frames; ++k) {
      integ->advance(sys, st, k / s.run.fps);
      if (wall() > budget_s && k < frames) {
        r.status = "partial";
        r.message = "stopped at the wall-time budget of " + format_fixed(budget_s, 0) + " s";
        break;
      }
    }
  } catch (const sim::SimulationError& e) {
    r.status = "failed";
    r.message = e.what();
  }
  r.wall_s = wall();
  r.simulated_s = st.t;
  for (const auto& p : sys.profile()) r.profile.emplace_back(p.name, p.seconds);
  const auto stats = integ->stats();
  r.steps = stats.steps;
  r.rhs = stats.rhs_evaluations;
  r.jacobians = stats.jacobian_evaluations;
  r.step_s = integ->step() > 0 ? integ->step() : (stats.steps > 0 ? st.t / stats.steps : 0.0);
  return r;
}

std::vector<EngineRecord> engine_study(const scene::SceneDef& base, double budget_s,
                                       const std::function<void(const EngineRecord&)>& on_record) {
  const int threads = omp_get_max_threads();
  std::vector<EngineRecord> records;
  auto add = [&](EngineRecord r) {
    if (on_record) on_record(r);
    records.push_back(std::move(r));
  };
  // Every model x integrator x thread count.
  for (const auto model : {scene::ClothModel::mass_spring, scene::ClothModel::strain_rosette}) {
    scene::SceneDef def = base;
    for (auto& c : def.cloth) c.model = model;
    for (const auto method : {sim::Method::symplectic_euler, sim::Method::midpoint, sim::Method::rk4,
                              sim::Method::implicit_euler, sim::Method::bdf})
      for (const int t : thread_counts()) add(run_engine(def, method, t, budget_s));
  }
  // The cost of each listed effect: the scene with it switched off (1 thread).
  auto variant = [&](const std::string& name, const scene::SceneDef& def) {
    EngineRecord r = run_engine(def, def.integrator.settings.method, 1, budget_s);
    r.variant = name;
    add(std::move(r));
  };
  variant("all effects", base);
  if (base.effects.wind) variant("no wind", [&] { auto d = base; d.effects.wind.reset(); return d; }());
  if (base.effects.viscosity) variant("no viscosity", [&] { auto d = base; d.effects.viscosity.reset(); return d; }());
  if (base.effects.gravity) variant("no gravity", [&] { auto d = base; d.effects.gravity.reset(); return d; }());
  if (base.effects.damping) variant("no damping", [&] { auto d = base; d.effects.damping.reset(); return d; }());
  omp_set_num_threads(threads);
  return records;
}

namespace {

// A peer's measurements of Blender 3.4 (Debian's package, implicit mass-spring
// cloth) on this kind of machine: wall seconds per simulated second.
struct Reference {
  const char* scene;
  double one_thread, two_threads;
};
constexpr Reference kBlender[] = {{"drape-sphere", 11.4, 8.1}, {"sew-cylinder", 13.0, 9.0}};
// The same peer's drape-sphere with Blender's self-collision on.
constexpr Reference kBlenderSelf[] = {{"drape-sphere", 13.9, 9.4}};

}  // namespace

SceneRecord run_scene(const std::string& name, int threads, double duration, bool self_collision, bool adapt_threads) {
  SceneRecord r;
  r.scene = name;
  r.threads = threads;
  r.self_collision = self_collision;
  r.adapt_threads = adapt_threads;
  omp_set_num_threads(threads);
  scene::SceneDef def = scene::load_scene(shipped_scene(name));
  if (duration > 0) def.run.duration = duration;
  if (self_collision) def.effects.self_collision = sim::SelfCollisionDef{};
  def.outputs.clear();
  scene::Scene s = scene::build(def);
  auto integ = sim::make_integrator(s.integrator);
  auto& sys = *s.system;
  r.particles = sys.model().num_particles();
  r.body_triangles = s.avatar ? s.avatar->surface.num_triangles() : 0;
  sim::State st = sim::initial_state(sys.model());
  sim::MemorySink frames;
  s.run.adapt_threads = adapt_threads;
  const sim::RunSummary sum = sim::run(sys, *integ, st, s.run, {&frames});
  r.frames_on_fewer_threads = sum.frames_on_fewer_threads;
  r.wall_s = sum.wall_s;
  r.simulated_s = sum.simulated_s;
  r.steps = sum.stats.steps;
  if (!sum.ok) {
    r.status = "failed";
    r.message = sum.error;
  }
  for (const auto& ref : self_collision ? std::span<const Reference>(kBlenderSelf) : std::span<const Reference>(kBlender))
    if (name == ref.scene) r.blender_s = threads > 1 ? ref.two_threads : ref.one_thread;
  if (s.avatar)
    for (const auto& x : frames.frames) {
      std::vector<mesh::Vec3> pts(sys.model().num_particles());
      for (int i = 0; i < sys.model().num_particles(); ++i) pts[i] = sim::at(x, i);
      for (double d : mesh::penetration_depths(s.avatar->surface, pts)) r.max_penetration = std::max(r.max_penetration, d);
    }
  if (!frames.frames.empty()) {
    dress::Certificate c;
    const double merge = def.effects.seams ? def.effects.seams->effect.merge_distance : 0.0;
    dress::measure_state(s, frames.frames.back(), merge, 0.004, true, c);
    for (const auto& seam : c.seams) r.seam_pairs += seam.pairs, r.seams_closed += seam.closed;
    r.crossings = c.triangle_intersections;
  }
  return r;
}

namespace {

// Where a run stood at one frame: enough to split it into phases.
struct Mark {
  double t = 0, wall_s = 0;
  long steps = 0, rhs = 0;
  std::vector<double> seconds;  // per effect (System::profile)
};

Mark mark(const sim::System& sys, const sim::Integrator& integ, double t, double wall_s) {
  Mark m{t, wall_s, integ.stats().steps, integ.stats().rhs_evaluations, {}};
  for (const auto& p : sys.profile()) m.seconds.push_back(p.seconds);
  return m;
}

// The part of a run between two marks.
EffectsRecord phase(const EffectsRecord& base, const std::string& variant, const Mark& a, const Mark& b) {
  EffectsRecord r = base;
  r.variant = variant;
  r.simulated_s = b.t - a.t;
  r.wall_s = b.wall_s - a.wall_s;
  r.steps = b.steps - a.steps;
  r.rhs = b.rhs - a.rhs;
  for (std::size_t i = 0; i < r.profile.size(); ++i) r.profile[i].second = b.seconds[i] - a.seconds[i];
  return r;
}

// Runs `def` for its duration with 1 thread. With `split_at_seams`, returns
// two phases: while the seam effect works, and after it finished (its last
// merge); else one record for the whole run.
std::vector<EffectsRecord> effects_run(const std::string& variant, const scene::SceneDef& def, bool split_at_seams) {
  EffectsRecord r;
  r.scene = def.name;
  r.variant = variant;
  omp_set_num_threads(1);
  scene::Scene s = scene::build(def);
  auto& sys = *s.system;
  auto integ = sim::make_integrator(s.integrator);
  r.particles = sys.model().num_particles();
  for (const auto& p : sys.profile()) {
    r.effects.push_back(p.name);
    r.profile.emplace_back(p.name, 0.0);
  }
  const sim::Effect* seam = nullptr;
  for (const auto& e : sys.effects())
    if (std::string(e->name()) == "seam") seam = e.get();
  sim::State st = sim::initial_state(sys.model());
  std::optional<Mark> closed;
  const sim::RunSummary sum = sim::run(sys, *integ, st, s.run, {}, [&](const sim::Progress& p) {
    if (seam && !closed && seam->finished()) closed = mark(sys, *integ, p.t, p.wall_s);
  });
  if (!sum.ok) {
    r.status = "failed";
    r.message = sum.error;
  }
  const Mark end = mark(sys, *integ, sum.simulated_s, sum.wall_s);
  const Mark start{0.0, 0.0, 0, 0, std::vector<double>(r.profile.size(), 0.0)};
  if (!split_at_seams) return {phase(r, variant, start, end)};
  if (!closed) {
    r.status = "partial";
    r.message = "the seams did not close within " + format_fixed(def.run.duration, 1) + " s";
    return {phase(r, "seams open", start, end)};
  }
  return {phase(r, "seams open", start, *closed), phase(r, "after the last merge", *closed, end)};
}

}  // namespace

std::vector<EffectsRecord> effects_study(bool quick, const std::function<void(const EffectsRecord&)>& on_record) {
  const int threads = omp_get_max_threads();
  std::vector<EffectsRecord> records;
  auto add = [&](std::vector<EffectsRecord> rs) {
    for (auto& r : rs) {
      if (on_record) on_record(r);
      records.push_back(std::move(r));
    }
  };
  auto shipped = [&](const char* name) {
    scene::SceneDef def = scene::load_scene(shipped_scene(name));
    def.outputs.clear();
    if (quick && def.name != "sew-cylinder") def.run.duration = 0.4;
    return def;
  };
  // The flag with and without its wind.
  const scene::SceneDef flag = shipped("flag");
  add(effects_run("with wind", flag, false));
  add(effects_run("no wind", [&] { auto d = flag; d.effects.wind.reset(); return d; }(), false));
  // The drape with and without self-collision.
  const scene::SceneDef drape = shipped("drape-sphere");
  add(effects_run("no self-collision", drape, false));
  add(effects_run("self-collision", [&] { auto d = drape; d.effects.self_collision = sim::SelfCollisionDef{}; return d; }(),
                  false));
  // A static body against one moving (the sphere rising into the cloth at
  // 5 cm/s): a rigid motion keeps the distance grid built once, each query
  // moves into the body's frame.
  add(effects_run("moving sphere", [&] { auto d = drape; d.effects.collision->velocity = sim::Vec3(0, 0.05, 0); return d; }(),
                  false));
  // The sewing scene while its seams work and after the last merge (seam
  // effect gone), and without seams at all.
  scene::SceneDef sew = shipped("sew-cylinder");
  sew.run.duration += 1.0;  // a second after the scene's end, for the closed phase
  add(effects_run("seams", sew, true));
  add(effects_run("no seams listed", [&] { auto d = sew; d.effects.seams.reset(); return d; }(), false));
  omp_set_num_threads(threads);
  return records;
}

std::vector<DressRecord> dress_study(double spacing, const std::string& size, double time_limit,
                                     bool between_particles, const std::function<void(const DressRecord&)>& on_record,
                                     int threads_only) {
  dress::DrapeOptions o;
  o.garment = data_file("garments/a-line-skirt.xvc");
  o.over = {data_file("garments/t-shirt.xvc")};
  o.size = size;
  o.spacing = spacing;
  o.time_limit = time_limit;
  o.between_particles = between_particles;
  const scene::SceneDef def = dress::drape_scene(o);
  const int threads = omp_get_max_threads();
  std::vector<DressRecord> records;
  for (const int t : thread_counts(threads_only)) {
    omp_set_num_threads(t);
    dress::DrapeResult r = dress::run_drape(def, {});
    DressRecord rec{t, std::move(r.certificate),
                    r.scene.avatar ? static_cast<int>(r.scene.avatar->surface.triangles.size()) : 0};
    if (on_record) on_record(rec);
    records.push_back(std::move(rec));
  }
  omp_set_num_threads(threads);
  return records;
}

// ---- robustness ---------------------------------------------------------------------

RobustnessOptions robustness_sweep(bool quick) {
  RobustnessOptions o;
  o.garments = {data_file("garments/t-shirt.xvc"), data_file("garments/a-line-skirt.xvc")};
  if (quick) {
    o.spacings = {0.015, 0.019};
    o.sizes = {"38"};
    o.materials = {""};
    o.models = {scene::ClothModel::mass_spring};
    o.jitters = 1;
    return o;
  }
  o.spacings = {0.012, 0.015, 0.019, 0.025};
  o.sizes = {"34", "36", "38", "40", "42"};
  o.materials = {"", "cotton-jersey.xvc", "denim.xvc"};
  o.models = {scene::ClothModel::mass_spring, scene::ClothModel::strain_rosette};
  return o;
}

namespace {

// The drape scene of one case (throws vgd::Error naming a garment or a
// material file that is not there).
scene::SceneDef case_scene(const RobustnessCase& k, const RobustnessOptions& o) {
  dress::DrapeOptions d;
  d.garment = k.garment;
  d.size = k.size;
  d.spacing = k.spacing;
  d.time_limit = o.time_limit;
  d.between_particles = o.between_particles;
  d.sleeves_first = o.sleeves_first;
  if (!k.material.empty()) d.material_xvc = data_file("materials/" + k.material);
  return dress::drape_scene(d);
}

// The record of one run, and where its particles ended (m, every original particle).
std::pair<RobustnessRecord, sim::VecX> drape_case(const RobustnessCase& k, const RobustnessOptions& o) {
  scene::SceneDef def = case_scene(k, o);
  for (auto& c : def.cloth) c.model = k.model;
  def.run.start_jitter = k.jitter;
  def.run.start_jitter_seed = k.seed;
  RobustnessRecord r;
  r.run = k;
  dress::DrapeResult res = dress::run_drape(def, {});
  r.certificate = std::move(res.certificate);
  const auto failures = r.certificate.failures();
  for (const auto& f : failures) {
    if (r.failure.find(f.kind) != std::string::npos) continue;
    r.failure += (r.failure.empty() ? "" : ", ") + f.kind;
    // Where a run that did not come to rest still moves: the body segments beside it.
    if (f.kind == "no rest" && r.certificate.still_moving && !r.certificate.still_moving->near.empty()) {
      std::string near;
      for (const auto& n : r.certificate.still_moving->near) near += (near.empty() ? "" : "/") + n;
      r.failure += " (" + near + ")";
    }
  }
  r.clean = failures.empty();
  for (const auto& s : r.certificate.strain) r.max_strain = std::max({r.max_strain, s.warp.p95, s.weft.p95});
  for (const auto& p : r.certificate.placement) r.max_moved = std::max(r.max_moved, p.moved.norm());
  return {std::move(r), std::move(res.positions)};
}

}  // namespace

void check_robustness(const RobustnessOptions& o) {
  for (const auto model : o.models)
    if (!scene::model_available(model))
      throw Error("vgd bench robustness", "", std::string("the cloth model ") + scene::to_string(model) +
                                              " is not in this build");
  for (const auto& garment : o.garments)
    for (const auto& material : o.materials) case_scene({garment, 0.015, "", material}, o);
}

std::vector<RobustnessRecord> robustness_study(const RobustnessOptions& o,
                                               const std::function<void(const RobustnessRecord&)>& on_record) {
  check_robustness(o);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  std::vector<RobustnessRecord> records;
  for (const auto& garment : o.garments)
    for (const double spacing : o.spacings)
      for (const auto& size : o.sizes)
        for (const auto& material : o.materials)
          for (const auto model : o.models) {
            sim::VecX reference;
            for (int j = 0; j <= o.jitters; ++j) {
              RobustnessCase k{garment, spacing, size, material, model, j == 0 ? 0.0 : o.jitter,
                               static_cast<unsigned>(j)};
              auto [r, x] = drape_case(k, o);
              if (j == 0) {
                reference = x;
              } else if (reference.size() == x.size()) {
                r.spread = 0.0;
                for (Eigen::Index i = 0; i + 2 < x.size(); i += 3)
                  r.spread = std::max(r.spread, (x.segment<3>(i) - reference.segment<3>(i)).norm());
              }
              if (on_record) on_record(r);
              records.push_back(std::move(r));
            }
          }
  omp_set_num_threads(threads);
  return records;
}

std::vector<RobustnessRow> summarise_robustness(const std::vector<RobustnessRecord>& records) {
  std::vector<RobustnessRow> rows;
  auto widen = [](double& lo, double& hi, double v) {
    if (lo > hi) lo = hi = v;
    lo = std::min(lo, v), hi = std::max(hi, v);
  };
  for (const auto& r : records) {
    const std::string garment = r.run.garment.stem().string();
    auto row = std::find_if(rows.begin(), rows.end(), [&](const RobustnessRow& w) {
      return w.garment == garment && w.spacing == r.run.spacing && w.material == r.run.material &&
             w.model == r.run.model;
    });
    if (row == rows.end()) {
      rows.push_back({garment, r.run.spacing, r.run.material, r.run.model});
      row = rows.end() - 1;
    }
    ++row->runs;
    row->clean += r.clean ? 1 : 0;
    std::vector<std::string> classes;
    for (const auto& f : r.certificate.failures())
      if (std::find(classes.begin(), classes.end(), f.kind) == classes.end()) classes.push_back(f.kind);
    for (const auto& k : classes) {
      auto it = std::find_if(row->failures.begin(), row->failures.end(),
                             [&](const auto& p) { return p.first == k; });
      if (it == row->failures.end())
        row->failures.emplace_back(k, 1);
      else
        ++it->second;
    }
    if (r.clean) widen(row->rest_lo, row->rest_hi, r.certificate.simulated_s);
    widen(row->wall_lo, row->wall_hi, r.certificate.wall_s);
    if (r.spread >= 0.0) widen(row->spread_lo, row->spread_hi, r.spread);
  }
  return rows;
}

}  // namespace vgd::study
