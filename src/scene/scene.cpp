// Scene definitions: names, the effective step, and the checks a Def passes
// before anything is built.
#include "vgd/scene/scene.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::scene {

const char* to_string(ClothModel m) {
  switch (m) {
    case ClothModel::mass_spring: return "mass-spring";
    case ClothModel::strain_rosette: return "strain-rosette";
  }
  return "?";
}

ClothModel parse_cloth_model(const std::string& s) {
  if (s == "mass-spring") return ClothModel::mass_spring;
  if (s == "strain-rosette") return ClothModel::strain_rosette;
  throw std::invalid_argument("unknown cloth model '" + s + "' (use mass-spring or strain-rosette)");
}

double effective_step(const SceneDef& def) {
  if (def.integrator.iterations_per_frame > 0) return 1.0 / (def.run.fps * def.integrator.iterations_per_frame);
  return def.integrator.settings.step;
}

namespace {

// Throws for the first problem, naming the scene file and the field's JSON path.
class Checker {
 public:
  explicit Checker(const SceneDef& d) : def_(d), file_(d.source.string()) {}

  void fail(const std::string& path, const std::string& msg) const { throw Error(file_, path, msg); }
  void finite(const std::string& path, double v) const {
    if (!std::isfinite(v)) fail(path, "is not a finite number");
  }
  void positive(const std::string& path, double v) const {
    if (!(v > 0.0) || !std::isfinite(v)) fail(path, "must be a positive number (got " + format_double(v) + ")");
  }
  void non_negative(const std::string& path, double v) const {
    if (!(v >= 0.0) || !std::isfinite(v)) fail(path, "must be >= 0 (got " + format_double(v) + ")");
  }
  void finite(const std::string& path, const Vec3& v) const {
    if (!v.allFinite()) fail(path, "holds a value that is not a finite number");
  }

  void run() const {
    if (def_.cloth.empty()) fail("cloth", "the scene has no cloth piece");
    std::set<std::string> names;
    for (std::size_t i = 0; i < def_.cloth.size(); ++i) {
      cloth(def_.cloth[i], "cloth[" + std::to_string(i) + "]");
      const auto& n = def_.cloth[i].name;
      if (!n.empty() && !names.insert(n).second)
        fail("cloth[" + std::to_string(i) + "].name", "two cloth pieces are called '" + n + "'");
    }
    // The engine's fabric effects act on every piece of the model: one cloth
    // model (and one bending choice) for the whole scene.
    for (std::size_t i = 1; i < def_.cloth.size(); ++i) {
      const auto& a = def_.cloth.front();
      const auto& b = def_.cloth[i];
      if (a.model != b.model)
        fail("cloth[" + std::to_string(i) + "].model",
             std::string("is ") + to_string(b.model) + " but cloth[0] is " + to_string(a.model) +
                 "; one scene uses one cloth model for all its pieces (for now)");
      if (a.model == ClothModel::strain_rosette && a.bending != b.bending)
        fail("cloth[" + std::to_string(i) + "].bending", "differs from cloth[0]; bending is on or off for the whole scene");
    }
    if (def_.avatar) avatar(*def_.avatar);
    effects();
    integrator();
    positive("frames.fps", def_.run.fps);
    non_negative("frames.duration", def_.run.duration);
    frame_and_step_counts();
    non_negative("frames.rest_energy", def_.run.rest_energy);
    if (def_.run.rest_frames < 1) fail("frames.rest_frames", "must be >= 1");
    if (!(def_.run.start_jitter >= 0.0) || def_.run.start_jitter > 0.01)
      fail("frames.start_jitter", "must be between 0 and 1 cm");
    for (std::size_t i = 0; i < def_.outputs.size(); ++i)
      if (def_.outputs[i].kind == OutputDef::Kind::obj && def_.outputs[i].directory.empty())
        fail("output[" + std::to_string(i) + "].directory", "an OBJ sequence needs a directory");
  }

