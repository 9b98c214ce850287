// Scene files: JSON -> SceneDef, with types, units and names checked and every
// problem named by its JSON path.
#include "vgd/scene/json.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/scene/quality.hpp"

namespace vgd::scene {

namespace {

using json = nlohmann::json;

// The file being read, for messages.
struct Context {
  std::string file;
  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw Error(file, path, message);
  }
};

std::string type_name(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "a list";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "true/false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "a number";
    default: return "something else";
  }
}

std::string index_path(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

// ---- values -------------------------------------------------------------------------

// A quantity: a number in the field's SI unit, or a string with a unit of the
// field's kind.
double quantity(const json& j, const std::string& path, const Dimension& d, const Context& c) {
  if (j.is_number()) {
    const double v = j.get<double>();
    if (!std::isfinite(v)) c.fail(path, "is not a finite number");
    return v;
  }
  if (j.is_string()) {
    const auto text = j.get<std::string>();
    const auto q = parse_quantity(text);
    if (!q)
      c.fail(path, "\"" + text + "\" is not a number with a unit (e.g. \"4 ms\", \"2 cm\", \"0.2 N.s/m\")");
    if (q->dimension != d)
      c.fail(path, "unit mismatch: \"" + text + "\" is in " + si_name(q->dimension) + ", but this field needs " +
                       si_name(d));
    return q->value;
  }
  c.fail(path, "expected a number (" + si_name(d) + "), got " + type_name(j));
}

int whole(const json& j, const std::string& path, const Context& c) {
  if (j.is_number_integer() || j.is_number_unsigned()) {
    const auto v = j.get<long long>();
    if (v < -2'000'000'000LL || v > 2'000'000'000LL) c.fail(path, "is out of range");
    return static_cast<int>(v);
  }
  if (j.is_number_float()) c.fail(path, "expected a whole number, got " + format_double(j.get<double>()));
  c.fail(path, "expected a whole number, got " + type_name(j));
}

bool boolean(const json& j, const std::string& path, const Context& c) {
  if (!j.is_boolean()) c.fail(path, "expected true or false, got " + type_name(j));
  return j.get<bool>();
}

std::string text(const json& j, const std::string& path, const Context& c) {
  if (!j.is_string()) c.fail(path, "expected a string, got " + type_name(j));
  return j.get<std::string>();
}

const json& list(const json& j, const std::string& path, const Context& c) {
  if (!j.is_array()) c.fail(path, "expected a list, got " + type_name(j));
  return j;
}

Vec3 vec3(const json& j, const std::string& path, const Dimension& d, const Context& c) {
  if (!j.is_array() || j.size() != 3)
    c.fail(path, "expected a list of 3 numbers (" + si_name(d) + "), got " +
                     (j.is_array() ? "a list of " + std::to_string(j.size()) : type_name(j)));
  return {quantity(j[0], index_path(path, 0), d, c), quantity(j[1], index_path(path, 1), d, c),
          quantity(j[2], index_path(path, 2), d, c)};
}

// ---- objects ------------------------------------------------------------------------

// One JSON object being read. Every key asked for is remembered; finish()
// refuses the keys nobody asked for, listing the ones that are known here.
class Object {
 public:
  Object(const json& j, std::string path, const Context& c) : j_(j), path_(std::move(path)), c_(c) {
    if (!j.is_object()) c.fail(path_.empty() ? "(top level)" : path_, "expected an object, got " + type_name(j));
  }
  const Context& context() const { return c_; }
  const std::string& path() const { return path_; }
  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  const json* find(const std::string& key) {
    known_.insert(key);
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  const json& need(const std::string& key, const std::string& why = "") {
    const json* v = find(key);
    if (!v) c_.fail(at(key), "is missing" + (why.empty() ? std::string() : " (" + why + ")"));
    return *v;
  }
  bool has(const std::string& key) {
    known_.insert(key);
    return j_.contains(key);
  }

  void number(const std::string& key, double& out, const Dimension& d) {
    if (const json* v = find(key)) out = quantity(*v, at(key), d, c_);
  }
  void integer(const std::string& key, int& out) {
    if (const json* v = find(key)) out = whole(*v, at(key), c_);
  }
  void flag(const std::string& key, bool& out) {
    if (const json* v = find(key)) out = boolean(*v, at(key), c_);
  }
  void string(const std::string& key, std::string& out) {
    if (const json* v = find(key)) out = text(*v, at(key), c_);
  }
  void strings(const std::string& key, std::vector<std::string>& out) {
    if (const json* v = find(key)) {
      const auto& l = list(*v, at(key), c_);
      for (std::size_t i = 0; i < l.size(); ++i) out.push_back(text(l[i], index_path(at(key), i), c_));
    }
  }
  void vector(const std::string& key, Vec3& out, const Dimension& d) {
    if (const json* v = find(key)) out = vec3(*v, at(key), d, c_);
  }

  // "enabled": false switches an effect off without deleting it.
  bool enabled() {
    bool on = true;
    flag("enabled", on);
    return on;
  }

  void finish() const {
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      if (known_.count(it.key())) continue;
      std::string list;
      for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
      c_.fail(at(it.key()), "unknown field '" + it.key() + "'" + (list.empty() ? "" : " (known here: " + list + ")"));
    }
  }

 private:
  const json& j_;
  std::string path_;
  const Context& c_;
  std::set<std::string> known_;
};

// ---- sections -----------------------------------------------------------------------

Placement read_placement(Object o) {
  Placement p;
  o.vector("origin", p.origin, dim::length);
  o.vector("u", p.u, dim::none);
  o.vector("v", p.v, dim::none);
  o.finish();
  return p;
}

GridDef read_grid(Object o) {
  GridDef g;
  const json& n = o.need("particles", "[nu, nv]: particles along u (warp) and v (weft)");
  if (!n.is_array() || n.size() != 2) o.context().fail(o.at("particles"), "expected [nu, nv], two whole numbers");
  g.nu = whole(n[0], index_path(o.at("particles"), 0), o.context());
  g.nv = whole(n[1], index_path(o.at("particles"), 1), o.context());
  const json& s = o.need("size", "[width, height] in m");
  if (!s.is_array() || s.size() != 2) o.context().fail(o.at("size"), "expected [width, height] in m");
  g.width = quantity(s[0], index_path(o.at("size"), 0), dim::length, o.context());
  g.height = quantity(s[1], index_path(o.at("size"), 1), dim::length, o.context());
  o.finish();
  return g;
}

XvcPiecesDef read_xvc_pieces(Object o) {
  XvcPiecesDef x;
  x.file = text(o.need("file", "the XVC document"), o.at("file"), o.context());
  o.string("size", x.size);
  o.strings("pieces", x.pieces);
  o.number("spacing", x.spacing, dim::length);
  if (const json* a = o.find("min_angle")) {
    // Degrees as a plain number; "25 deg" also reads (the quantity is in radians).
    x.min_angle = a->is_string() ? quantity(*a, o.at("min_angle"), dim::none, o.context()) * 180.0 / M_PI
                                 : quantity(*a, o.at("min_angle"), dim::none, o.context());
  }
  std::string layout;
  o.string("layout", layout);
  if (layout == "own") x.layout = Layout::own;
  else if (layout == "row" || layout.empty()) x.layout = Layout::row;
  else o.context().fail(o.at("layout"), "unknown layout '" + layout + "' (use row or own)");
  o.number("gap", x.gap, dim::length);
  o.finish();
  return x;
}

GarmentDef read_garment(Object o) {
  GarmentDef g;
  g.file = text(o.need("file", "the XVC document"), o.at("file"), o.context());
  o.string("size", g.size);
  o.strings("pieces", g.pieces);
  o.number("spacing", g.spacing, dim::length);
  o.integer("layer", g.layer);
  if (g.layer < 0) o.context().fail(o.at("layer"), "must be >= 0 (0: next to the body)");
  o.finish();
  return g;
}

AvatarDef read_avatar(Object o) {
  AvatarDef a;
  int kinds = 0;
  if (const json* j = o.find("mannequin")) {
    ++kinds;
    a.kind = AvatarDef::Kind::mannequin;
    Object m(*j, o.at("mannequin"), o.context());
    m.string("size", a.size);
    m.string("table", a.table);
    m.integer("triangles", a.triangles);
    auto& b = a.measurements;
    m.string("sex", b.sex);
    m.number("height", b.height, dim::length);
    m.number("bust", b.bust, dim::length);
    m.number("under_bust", b.under_bust, dim::length);
    m.number("waist", b.waist, dim::length);
    m.number("hip", b.hip, dim::length);
    m.number("shoulder_width", b.shoulder_width, dim::length);
    m.number("neck", b.neck, dim::length);
    m.number("arm_length", b.arm_length, dim::length);
    m.number("inseam", b.inseam, dim::length);
    m.finish();
  }
  if (const json* j = o.find("file")) {
    ++kinds;
    a.kind = AvatarDef::Kind::file;
    if (j->is_string()) {
      a.file = j->get<std::string>();
    } else {
      Object f(*j, o.at("file"), o.context());
      a.file = text(f.need("path", "the mesh file"), f.at("path"), o.context());
      f.string("unit", a.unit);
      f.string("up", a.up);
      f.string("facing", a.facing);
      f.flag("human", a.human);
      f.finish();
    }
  }
  if (const json* j = o.find("sphere")) {
    ++kinds;
    a.kind = AvatarDef::Kind::sphere;
    Object s(*j, o.at("sphere"), o.context());
    s.vector("centre", a.centre, dim::length);
    s.number("radius", a.radius, dim::length);
    s.integer("segments", a.segments);
    s.integer("rings", a.rings);
    s.finish();
  }
  if (const json* j = o.find("cylinder")) {
    ++kinds;
    a.kind = AvatarDef::Kind::cylinder;
    Object s(*j, o.at("cylinder"), o.context());
    a.segments = 64;
    a.rings = 1;
    s.vector("base", a.centre, dim::length);
    s.number("radius", a.radius, dim::length);
    s.number("height", a.height, dim::length);
    s.integer("segments", a.segments);
    s.integer("stacks", a.rings);
    s.finish();
  }
  if (kinds != 1)
    o.context().fail(o.path(), kinds == 0 ? "say what the body is: mannequin, file, sphere or cylinder"
                                          : "give one of mannequin, file, sphere and cylinder");
  o.finish();
  return a;
}

// Inline material values: parameter names as in XVC MATERIALs.
MaterialDef read_material_values(Object& o, const json& j) {
  MaterialDef m;
  // The thickness first: per-volume values are converted with it.
  if (const json* t = o.find("thickness")) m.thickness = quantity(*t, o.at("thickness"), dim::length, o.context());
  o.string("name", m.name);
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    if (key == "thickness" || key == "name" || key == "xvc" || key == "id") continue;
    const std::string path = o.at(key);
    const MaterialParameter* p = find_material_parameter(key);
    if (!p) continue;  // finish() reports it with the list of known fields
    o.find(key);
    Quantity q{0.0, p->dimension};
    if (it->is_number()) {
      q.value = quantity(*it, path, p->dimension, o.context());
    } else if (it->is_string()) {
      const auto parsed = parse_quantity(it->get<std::string>());
      if (!parsed) o.context().fail(path, "\"" + it->get<std::string>() + "\" is not a number with a unit");
      q = *parsed;
    } else {
      o.context().fail(path, "expected a number (" + std::string(p->unit) + "), got " + type_name(*it));
    }
    set_material_parameter(m, key, q.value, q.dimension, o.context().file, path);
  }
  for (const auto& p : material_parameters()) o.find(std::string(p.name));
  return m;
}

