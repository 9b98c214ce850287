#include "vgd/dress/drape.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <optional>

#include "vgd/core/data.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/version.hpp"
#include "vgd/dress/dress.hpp"
#include "vgd/scene/quality.hpp"
#include "vgd/sim/effects/seam.hpp"
#include "vgd/sim/effects/contact.hpp"
#include "vgd/sim/effects/self_collision.hpp"
#include "vgd/sim/threads.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::dress {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string metres(double v) { return format_double(v) + " m"; }

// The last frames of a run (a second of simulated time: fps + 1 frames), to
// say where a drape that did not come to rest still moves.
class MotionWindow : public sim::FrameSink {
 public:
  explicit MotionWindow(int frames) : keep_(std::max(2, frames + 1)) {}
  void frame(int, double t, const sim::VecX& x) override {
    frames_.push_back(x);
    times_.push_back(t);
    if (static_cast<int>(frames_.size()) > keep_) {
      frames_.pop_front();
      times_.pop_front();
    }
  }

  // Certificate::still_moving from the frames kept; nullopt with fewer than two.
  std::optional<StillMoving> still_moving(const scene::Scene& scene) const {
    if (frames_.size() < 2) return std::nullopt;
    const auto n = static_cast<int>(frames_.back().size() / 3);
    std::vector<double> path(n, 0.0);
    for (std::size_t k = 1; k < frames_.size(); ++k) {
      if (frames_[k].size() != frames_[k - 1].size()) return std::nullopt;
      for (int i = 0; i < n; ++i) path[i] += (sim::at(frames_[k], i) - sim::at(frames_[k - 1], i)).norm();
    }
    StillMoving m;
    m.window_s = times_.back() - times_.front();
    const int top = static_cast<int>(std::max_element(path.begin(), path.end()) - path.begin());
    m.path = path[top];
    m.at = sim::at(frames_.back(), top);
    std::map<std::string, int> by_piece;
    for (const auto& p : scene.pieces)
      for (int i = p.first; i < p.first + p.count && i < n; ++i)
        if (path[i] >= 0.5 * m.path) ++by_piece[p.name];
    m.pieces.assign(by_piece.begin(), by_piece.end());
    std::stable_sort(m.pieces.begin(), m.pieces.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    if (scene.avatar) m.near = body::segments_beside(*scene.avatar, m.at, kNearCrease);
    return m;
  }

 private:
  int keep_;
  std::deque<sim::VecX> frames_;
  std::deque<double> times_;
};

}  // namespace

scene::MaterialSource garment_fabric(const xvc::Document& garment, const fs::path& garment_file,
                                     const fs::path& material_xvc, const std::string& material_id) {
  scene::MaterialSource fabric;
  if (!material_xvc.empty()) {
    fabric.xvc = fs::absolute(material_xvc);
    fabric.id = material_id;
  } else if (const std::string own = xvc::garment_material(garment); !own.empty()) {
    fabric.xvc = garment_file;
    fabric.id = own;
  } else {
    fabric.xvc = data_file("materials/shirting.xvc");
    fabric.id = "shirting";
  }
  if (fabric.id.empty()) {
    const xvc::Document mdoc = xvc::load_file(fabric.xvc);
    const auto* mats = mdoc.container("MATERIALS");
    if (!mats || mats->children.empty()) throw Error(fabric.xvc.string(), "MATERIALS", "holds no MATERIAL");
    fabric.id = std::string(mats->children.front().id());
  }
  return fabric;
}

scene::MaterialDef garment_fabric_of(const xvc::Document& garment, const fs::path& garment_file,
                                     const fs::path& material_xvc, const std::string& material_id) {
  const scene::MaterialSource src = garment_fabric(garment, garment_file, material_xvc, material_id);
  // The document's own from the document in hand (it may be unsaved).
  if (material_xvc.empty() && src.xvc == garment_file) return scene::material_from_xvc(garment, src.id, garment_file.string());
  return scene::load_xvc_material(src.xvc, src.id);
}

