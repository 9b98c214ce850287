// Materials: the parameter vocabulary shared by scene files and XVC MATERIAL
// modules, unit conversion, and reading a MATERIAL from an XVC document.
#include "vgd/scene/material.hpp"

#include <array>
#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/xvc/document.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::scene {

namespace {

constexpr std::array<MaterialParameter, 21> kParameters{{
    {"density", dim::areal_density, "kg/m2",
     "areal density: lumped particle masses are triangle area x density / 3 (cotton shirting ~0.12 kg/m2); "
     "kg/m3 is multiplied by thickness"},
    {"thickness", dim::length, "m", "fabric thickness (~0.0005 m); converts Pa and kg/m3 values"},
    {"particle_mass", dim::mass, "kg",
     "mass of every particle, mass-spring model only (seed 000's flag: 0.1 kg); overrides density"},
    {"spring.warp", dim::stiffness, "N/m", "mass-spring: structural springs along the warp (seed: 1800 N/m)"},
    {"spring.weft", dim::stiffness, "N/m", "mass-spring: structural springs along the weft (seed: 1800 N/m)"},
    {"spring.shear", dim::stiffness, "N/m", "mass-spring: springs on the bias (seed: 400 N/m)"},
    {"spring.bend_warp", dim::stiffness, "N/m", "mass-spring: bending springs two apart along the warp (seed: 400 N/m)"},
    {"spring.bend_weft", dim::stiffness, "N/m", "mass-spring: bending springs two apart along the weft (seed: 400 N/m)"},
    {"spring.damping", dim::damping, "kg/s", "mass-spring: damping k_d of every spring, N.s/m (seed: 0.1)"},
    {"spring.max_strain", dim::none, "1",
     "mass-spring: Provot's limit, warp and weft springs never stretch beyond (1 + max_strain) x rest (0 = off)"},
    {"strain_limit", dim::none, "1",
     "either model: after each step no triangle stretches along the warp or the weft beyond (1 + strain_limit) x "
     "rest, where the yarns lock (wovens ~0.05-0.1; 0 = none)"},
    {"E_warp", dim::stiffness, "N/m",
     "strain rosette: sheet Young's modulus along the warp (1e3-2e4 N/m); Pa is multiplied by thickness"},
    {"E_weft", dim::stiffness, "N/m", "strain rosette: sheet Young's modulus along the weft (1e3-2e4 N/m)"},
    {"G", dim::stiffness, "N/m", "strain rosette: in-plane sheet shear modulus (20-500 N/m)"},
    {"nu_warp_weft", dim::none, "1", "strain rosette: Poisson ratio, weft contraction under warp stress (0.1-0.5)"},
    {"nu_weft_warp", dim::none, "1", "strain rosette: Poisson ratio the other way; default from reciprocity"},
    {"residual_warp", dim::none, "1", "strain rosette: stress-free strain along the warp, as cut (typically 0)"},
    {"residual_weft", dim::none, "1", "strain rosette: stress-free strain along the weft, as cut (typically 0)"},
    {"B_warp", dim::moment, "N.m", "bending rigidity along the warp (2e-6-5e-5 N.m, FAST-2)"},
    {"B_weft", dim::moment, "N.m", "bending rigidity along the weft (2e-6-5e-5 N.m)"},
    {"D_twist", dim::moment, "N.m", "twisting rigidity; default G thickness^2 / 12"},
}};

std::string fmt(double v) { return format_double(v); }

sim::MassSpringMaterial& springs(MaterialDef& m) {
  if (!m.mass_spring) m.mass_spring.emplace();
  return *m.mass_spring;
}

sim::OrthotropicMaterial& membrane(MaterialDef& m) {
  if (!m.orthotropic) m.orthotropic.emplace();
  return *m.orthotropic;
}

}  // namespace

std::span<const MaterialParameter> material_parameters() { return kParameters; }

const MaterialParameter* find_material_parameter(std::string_view name) {
  for (const auto& p : kParameters)
    if (p.name == name) return &p;
  return nullptr;
}