MaterialSource read_material(const json& j, const std::string& path, const Context& c) {
  Object o(j, path, c);
  MaterialSource s;
  if (o.has("xvc") || o.has("id")) {
    s.xvc = text(o.need("xvc", "the XVC document holding the MATERIAL"), o.at("xvc"), c);
    s.id = text(o.need("id", "the MATERIAL's id"), o.at("id"), c);
  } else {
    s.values = read_material_values(o, j);
  }
  o.finish();
  return s;
}

ClothDef read_cloth(Object o, SceneDef& def) {
  ClothDef cl;
  o.string("name", cl.name);
  if (const json* g = o.find("grid")) cl.grid = read_grid(Object(*g, o.at("grid"), o.context()));
  if (const json* x = o.find("xvc")) cl.xvc = read_xvc_pieces(Object(*x, o.at("xvc"), o.context()));
  if (const json* x = o.find("garment")) cl.garment = read_garment(Object(*x, o.at("garment"), o.context()));
  if (const json* p = o.find("placement")) cl.placement = read_placement(Object(*p, o.at("placement"), o.context()));
  std::string model = "mass-spring";
  o.string("model", model);
  try {
    cl.model = parse_cloth_model(model);
  } catch (const std::invalid_argument& e) {
    o.context().fail(o.at("model"), e.what());
  }
  o.flag("bending", cl.bending);
  const json& m = o.need("material", "a name from `materials` or the material itself");
  if (m.is_string()) {
    cl.material = m.get<std::string>();
  } else if (m.is_object()) {
    cl.material = o.at("material");  // an inline material is kept under its own path
    def.materials[cl.material] = read_material(m, o.at("material"), o.context());
  } else {
    o.context().fail(o.at("material"), "expected a material name or a material object, got " + type_name(m));
  }
  o.finish();
  return cl;
}