scene::SceneDef drape_scene(const DrapeOptions& o) {
  std::error_code ec;
  if (!fs::is_regular_file(o.garment, ec)) throw Error(o.garment.string(), "", "no such garment document");
  const fs::path garment = fs::absolute(o.garment);
  const xvc::Document doc = xvc::load_file(garment);

  scene::SceneDef def;
  def.name = "drape " + garment.stem().string();

  // The body: the mannequin of the garment's size unless told otherwise.
  if (o.avatar) {
    def.avatar = *o.avatar;
  } else {
    scene::AvatarDef a;
    a.kind = scene::AvatarDef::Kind::mannequin;
    std::string size = o.size;
    if (size.empty())
      if (const auto* g = doc.container("GRADATIONS")) size = std::string(g->attribute("sample_size"));
    a.size = size.empty() ? "38" : size;
    a.table = o.mannequin_table;
    def.avatar = a;
  }

  // Each garment's fabric: its own MATERIAL, else vgd's shirting (or the
  // --material given, for every garment).
  std::vector<fs::path> garments{garment};
  for (const auto& p : o.over) {
    if (std::find(garments.begin(), garments.end(), fs::absolute(p)) != garments.end())
      throw Error(p.string(), "", "the same garment is given twice");
    if (!fs::is_regular_file(p, ec)) throw Error(p.string(), "", "no such garment document");
    garments.push_back(fs::absolute(p));
  }
  for (std::size_t k = 0; k < garments.size(); ++k) {
    std::optional<xvc::Document> loaded;
    if (k > 0) loaded = xvc::load_file(garments[k]);
    const xvc::Document& gdoc = k == 0 ? doc : *loaded;
    const scene::MaterialSource fabric = garment_fabric(gdoc, garments[k], o.material_xvc, o.material_id);
    const std::string mat = k == 0 ? "fabric" : "fabric" + std::to_string(k + 1);
    def.materials[mat] = fabric;

    scene::ClothDef cloth;
    cloth.name = garments[k].stem().string();
    scene::GarmentDef g;
    g.file = garments[k];
    g.size = o.size;
    g.spacing = o.spacing;
    if (k == 0) g.pieces = o.pieces;
    g.layer = static_cast<int>(k);
    cloth.garment = g;
    cloth.model = o.model;
    cloth.material = mat;
    def.cloth.push_back(cloth);
  }

  auto& e = def.effects;
  e.gravity = sim::GravityDef{};
  // Air drag, mass-proportional so it does not depend on the mesh (a garment
  // settles in about a second instead of swinging for ten).
  e.viscosity = sim::ViscosityDef{0.0, 2.0};
  e.collision = sim::BodyCollisionDef{};
  if (o.between_particles) e.collision->vertex_clearance = 0.001;
  // Seams pull hard enough to slide cloth over the body against friction: a
  // pair pulls with 200 N/m near closing and at most 1 N; implicit Euler keeps
  // that stable. Pairs merge at 2 mm. Measured on the shipped garments
  // (docs/drape.md): 0.5 N left seams open; 2 N closed them but the yank
  // (particles at 20 m/s) folded the skirt's waistband through itself.
  scene::SeamsDef seams;
  seams.effect.stiffness = 200.0;
  seams.effect.max_force = 1.0;
  seams.effect.damping = 0.01;
  // A pair next to a sewn one merges within 2 cm (about 1.3 mesh spacings), so
  // seams zip closed where tight cloth (a sleeve cap's ease, the armpit) would
  // hold the last pairs a few mm apart.
  seams.effect.zip_distance = 0.02;
  // The last open pair of a seam, stalled for 0.4 s, merges within 5 cm: an
  // armpit's corner pair otherwise hung 2.7–4.8 cm open for good (the four
  // pieces' corners held on both sides of the crease) and the drape never
  // came to rest (T-shirt sizes 34, spacings 1.4, 1.5 cm; docs/drape.md).
  seams.effect.last_stitch_distance = 0.05;
  seams.effect.last_stitch_frames = 10;
  // Sleeves first (an option): a sleeve is sewn to its armhole once it is a
  // tube round its arm (its underarm seam closed; SeamPairs::after,
  // dress_garments), or after 1 s whatever its other seams do. Pulled to the
  // armhole while still open, a sleeve on an arm swung forward slid off the
  // arm through its opening (docs/seams.md, "Order").
  seams.sleeves_first = o.sleeves_first;
  seams.effect.wait_limit = 1.0;
  e.seams = seams;
  if (o.self_collision) {
    e.self_collision = sim::SelfCollisionDef{};
    e.self_collision->damping = o.repulsion_damping;
    // Seams accelerate particles to tens of m/s; capped at 1 m/s (a 20 cm gap
    // closes in 0.2 s), each particle's motion over a 10 ms step stays under
    // 1 cm and self-collision tests stay local (minutes per simulated second
    // without it on the T-shirt).
    e.speed_limit = sim::SpeedLimitDef{1.0};
  }

  if (o.offset_contact) {
    e.collision.reset();
    e.self_collision.reset();
    e.contact = sim::ContactDef{};
    e.speed_limit = sim::SpeedLimitDef{1.0};
    // A seam's two sides are kept apart like any cloth, so they merge a
    // millimetre beyond the contact radius, where the repulsion lets them come.
    e.seams->effect.merge_distance = e.contact->radius + 0.001;
  }

  // Implicit Euler at 2, 4 or 8 steps per frame (quality.hpp).
  def.integrator = scene::quality_integrator(o.quality, true);
  // Touching cloth held on the body's surface once every seam is sewn, when
  // asked (sim::IntegratorSettings::hold_contacts_once_sewn).
  def.integrator.settings.hold_contacts_once_sewn = o.hold_contacts_once_sewn;
  def.run.fps = o.fps;
  def.run.duration = o.time_limit;
  // Preview: coarser by stopping sooner (docs/accuracy-vs-time.md), never
  // by leaving out the contacts that keep its result free of crossings.
  def.run.rest_energy = o.quality == scene::Quality::preview ? 10.0 * o.rest_energy : o.rest_energy;
  def.run.rest_frames = o.rest_frames;
  validate(def);
  return def;
}