 private:
  // What a run plans must be bounded: a mistyped rate ("fps": 1e9) would plan
  // tens of millions of frames, a step of 1e-12 s a run that never ends.
  void frame_and_step_counts() const {
    if (def_.run.fps > kMaxFps)
      fail("frames.fps", format_double(def_.run.fps) + " frames per second is more than the " +
                             format_fixed(kMaxFps, 0) + " a scene may ask for");
    const double frames = def_.run.duration * def_.run.fps;
    if (frames > kMaxFrames)
      fail("frames.duration",
           format_fixed(def_.run.duration, 3) + " s at " + format_double(def_.run.fps) + " frames per second is " +
               format_fixed(frames, 0) + " frames, more than the " + format_fixed(kMaxFrames, 0) +
               " a run may write; shorten it or lower frames.fps");
    const double step = effective_step(def_);
    if (step > 0.0 && def_.run.duration / step > kMaxSteps)
      fail("integrator.step",
           format_double(step) + " s for " + format_fixed(def_.run.duration, 3) + " s is " +
               format_fixed(def_.run.duration / step, 0) + " steps, more than the " + format_fixed(kMaxSteps, 0) +
               " a run may take; lengthen the step or shorten the run");
  }

  void cloth(const ClothDef& c, const std::string& p) const {
    const int sources = c.grid.has_value() + c.xvc.has_value() + c.garment.has_value();
    if (sources != 1)
      fail(p, sources > 1 ? "give one of grid, xvc and garment" : "say where the cloth comes from: grid, xvc or garment");
    if (c.garment) {
      if (c.garment->file.empty()) fail(p + ".garment.file", "is empty");
      non_negative(p + ".garment.spacing", c.garment->spacing);
      if (!def_.avatar) fail(p + ".garment", "a garment is dressed on a body: the scene needs an avatar");
    }
    if (c.grid) {
      if (c.grid->nu < 2 || c.grid->nv < 2)
        fail(p + ".grid.particles", "a grid needs at least 2 x 2 particles (got " + std::to_string(c.grid->nu) +
                                        " x " + std::to_string(c.grid->nv) + ")");
      if (static_cast<long long>(c.grid->nu) * c.grid->nv > 50'000'000LL)
        fail(p + ".grid.particles", "more than 50 million particles");
      positive(p + ".grid.size[0]", c.grid->width);
      positive(p + ".grid.size[1]", c.grid->height);
    }
    if (c.xvc) {
      if (c.xvc->file.empty()) fail(p + ".xvc.file", "is empty");
      non_negative(p + ".xvc.spacing", c.xvc->spacing);
      if (!(c.xvc->min_angle >= 0.0 && c.xvc->min_angle <= 33.0))
        fail(p + ".xvc.min_angle", "must be between 0 (the document's) and 33 degrees");
      non_negative(p + ".xvc.gap", c.xvc->gap);
    }
    finite(p + ".placement.origin", c.placement.origin);
    finite(p + ".placement.u", c.placement.u);
    finite(p + ".placement.v", c.placement.v);
    if (c.placement.u.norm() < 1e-12) fail(p + ".placement.u", "is the zero vector");
    if (c.placement.v.norm() < 1e-12) fail(p + ".placement.v", "is the zero vector");
    if (c.placement.u.normalized().cross(c.placement.v.normalized()).norm() < 1e-6)
      fail(p + ".placement.v", "is parallel to u; the cloth's plane needs two directions");
    if (!model_available(c.model))
      fail(p + ".model", std::string("the ") + to_string(c.model) + " model is not available in this build yet");
    if (c.material.empty()) fail(p + ".material", "is missing");
    const auto it = def_.materials.find(c.material);
    if (it == def_.materials.end()) {
      std::string known;
      for (const auto& [k, v] : def_.materials)
        if (k.find('.') == std::string::npos) known += (known.empty() ? "" : ", ") + k;
      fail(p + ".material", "unknown material '" + c.material + "'" +
                                (known.empty() ? " (the scene defines no materials)" : " (known: " + known + ")"));
    }
    const MaterialSource& m = it->second;
    const std::string mp = it->first.find('.') == std::string::npos ? "materials." + it->first : it->first;
    if (!m.xvc.empty() && m.id.empty()) fail(mp + ".id", "is missing (the MATERIAL's id in " + m.xvc.string() + ")");
    if (m.xvc.empty()) {
      // Inline values: check now what the model needs. XVC materials are checked when read.
      if (c.model == ClothModel::mass_spring) {
        const auto problem = mass_spring_problem(m.values);
        if (!problem.empty()) fail(mp, "cannot be used with the mass-spring model: " + problem);
      }
      if (c.model == ClothModel::strain_rosette) {
        const auto problem = orthotropic_problem(m.values);
        if (!problem.empty()) fail(mp, "cannot be used with the strain-rosette model: " + problem);
      }
    }
  }