PinGroupDef read_pins(Object o, bool& on) {
  PinGroupDef p;
  on = o.enabled();
  o.string("piece", p.piece);
  if (const json* l = o.find("particles")) {
    const auto& a = list(*l, o.at("particles"), o.context());
    for (std::size_t i = 0; i < a.size(); ++i) p.particles.push_back(whole(a[i], index_path(o.at("particles"), i), o.context()));
  }
  o.strings("sets", p.sets);
  if (const json* r = o.find("region")) {
    Object b(*r, o.at("region"), o.context());
    Box box;
    box.min = vec3(b.need("min", "the box's lowest corner, m"), b.at("min"), dim::length, o.context());
    box.max = vec3(b.need("max", "the box's highest corner, m"), b.at("max"), dim::length, o.context());
    b.finish();
    p.region = box;
  }
  o.vector("velocity", p.velocity, dim::velocity);
  o.finish();
  return p;
}

EffectsDef read_effects(Object o) {
  EffectsDef e;
  if (const json* j = o.find("gravity")) {
    Object g(*j, o.at("gravity"), o.context());
    sim::GravityDef d;
    g.vector("g", d.g, dim::acceleration);
    if (g.enabled()) e.gravity = d;
    g.finish();
  }
  if (const json* j = o.find("viscosity")) {
    Object v(*j, o.at("viscosity"), o.context());
    sim::ViscosityDef d;
    v.number("k", d.k, dim::damping);
    v.number("alpha", d.alpha, dim::rate);
    if (v.enabled()) e.viscosity = d;
    v.finish();
  }
  if (const json* j = o.find("speed_limit")) {
    Object v(*j, o.at("speed_limit"), o.context());
    sim::SpeedLimitDef d;
    v.number("max_speed", d.max_speed, dim::velocity);
    if (v.enabled()) e.speed_limit = d;
    v.finish();
  }
  if (const json* j = o.find("damping")) {
    Object v(*j, o.at("damping"), o.context());
    sim::DampingDef d;
    v.number("c", d.c, dim::damping);
    if (v.enabled()) e.damping = d;
    v.finish();
  }
  if (const json* j = o.find("wind")) {
    Object w(*j, o.at("wind"), o.context());
    sim::WindDef d;
    w.vector("velocity", d.velocity, dim::velocity);
    w.number("coefficient", d.coefficient, dim::drag);
    w.number("turbulence", d.turbulence, dim::none);
    w.number("gust_frequency", d.gust_frequency, dim::rate);
    int seed = static_cast<int>(d.seed);
    w.integer("seed", seed);
    if (seed < 0) o.context().fail(w.at("seed"), "must be >= 0");
    d.seed = static_cast<unsigned>(seed);
    if (w.enabled()) e.wind = d;
    w.finish();
  }
  if (const json* j = o.find("collision")) {
    Object c(*j, o.at("collision"), o.context());
    sim::BodyCollisionDef d;
    c.number("clearance", d.clearance, dim::length);
    std::string response = "provot";
    c.string("response", response);
    if (response == "provot") d.response = sim::ContactResponse::provot;
    else if (response == "slide") d.response = sim::ContactResponse::slide;
    else o.context().fail(c.at("response"), "unknown response '" + response + "' (use provot or slide)");
    c.number("friction", d.friction, dim::none);
    c.number("restitution", d.restitution, dim::none);
    c.number("min_bounce_speed", d.min_bounce_speed, dim::velocity);
    std::string query = "grid";
    c.string("query", query);
    if (query == "grid") d.query = sim::BodyQuery::grid;
    else if (query == "exact") d.query = sim::BodyQuery::exact;
    else o.context().fail(c.at("query"), "unknown query '" + query + "' (use grid or exact)");
    c.number("grid_spacing", d.grid.spacing, dim::length);
    c.number("grid_band", d.grid.band, dim::length);
    c.vector("body_velocity", d.velocity, dim::velocity);
    c.number("vertex_clearance", d.vertex_clearance, dim::length);
    c.number("vertex_reach", d.vertex_reach, dim::length);
    c.string("seam_response", e.collision_seam_response);
    if (e.collision_seam_response != "seed" && e.collision_seam_response != "slide" &&
        e.collision_seam_response != "glide" &&
        e.collision_seam_response != "body")
      o.context().fail(c.at("seam_response"), "unknown seam response '" + e.collision_seam_response +
                                                  "' (use glide, seed, slide or body)");
    if (c.enabled()) e.collision = d;
    c.finish();
  }
  if (const json* j = o.find("self_collision")) {
    Object c(*j, o.at("self_collision"), o.context());
    sim::SelfCollisionDef d;
    c.number("thickness", d.thickness, dim::length);
    c.number("stiffness", d.stiffness, dim::stiffness);
    c.number("damping", d.damping, dim::none);
    if (d.damping < 0.0) o.context().fail(c.at("damping"), "damping must be >= 0 (a fraction of critical)");
    c.flag("skip_one_ring", d.skip_one_ring);
    c.integer("passes", d.passes);
    if (c.enabled()) e.self_collision = d;
    c.finish();
  }
  if (const json* j = o.find("contact")) {
    Object c(*j, o.at("contact"), o.context());
    sim::ContactDef d;
    c.number("radius", d.radius, dim::length);
    c.number("reach", d.reach, dim::length);
    c.number("gamma", d.gamma, dim::none);
    c.number("stiffness", d.stiffness, dim::stiffness);
    c.number("friction", d.friction, dim::none);
    c.number("slip_speed", d.slip_speed, dim::velocity);
    c.integer("rounds", d.rounds);
    c.number("floor", d.floor, dim::length);
    if (c.enabled()) e.contact = d;
    c.finish();
  }
  if (const json* j = o.find("seams")) {
    Object c(*j, o.at("seams"), o.context());
    SeamsDef d;
    c.number("stiffness", d.effect.stiffness, dim::stiffness);
    c.number("max_force", d.effect.max_force, dim::force);
    c.number("damping", d.effect.damping, dim::damping);
    c.number("merge_distance", d.effect.merge_distance, dim::length);
    c.number("zip_distance", d.effect.zip_distance, dim::length);
    c.number("last_stitch_distance", d.effect.last_stitch_distance, dim::length);
    c.integer("last_stitch_frames", d.effect.last_stitch_frames);
    c.number("wait_limit", d.effect.wait_limit, dim::time);
    c.flag("sleeves_first", d.sleeves_first);
    c.flag("merge", d.effect.merge);
    std::string law = "saturating";
    c.string("law", law);
    if (law == "linear") d.effect.law = sim::SeamLaw::linear;
    else if (law == "saturating") d.effect.law = sim::SeamLaw::saturating;
    else o.context().fail(c.at("law"), "unknown law '" + law + "' (use linear or saturating)");
    if (const json* g = c.find("grid")) {
      const auto& l = list(*g, c.at("grid"), o.context());
      for (std::size_t i = 0; i < l.size(); ++i) {
        Object q(l[i], index_path(c.at("grid"), i), o.context());
        GridSeamDef gs;
        const auto side = [&](const std::string& key, std::string& piece, std::string& set) {
          Object s2(q.need(key, "{\"piece\": ..., \"set\": ...}"), q.at(key), o.context());
          piece = text(s2.need("piece"), s2.at("piece"), o.context());
          set = text(s2.need("set", "a grid set such as edge-u1"), s2.at("set"), o.context());
          s2.finish();
        };
        side("a", gs.piece_a, gs.set_a);
        side("b", gs.piece_b, gs.set_b);
        q.flag("reverse", gs.reverse);
        q.finish();
        d.grid.push_back(gs);
      }
    }
    if (c.enabled()) e.seams = d;
    c.finish();
  }
  if (const json* j = o.find("pins")) {
    const auto& l = list(*j, o.at("pins"), o.context());
    for (std::size_t i = 0; i < l.size(); ++i) {
      bool on = true;
      PinGroupDef g = read_pins(Object(l[i], index_path(o.at("pins"), i), o.context()), on);
      if (on) e.pins.push_back(std::move(g));
    }
  }
  o.finish();
  return e;
}