DrapeResult run_drape(const scene::SceneDef& def, const std::vector<sim::FrameSink*>& sinks,
                      const std::function<void(const DrapeStageProgress&)>& progress) {
  DrapeResult r;
  const auto t_start = Clock::now();
  {
    // Placing on one thread: with nothing measured yet it cannot tell whether
    // other processes keep the cores busy, where a team spinning at its
    // barriers is slowed many times; on an idle machine its threads save 7 %
    // of it (the polo: 2.35 s instead of 2.53 s). The frames then adapt
    // (sim/threads.hpp).
    sim::ThreadGovernor one(omp_get_max_threads());
    r.scene = dress::build(def);
  }
  const double placing_wall = seconds_since(t_start);
  sim::System& sys = *r.scene.system;
  r.state = sim::initial_state(sys.model());
  auto integrator = sim::make_integrator(r.scene.integrator);

  // The seam effect, for progress.
  const sim::Effect* seam_effect = nullptr;
  for (const auto& e : sys.effects())
    if (sim::seam_report(*e)) seam_effect = e.get();

  Certificate& c = r.certificate;
  double sewn_at = -1.0, sewn_wall = 0.0;
  const auto t_run = Clock::now();
  auto on_frame = [&](const sim::Progress& p) {
    DrapeStageProgress d;
    d.t = p.t;
    d.time_limit = p.duration;
    d.wall_s = seconds_since(t_start);
    if (seam_effect) {
      const auto* rep = sim::seam_report(*seam_effect);
      d.seams_closed = rep->total.closed;
      d.seam_pairs = rep->total.total;
      for (const auto& s : rep->seams) d.seams_waiting += s.waiting ? 1 : 0;
    }
    if (sewn_at < 0 && d.seams_closed == d.seam_pairs) {
      sewn_at = p.t;
      sewn_wall = seconds_since(t_run);
    }
    d.stage = sewn_at < 0 ? "sewing" : "settling";
    d.kinetic_energy = p.kinetic_energy;
    if (progress) progress(d);
  };
  if (progress) progress({"placing", 0.0, def.run.duration, placing_wall, 0, 0, 0.0, &r.scene});
  MotionWindow window(static_cast<int>(std::lround(r.scene.run.fps)));
  std::vector<sim::FrameSink*> all_sinks = sinks;
  all_sinks.push_back(&window);
  r.summary = sim::run(sys, *integrator, r.state, r.scene.run, all_sinks, on_frame);
  r.positions = sys.expand(r.state.x);

  // The certificate.
  c.version = std::string(kVersion);
  int garment_count = 0;
  for (const auto& cl : def.cloth)
    if (cl.garment)
      c.inputs.emplace_back(garment_count++ == 0 ? "garment" : "garment_" + std::to_string(garment_count),
                            cl.garment->file.string());
  if (r.scene.avatar) c.inputs.emplace_back("avatar", r.scene.avatar->source);
  for (const auto& [k, m] : def.materials)
    if (!m.xvc.empty()) c.inputs.emplace_back(k == "fabric" ? "material" : "material_" + k.substr(6), m.xvc.string() + "#" + m.id);
  if (def.integrator.preset) c.settings.emplace_back("quality", to_string(*def.integrator.preset));
  if (!def.cloth.empty()) c.settings.emplace_back("model", scene::to_string(def.cloth.front().model));
  c.settings.emplace_back("integrator", sim::to_string(r.scene.integrator.method));
  c.settings.emplace_back("step", format_double(r.scene.integrator.step) + " s");
  c.settings.emplace_back("hold_contacts", r.scene.integrator.hold_contacts_once_sewn ? "once sewn" : "off");
  c.settings.emplace_back("fps", format_double(def.run.fps));
  c.settings.emplace_back("time_limit", format_double(def.run.duration) + " s");
  c.settings.emplace_back("rest_energy", format_double(def.run.rest_energy) + " J per particle");
  c.settings.emplace_back("rest_frames", std::to_string(def.run.rest_frames));
  double merge_distance = 0.0, contact = 0.004;
  if (def.effects.collision) {
    c.settings.emplace_back("clearance", metres(def.effects.collision->clearance));
    contact = def.effects.collision->clearance + 0.001;
  }
  if (def.effects.contact) {
    c.settings.emplace_back("clearance", metres(def.effects.contact->radius));
    contact = def.effects.contact->radius + 0.001;
  }
  if (def.effects.seams) {
    merge_distance = def.effects.seams->effect.merge_distance;
    c.settings.emplace_back("seam_merge_distance", metres(merge_distance));
    c.settings.emplace_back("sleeves_first", def.effects.seams->sleeves_first ? "on" : "off");
  }
  c.settings.emplace_back("self_collision", def.effects.self_collision ? "on" : "off");
  if (def.effects.self_collision && def.effects.self_collision->damping > 0.0)
    c.settings.emplace_back("repulsion_damping", format_double(def.effects.self_collision->damping) + " of critical");
  if (def.effects.contact) c.settings.emplace_back("contact", "offset");
  c.settings.emplace_back("between_particles",
                          def.effects.collision && def.effects.collision->vertex_clearance > 0.0 ? "on" : "off");
  c.stop_reason = !r.summary.ok ? "error" : r.summary.at_rest ? "rest" : "time limit";
  c.stop_message = r.summary.error;
  if (c.stop_reason == "time limit") c.still_moving = window.still_moving(r.scene);
  c.simulated_s = r.summary.simulated_s;
  c.wall_s = seconds_since(t_start);
  c.frames = r.summary.frames;
  c.frames_on_fewer_threads = r.summary.frames_on_fewer_threads;
  c.stages.push_back({"placing", placing_wall, 0.0});
  const double run_wall = r.summary.wall_s;
  if (sewn_at >= 0) {
    c.stages.push_back({"sewing", sewn_wall, sewn_at});
    c.stages.push_back({"settling", run_wall - sewn_wall, r.summary.simulated_s - sewn_at});
  } else {
    c.stages.push_back({"sewing", run_wall, r.summary.simulated_s});
  }
  for (const auto& p : sys.profile()) c.effect_seconds.emplace_back(p.name, p.seconds);
  for (const auto& e : sys.effects())
    if (std::string(e->name()) == "self-collision") {
      const auto& st = sim::self_collision_stats(*e);
      c.self_detections = st.detections, c.self_pairs = st.pairs_total, c.self_reverted = st.reverted, c.self_untangled = st.untangled;
    } else if (std::string(e->name()) == "contact") {
      const auto& st = sim::contact_stats(*e);
      c.contact_detections = st.detections, c.contact_cut = st.cut, c.contact_unfinished = st.unfinished;
      c.contact_merges_held = st.merges_held;
    }
  c.steps = r.summary.stats.steps;
  c.force_evaluations = r.summary.stats.rhs_evaluations;
  c.linear_iterations = r.summary.stats.linear_iterations;
  c.times = r.summary.times;
  c.kinetic_energy = r.summary.kinetic_energy;
  measure_state(r.scene, r.positions, merge_distance, contact, true, c);
  return r;
}

}  // namespace vgd::dress