  void avatar(const AvatarDef& a) const {
    switch (a.kind) {
      case AvatarDef::Kind::mannequin: {
        if (!a.size.empty()) break;
        const auto& m = a.measurements;
        for (const auto& [name, v] : {std::pair{"height", m.height}, {"bust", m.bust}, {"under_bust", m.under_bust},
                                      {"waist", m.waist}, {"hip", m.hip}, {"shoulder_width", m.shoulder_width},
                                      {"neck", m.neck}, {"arm_length", m.arm_length}, {"inseam", m.inseam}})
          positive(std::string("avatar.mannequin.") + name, v);
        if (m.sex != "female" && m.sex != "male") fail("avatar.mannequin.sex", "must be female or male");
        break;
      }
      case AvatarDef::Kind::file:
        if (a.file.empty()) fail("avatar.file", "is empty");
        break;
      case AvatarDef::Kind::sphere:
        finite("avatar.sphere.centre", a.centre);
        positive("avatar.sphere.radius", a.radius);
        if (a.segments < 3 || a.rings < 2) fail("avatar.sphere", "needs segments >= 3 and rings >= 2");
        break;
      case AvatarDef::Kind::cylinder:
        finite("avatar.cylinder.base", a.centre);
        positive("avatar.cylinder.radius", a.radius);
        positive("avatar.cylinder.height", a.height);
        if (a.segments < 3 || a.rings < 1) fail("avatar.cylinder", "needs segments >= 3 and stacks >= 1");
        break;
    }
  }