// `effects` decide what a quality preset means (explicit methods without
// contact, implicit Euler with it); fields given with a preset override it.
IntegratorDef read_integrator(Object o, const EffectsDef& effects) {
  IntegratorDef d;
  std::string preset;
  o.string("preset", preset);
  if (!preset.empty()) {
    try {
      d = quality_integrator(parse_quality(preset), has_contact(effects));
    } catch (const std::invalid_argument& e) {
      o.context().fail(o.at("preset"), e.what());
    }
  }
  auto& s = d.settings;
  std::string method;  // default: the preset's, else symplectic Euler ("euler")
  o.string("method", method);
  if (!method.empty()) try {
      s.method = sim::parse_method(method);
    } catch (const std::invalid_argument& e) {
      o.context().fail(o.at("method"), e.what());
    }
  o.number("step", s.step, dim::time);
  if (o.has("step")) d.iterations_per_frame = 0;  // a step given replaces the preset's steps per frame
  o.integer("iterations_per_frame", d.iterations_per_frame);
  if (o.has("step") && o.has("iterations_per_frame"))
    o.context().fail(o.at("iterations_per_frame"),
                     "give either step or iterations_per_frame (the step is then 1 / (fps x iterations))");
  o.flag("auto_substep", s.auto_substep);
  o.number("safety", s.safety, dim::none);
  o.integer("newton_iterations", s.newton_iterations);
  o.number("cg_tolerance", s.cg_tolerance, dim::none);
  o.integer("cg_max_iterations", s.cg_max_iterations);
  o.flag("hold_contacts", s.hold_contacts);
  o.flag("hold_contacts_once_sewn", s.hold_contacts_once_sewn);
  std::string solver;
  o.string("linear_solver", solver);
  if (solver == "cholesky") s.linear_solver = sim::IntegratorSettings::LinearSolver::cholesky;
  else if (solver == "cg" || solver.empty()) s.linear_solver = sim::IntegratorSettings::LinearSolver::cg;
  else o.context().fail(o.at("linear_solver"), "unknown linear solver '" + solver + "' (use cg or cholesky)");
  o.number("rtol", s.rtol, dim::none);
  o.number("atol", s.atol, dim::none);
  o.integer("max_order", s.max_order);
  o.flag("krylov", s.krylov);
  o.number("max_step", s.max_step, dim::time);
  o.number("max_speed", s.max_speed, dim::velocity);
  o.finish();
  return d;
}