void set_material_parameter(MaterialDef& m, std::string_view name, double v, const Dimension& d,
                            const std::string& file, const std::string& entity) {
  const MaterialParameter* p = find_material_parameter(name);
  if (!p) {
    std::string known;
    for (const auto& k : kParameters) known += (known.empty() ? "" : ", ") + std::string(k.name);
    throw Error(file, entity, "unknown material parameter '" + std::string(name) + "' (known: " + known + ")");
  }
  // Per-volume values become per-area ones through the thickness.
  if (d != p->dimension) {
    const bool per_volume = (p->dimension == dim::areal_density && d == dim::density) ||
                            (p->dimension == dim::stiffness && d == dim::pressure);
    if (!per_volume)
      throw Error(file, entity,
                  "the unit is " + si_name(d) + ", but " + std::string(name) + " needs " + std::string(p->unit) +
                      (p->dimension == dim::stiffness ? " (or Pa with a thickness)"
                       : p->dimension == dim::areal_density ? " (or kg/m3 with a thickness)"
                                                            : ""));
    if (!(m.thickness > 0.0))
      throw Error(file, entity,
                  std::string(name) + " is given per volume (" + si_name(d) +
                      ") but the material has no thickness to convert it; add a thickness parameter (m) before it");
    v *= m.thickness;
  }
  if (!std::isfinite(v)) throw Error(file, entity, std::string(name) + " is not a finite number");
  auto positive = [&] {
    if (!(v > 0.0)) throw Error(file, entity, std::string(name) + " must be > 0 (got " + fmt(v) + ")");
  };
  auto non_negative = [&] {
    if (!(v >= 0.0)) throw Error(file, entity, std::string(name) + " must be >= 0 (got " + fmt(v) + ")");
  };
  if (name == "density") positive(), m.density = v;
  else if (name == "thickness") positive(), m.thickness = v;
  else if (name == "particle_mass") positive(), m.particle_mass = v;
  else if (name == "spring.warp") non_negative(), springs(m).warp = v;
  else if (name == "spring.weft") non_negative(), springs(m).weft = v;
  else if (name == "spring.shear") non_negative(), springs(m).shear = v;
  else if (name == "spring.bend_warp") non_negative(), springs(m).bend_warp = v;
  else if (name == "spring.bend_weft") non_negative(), springs(m).bend_weft = v;
  else if (name == "spring.damping") non_negative(), springs(m).damping = v;
  else if (name == "spring.max_strain") non_negative(), springs(m).max_strain = v;
  else if (name == "strain_limit") non_negative(), m.strain_limit = v;
  else if (name == "E_warp") positive(), membrane(m).E_warp = v;
  else if (name == "E_weft") positive(), membrane(m).E_weft = v;
  else if (name == "G") positive(), membrane(m).G = v;
  else if (name == "nu_warp_weft") membrane(m).nu_warp_weft = v;
  else if (name == "nu_weft_warp") membrane(m).nu_weft_warp = v;
  else if (name == "residual_warp") membrane(m).residual_warp = v;
  else if (name == "residual_weft") membrane(m).residual_weft = v;
  else if (name == "B_warp") positive(), membrane(m).B_warp = v;
  else if (name == "B_weft") positive(), membrane(m).B_weft = v;
  else if (name == "D_twist") positive(), membrane(m).D_twist = v;
}