  void effects() const {
    const auto& e = def_.effects;
    if (e.collision) {
      if (!def_.avatar) fail("effects.collision", "collides the cloth with the avatar, but the scene has no avatar");
      non_negative("effects.collision.clearance", e.collision->clearance);
      non_negative("effects.collision.friction", e.collision->friction);
      if (!(e.collision->restitution >= 0.0 && e.collision->restitution <= 1.0))
        fail("effects.collision.restitution", "must be in [0, 1]");
      positive("effects.collision.grid_spacing", e.collision->grid.spacing);
      positive("effects.collision.grid_band", e.collision->grid.band);
    }
    if (e.self_collision) {
      positive("effects.self_collision.thickness", e.self_collision->thickness);
      non_negative("effects.self_collision.stiffness", e.self_collision->stiffness);
      if (e.self_collision->passes < 1) fail("effects.self_collision.passes", "must be >= 1");
    }
    if (e.contact) {
      if (!def_.avatar) fail("effects.contact", "keeps the cloth off the avatar, but the scene has no avatar");
      if (e.collision || e.self_collision)
        fail("effects.contact", "replaces collision and self_collision: give contact or those, not both");
      positive("effects.contact.radius", e.contact->radius);
      if (!(e.contact->reach >= e.contact->radius)) fail("effects.contact.reach", "must be >= radius");
      if (!(e.contact->gamma > 0.0 && e.contact->gamma < 0.5)) fail("effects.contact.gamma", "must be in (0, 0.5)");
      non_negative("effects.contact.stiffness", e.contact->stiffness);
      non_negative("effects.contact.friction", e.contact->friction);
      positive("effects.contact.slip_speed", e.contact->slip_speed);
      if (e.contact->rounds < 1) fail("effects.contact.rounds", "must be >= 1");
      if (!(e.contact->floor >= 0.0 && e.contact->floor < e.contact->radius))
        fail("effects.contact.floor", "must be >= 0 and smaller than the radius");
    }
    if (e.seams) {
      non_negative("effects.seams.stiffness", e.seams->effect.stiffness);
      positive("effects.seams.max_force", e.seams->effect.max_force);
      non_negative("effects.seams.damping", e.seams->effect.damping);
      non_negative("effects.seams.merge_distance", e.seams->effect.merge_distance);
      non_negative("effects.seams.zip_distance", e.seams->effect.zip_distance);
      non_negative("effects.seams.last_stitch_distance", e.seams->effect.last_stitch_distance);
      if (e.seams->effect.last_stitch_frames < 1) fail("effects.seams.last_stitch_frames", "must be >= 1");
      non_negative("effects.seams.wait_limit", e.seams->effect.wait_limit);
    }
    if (e.gravity) finite("effects.gravity.g", e.gravity->g);
    if (e.speed_limit) positive("effects.speed_limit.max_speed", e.speed_limit->max_speed);
    if (e.viscosity) {
      non_negative("effects.viscosity.k", e.viscosity->k);
      non_negative("effects.viscosity.alpha", e.viscosity->alpha);
    }
    if (e.damping) non_negative("effects.damping.c", e.damping->c);
    if (e.wind) {
      finite("effects.wind.velocity", e.wind->velocity);
      non_negative("effects.wind.coefficient", e.wind->coefficient);
      non_negative("effects.wind.turbulence", e.wind->turbulence);
      positive("effects.wind.gust_frequency", e.wind->gust_frequency);
    }
    for (std::size_t i = 0; i < e.pins.size(); ++i) {
      const auto& g = e.pins[i];
      const std::string p = "effects.pins[" + std::to_string(i) + "]";
      if (g.particles.empty() && g.sets.empty() && !g.region)
        fail(p, "a pin group needs particles, sets or a region");
      finite(p + ".velocity", g.velocity);
      for (std::size_t k = 0; k < g.particles.size(); ++k)
        if (g.particles[k] < 0)
          fail(p + ".particles[" + std::to_string(k) + "]", "particle indices start at 0 (got " +
                                                                std::to_string(g.particles[k]) + ")");
      if (g.region) {
        finite(p + ".region.min", g.region->min);
        finite(p + ".region.max", g.region->max);
        if ((g.region->max - g.region->min).minCoeff() < 0.0) fail(p + ".region", "max lies below min");
      }
      if (!g.piece.empty()) {
        bool found = false;
        for (const auto& c : def_.cloth) found = found || c.name == g.piece || c.xvc;  // XVC blocks are known later
        if (!found) fail(p + ".piece", "no cloth piece is called '" + g.piece + "'");
      }
    }
  }

  void integrator() const {
    const auto& d = def_.integrator;
    const auto& s = d.settings;
    if (d.iterations_per_frame < 0) fail("integrator.iterations_per_frame", "must be >= 1");
    if (d.iterations_per_frame == 0) positive("integrator.step", s.step);
    if (!(s.safety > 0.0 && s.safety <= 1.0)) fail("integrator.safety", "must be in (0, 1]");
    if (s.newton_iterations < 1) fail("integrator.newton_iterations", "must be >= 1");
    positive("integrator.cg_tolerance", s.cg_tolerance);
    if (s.cg_max_iterations < 1) fail("integrator.cg_max_iterations", "must be >= 1");
    positive("integrator.rtol", s.rtol);
    positive("integrator.atol", s.atol);
    if (s.max_order < 1 || s.max_order > 5) fail("integrator.max_order", "must be 1 to 5");
    non_negative("integrator.max_step", s.max_step);
    positive("integrator.max_speed", s.max_speed);
  }

  const SceneDef& def_;
  std::string file_;
};

}  // namespace

void validate(const SceneDef& def) { Checker(def).run(); }

}  // namespace vgd::scene