std::vector<OutputDef> read_outputs(const json& j, const std::string& path, const Context& c) {
  std::vector<OutputDef> out;
  const auto& l = list(j, path, c);
  for (std::size_t i = 0; i < l.size(); ++i) {
    Object o(l[i], index_path(path, i), c);
    OutputDef d;
    const std::string type = text(o.need("type", "obj or memory"), o.at("type"), c);
    if (type == "obj") {
      d.kind = OutputDef::Kind::obj;
      d.directory = text(o.need("directory", "where frame_0000.obj, ... go"), o.at("directory"), c);
    } else if (type == "memory") {
      d.kind = OutputDef::Kind::memory;
    } else {
      c.fail(o.at("type"), "unknown output type '" + type + "' (use obj or memory)");
    }
    o.finish();
    out.push_back(std::move(d));
  }
  return out;
}

// 1-based line of a byte offset.
int line_of(std::string_view text, std::size_t byte) {
  int line = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

}  // namespace

SceneDef parse_scene(std::string_view json_text, const std::filesystem::path& source) {
  const Context c{source.string()};
  json j;
  try {
    j = json::parse(json_text.begin(), json_text.end());
  } catch (const json::parse_error& e) {
    throw Error(c.file, "", json_error_message(e.what(), "not valid JSON"), line_of(json_text, e.byte));
  } catch (const json::exception& e) {
    // A number too large for a double ("1e999") and the like: out_of_range.
    throw Error(c.file, "", json_error_message(e.what(), "not valid JSON"));
  }

  SceneDef def;
  def.source = source;
  Object top(j, "", c);
  if (const json* v = top.find("version")) {
    if (whole(*v, "version", c) != 1) c.fail("version", "this vgd reads scene files of version 1");
  }
  top.string("name", def.name);
  std::string description;
  top.string("description", description);

  if (const json* m = top.find("materials")) {
    Object mats(*m, "materials", c);
    for (auto it = m->begin(); it != m->end(); ++it) {
      mats.find(it.key());
      def.materials[it.key()] = read_material(*it, mats.at(it.key()), c);
    }
  }
  if (const json* a = top.find("avatar")) def.avatar = read_avatar(Object(*a, "avatar", c));
  const json& cloth = top.need("cloth", "a list of cloth pieces");
  const auto& l = list(cloth, "cloth", c);
  for (std::size_t i = 0; i < l.size(); ++i) def.cloth.push_back(read_cloth(Object(l[i], index_path("cloth", i), c), def));
  if (const json* e = top.find("effects")) def.effects = read_effects(Object(*e, "effects", c));
  if (const json* s = top.find("integrator"))
    def.integrator = read_integrator(Object(*s, "integrator", c), def.effects);
  if (const json* f = top.find("frames")) {
    Object fr(*f, "frames", c);
    fr.number("fps", def.run.fps, dim::rate);
    fr.number("duration", def.run.duration, dim::time);
    fr.number("rest_energy", def.run.rest_energy, dim::energy);
    fr.integer("rest_frames", def.run.rest_frames);
    fr.number("start_jitter", def.run.start_jitter, dim::length);
    int seed = static_cast<int>(def.run.start_jitter_seed);
    fr.integer("start_jitter_seed", seed);
    def.run.start_jitter_seed = static_cast<unsigned>(std::max(seed, 0));
    fr.finish();
  }
  if (const json* o = top.find("output")) def.outputs = read_outputs(*o, "output", c);
  top.finish();

  validate(def);
  return def;
}

SceneDef load_scene(const std::filesystem::path& file) { return parse_scene(read_file(file), file); }

}  // namespace vgd::scene