MaterialDef material_from_xvc(const xvc::Document& doc, std::string_view id, const std::string& file) {
  const xvc::Node* node = doc.find(id);
  if (!node) {
    std::string known;
    if (const auto* c = doc.container("MATERIALS"))
      for (const auto& mat : c->children) known += (known.empty() ? "" : ", ") + std::string(mat.id());
    throw Error(file, std::string(id),
                "no MATERIAL with this id in the document" + (known.empty() ? std::string(" (it has none)")
                                                                            : " (materials: " + known + ")"));
  }
  if (node->tag != "MATERIAL")
    throw Error(file, std::string(id), std::string(id) + " is a " + node->tag + ", not a MATERIAL", node->line);
  MaterialDef m;
  m.name = std::string(node->attribute("name"));
  if (m.name.empty()) m.name = std::string(id);
  // The thickness first: per-volume values are converted with it.
  for (int pass = 0; pass < 2; ++pass)
    for (const auto& p : node->children) {
      if (p.tag != "PARAMETER") continue;
      const std::string name(p.attribute("name"));
      if ((name == "thickness") != (pass == 0)) continue;
      const std::string entity = "MATERIAL " + std::string(id) + ", PARAMETER " + name;
      const auto value = parse_double(p.attribute("value"));
      if (!value) throw Error(file, entity, "the value is not a number", p.line);
      const auto unit = parse_unit(p.attribute("unit"));
      if (!unit) throw Error(file, entity, "unknown unit '" + std::string(p.attribute("unit")) + "'", p.line);
      try {
        set_material_parameter(m, name, *value * unit->value, unit->dimension, file, entity);
      } catch (const Error& e) {
        Diagnostic d = e.diagnostic();
        d.line = p.line;
        throw Error(d);
      }
    }
  return m;
}

MaterialDef load_xvc_material(const std::filesystem::path& file, std::string_view id) {
  const auto doc = xvc::load_file(file);
  return material_from_xvc(doc, id, file.string());
}

std::string mass_spring_problem(const MaterialDef& m) {
  if (!m.mass_spring) return "it has no mass-spring values (spring.warp, spring.weft, spring.shear, ...)";
  if (!(m.particle_mass > 0.0) && !(m.density > 0.0)) return "it has neither particle_mass nor density";
  return "";
}

sim::OrthotropicMaterial orthotropic_of(const MaterialDef& m) {
  sim::OrthotropicMaterial o = m.orthotropic.value_or(sim::OrthotropicMaterial{});
  if (m.density > 0.0) o.density = m.density;
  if (m.thickness > 0.0) o.thickness = m.thickness;
  return o;
}

std::string orthotropic_problem(const MaterialDef& m) {
  if (!m.orthotropic) return "it has no membrane values (E_warp, E_weft, G, B_warp, B_weft, ...)";
  if (!(m.density > 0.0)) return "it has no density";
  const auto p = sim::problems(orthotropic_of(m));
  std::string all;
  for (const auto& s : p) all += (all.empty() ? "" : "; ") + s;
  return all;
}

MaterialDef layered(const MaterialDef& m, int layers) {
  MaterialDef out = m;
  const double n = layers;
  out.name = m.name + " (" + std::to_string(layers) + " layers)";
  out.density *= n;
  out.particle_mass *= n;
  out.thickness *= n;
  if (out.mass_spring) {
    auto& s = *out.mass_spring;
    s.warp *= n, s.weft *= n, s.shear *= n, s.bend_warp *= n, s.bend_weft *= n, s.damping *= n;
  }
  if (out.orthotropic) {
    auto& o = *out.orthotropic;
    // Unbonded plies twist each on its own: n times one ply's D66 (derived
    // from the sum's G and thickness it would be n^3 times).
    o.D_twist = n * sim::twist_rigidity(orthotropic_of(m));
    o.E_warp *= n, o.E_weft *= n, o.G *= n, o.B_warp *= n, o.B_weft *= n;
    for (auto* c : {&o.curve_warp, &o.curve_weft})
      for (auto& v : c->stress) v *= n;
    o.density *= n;
    o.thickness *= n;
  }
  return out;
}

MaterialDef piece_fabric(const xvc::Document& garment, std::string_view piece, const MaterialDef& garment_fabric,
                         const std::string& file) {
  for (const xvc::Node* p : garment.patterns())
    if (p->attribute("block") == piece || p->attribute("piece") == piece) {
      const std::string own = xvc::piece_material(garment, *p);
      return own.empty() ? garment_fabric : material_from_xvc(garment, own, file);
    }
  return garment_fabric;
}

}  // namespace vgd::scene
