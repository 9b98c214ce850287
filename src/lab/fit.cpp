// Fabric fingerprints: measurements → model parameters by least squares →
// XVC MATERIAL (include/vgd/lab/fit.hpp, docs/fabric-lab.md).
#include "vgd/lab/fit.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/LevenbergMarquardt>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/lab/lab.hpp"
#include "vgd/scene/units.hpp"
#include "vgd/xvc/document.hpp"
#include "vgd/xvc/io.hpp"

namespace vgd::lab {

using scene::Dimension;
using scene::find_material_parameter;
using scene::parse_quantity;
using scene::parse_unit;
using scene::si_name;
namespace dim = scene::dim;

namespace {

constexpr double kGravity = 9.81;  // m/s², as the lab's cantilever
// The shipped fabrics' mass-spring convention (data/materials/*.xvc): a bending
// spring of 10 N/m stands for B = 1e-5 N·m, so B = spring.bend × 1e-6 m².
constexpr double kBendScale = 1e-6;
constexpr const char* kHeader = "quantity,direction,x,value,unit";

struct MeasureInfo {
  Measure kind;
  const char* name;
  Dimension dimension;
  bool directional;
};
constexpr MeasureInfo kMeasures[] = {
    {Measure::weight, "weight", dim::areal_density, false},
    {Measure::thickness, "thickness", dim::length, false},
    {Measure::tensile, "tensile", dim::stiffness, true},
    {Measure::tensile_modulus, "tensile_modulus", dim::stiffness, true},
    {Measure::bending_rigidity, "bending_rigidity", dim::moment, true},
    {Measure::bending_length, "bending_length", dim::length, true},
    {Measure::shear_rigidity, "shear_rigidity", dim::stiffness, true},
};

const MeasureInfo& info(Measure m) {
  for (const auto& i : kMeasures)
    if (i.kind == m) return i;
  return kMeasures[0];
}

std::string known_quantities() {
  std::string s;
  for (const auto& i : kMeasures) s += (s.empty() ? "" : ", ") + std::string(i.name);
  return s;
}

}  // namespace

const char* to_string(Measure m) { return info(m).name; }

std::vector<Measurement> read_measurements(const std::filesystem::path& file, std::size_t max_rows) {
  return parse_measurements(read_file(file), file.string(), max_rows);
}

std::vector<Measurement> parse_measurements(std::string_view text_of_file, const std::string& f,
                                            std::size_t max_rows) {
  const std::vector<std::string> lines = split(text_of_file, '\n');
  std::vector<Measurement> out;
  bool header = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    const std::string text(trim(lines[i]));
    if (text.empty() || text[0] == '#') continue;
    std::vector<std::string> fields = split(text, ',');
    for (auto& s : fields) s = std::string(trim(s));
    if (!header) {
      std::string got;
      for (const auto& s : fields) got += (got.empty() ? "" : ",") + s;
      if (got != kHeader)
        throw Error(f, "header", "the first line must be '" + std::string(kHeader) + "' (got '" + text + "')", line);
      header = true;
      continue;
    }
    if (out.size() == max_rows)
      throw Error(f, "", "more than " + std::to_string(max_rows) +
                             " measurements (--max-rows): thin a tensile curve to the points that shape it", line);
    if (fields.size() != 5)
      throw Error(f, "", "expected 5 fields (" + std::string(kHeader) + "), got " + std::to_string(fields.size()),
                  line);
    const MeasureInfo* kind = nullptr;
    for (const auto& k : kMeasures)
      if (fields[0] == k.name) kind = &k;
    if (!kind) throw Error(f, fields[0], "unknown quantity '" + fields[0] + "' (" + known_quantities() + ")", line);
    const std::string entity = fields[0];
    Measurement m;
    m.kind = kind->kind, m.line = line;
    // direction
    const std::string& d = fields[1];
    if (!kind->directional) {
      if (!d.empty()) throw Error(f, entity, entity + " has no direction: leave the field empty (got '" + d + "')", line);
    } else if (d.empty()) {
      if (m.kind != Measure::shear_rigidity)
        throw Error(f, entity, entity + " needs a direction: warp, weft, bias or an angle from the warp in degrees",
                    line);
    } else if (d == "warp") m.angle_deg = 0.0;
    else if (d == "weft") m.angle_deg = 90.0;
    else if (d == "bias") m.angle_deg = 45.0;
    else if (const auto a = parse_double(d); a && *a >= 0.0 && *a <= 90.0) m.angle_deg = *a;
    else throw Error(f, entity, "direction '" + d + "' is not warp, weft, bias or an angle of 0 to 90 degrees", line);
    // x: the strain of a tensile point
    if (m.kind == Measure::tensile) {
      const auto x = parse_quantity(fields[2]);
      if (!x || x->dimension != dim::none || !(x->value >= 0.0))
        throw Error(f, entity, "x must be the engineering strain, a number >= 0 such as 0.01 or 1% (got '" +
                                   fields[2] + "')", line);
      m.x = x->value;
    } else if (!fields[2].empty()) {
      throw Error(f, entity, "x is only for tensile points (the strain); leave it empty (got '" + fields[2] + "')",
                  line);
    }
    // value and unit
    const auto v = parse_double(fields[3]);
    if (!v) throw Error(f, entity, "the value '" + fields[3] + "' is not a number", line);
    const bool zero_ok = m.kind == Measure::tensile && m.x == 0.0;  // a curve's origin
    if (!(*v > 0.0) && !(zero_ok && *v == 0.0))
      throw Error(f, entity, "the value must be > 0 (got " + fields[3] + ")", line);
    double factor = 1.0;
    if (!fields[4].empty()) {
      const auto u = parse_unit(fields[4]);
      if (!u) throw Error(f, entity, "unknown unit '" + fields[4] + "'", line);
      if (u->dimension != kind->dimension)
        throw Error(f, entity, "the unit '" + fields[4] + "' is " + si_name(u->dimension) + ", but " + entity +
                                   " needs " + si_name(kind->dimension), line);
      factor = u->value;
    }
    m.value = *v * factor;
    if (m.kind == Measure::tensile && (m.x == 0.0) != (m.value == 0.0))
      throw Error(f, entity, "a tensile point at zero strain must have zero stress and the other way round", line);
    out.push_back(m);
  }
  if (!header) throw Error(f, "", "no header line '" + std::string(kHeader) + "' and no measurements");
  if (out.empty()) throw Error(f, "", "no measurements after the header");
  return out;
}

double predict(const Measurement& m, const scene::MaterialDef& mat, scene::ClothModel model) {
  const double nan = std::nan("");
  const double theta = m.angle_deg * std::numbers::pi / 180.0;
  if (m.kind == Measure::weight) return mat.density;
  if (m.kind == Measure::thickness) return mat.thickness > 0.0 ? mat.thickness : nan;
  if (model == scene::ClothModel::strain_rosette) {
    if (!mat.orthotropic) return nan;
    const sim::OrthotropicMaterial o = scene::orthotropic_of(mat);
    switch (m.kind) {
      case Measure::tensile: return sim::off_axis_modulus(o, theta) * m.x;
      case Measure::tensile_modulus: return sim::off_axis_modulus(o, theta);
      case Measure::bending_rigidity: return sim::bending_rigidity(o, theta);
      case Measure::bending_length: return std::cbrt(sim::bending_rigidity_strip(o, theta) / (mat.density * kGravity));
      case Measure::shear_rigidity: return simple_shear_modulus(o, m.angle_deg);
      default: return nan;
    }
  }
  // Mass-spring: closed forms along the yarns only (the lattice's sheet
  // modulus E = spring + shear + 4 bend, as the shipped files' rule; G =
  // spring.shear); off the yarns the blended springs have none.
  if (!mat.mass_spring || (m.angle_deg != 0.0 && m.angle_deg != 90.0)) return nan;
  const auto& s = *mat.mass_spring;
  const bool warp = m.angle_deg == 0.0;
  const double E = (warp ? s.warp : s.weft) + s.shear + 4 * (warp ? s.bend_warp : s.bend_weft);
  const double B = (warp ? s.bend_warp : s.bend_weft) * kBendScale;
  switch (m.kind) {
    case Measure::tensile: return E * m.x;
    case Measure::tensile_modulus: return E;
    case Measure::bending_rigidity: return B;
    case Measure::bending_length: return std::cbrt(B / (mat.density * kGravity));
    case Measure::shear_rigidity: return s.shear;
    default: return nan;
  }
}

namespace {

// One parameter of the fit. Positive ones are fitted as logarithms (they span
// decades and must stay positive); ν as itself.
struct Param {
  std::string name, unit;
  double value = 0.0;  // SI
  bool log = true, required = true;
  std::string need;    // what measurement determines it, for the message when none does
  bool free = false;
};

double mean_of(const std::vector<Measurement>& ms, auto pick, double fallback) {
  double sum = 0.0;
  int n = 0;
  for (const auto& m : ms)
    if (const auto v = pick(m)) sum += *v, ++n;
  return n ? sum / n : fallback;
}

// Starting values read directly from the measurements where one gives a
// parameter alone (modulus along a yarn, G, B, weight), else the shirting's.
std::vector<Param> start(const std::vector<Measurement>& ms, scene::ClothModel model) {
  auto along = [&](Measure kind, double angle, double fallback) {
    return mean_of(ms, [&](const Measurement& m) -> std::optional<double> {
      if (m.angle_deg != angle) return std::nullopt;
      if (kind == Measure::tensile_modulus && m.kind == Measure::tensile && m.x > 0.0) return m.value / m.x;
      if (m.kind == kind) return m.value;
      return std::nullopt;
    }, fallback);
  };
  const double density = along(Measure::weight, 0.0, 0.2);
  auto bending = [&](double angle, double fallback) {
    const double c = along(Measure::bending_length, angle, 0.0);
    return c > 0.0 ? density * kGravity * c * c * c : along(Measure::bending_rigidity, angle, fallback);
  };
  const double E_warp = along(Measure::tensile_modulus, 0.0, 5000.0);
  const double E_weft = along(Measure::tensile_modulus, 90.0, 0.6 * E_warp);
  const double G = along(Measure::shear_rigidity, 0.0, 0.08 * E_warp);
  const double B_warp = bending(0.0, 1e-5), B_weft = bending(90.0, 0.6 * B_warp);
  const double thickness = along(Measure::thickness, 0.0, 0.0005);
  const std::string tensile = "a tensile or tensile_modulus measurement", bend = "a bending_rigidity or bending_length";
  if (model == scene::ClothModel::strain_rosette)
    return {{"E_warp", "N/m", E_warp, true, true, tensile + " (warp)"},
            {"E_weft", "N/m", E_weft, true, true, tensile + " (weft)"},
            {"G", "N/m", G, true, true, "a shear_rigidity or a bias tensile_modulus"},
            {"nu_warp_weft", "1", 0.3, false, false, "tensile moduli at 0, 90 deg and off-axis with a shear_rigidity"},
            {"B_warp", "N.m", B_warp, true, true, bend + " along the warp"},
            {"B_weft", "N.m", B_weft, true, true, bend + " along the weft"},
            {"D_twist", "N.m", G * thickness * thickness / 12, true, false, "bending off the yarns"},
            {"density", "kg/m2", density, true, true, "a weight"},
            {"thickness", "m", thickness, true, false, "a thickness"}};
  const double bend_warp = B_warp / kBendScale, bend_weft = B_weft / kBendScale;
  return {{"spring.warp", "N/m", std::max(E_warp - G - 4 * bend_warp, 0.1 * E_warp), true, true, tensile + " along the warp"},
          {"spring.weft", "N/m", std::max(E_weft - G - 4 * bend_weft, 0.1 * E_weft), true, true, tensile + " along the weft"},
          {"spring.shear", "N/m", G, true, true, "a shear_rigidity along a yarn"},
          {"spring.bend_warp", "N/m", bend_warp, true, true, bend + " along the warp"},
          {"spring.bend_weft", "N/m", bend_weft, true, true, bend + " along the weft"},
          {"density", "kg/m2", density, true, true, "a weight"},
          {"thickness", "m", thickness, true, false, "a thickness"}};
}

// The material of the parameters (SI values); held optional ones keep their defaults.
// `file` (the measurements) names the fit in messages.
scene::MaterialDef material_of(const std::vector<Param>& ps, scene::ClothModel model, bool have_thickness,
                               const std::string& file) {
  scene::MaterialDef m;
  for (const auto& p : ps) {
    if (!p.free && !p.required && p.name != "nu_warp_weft") continue;  // derived / not given
    if (p.name == "thickness" && !have_thickness) continue;
    if (!std::isfinite(p.value))
      throw Error(file, p.name,
                  "the fit drove it to a value that is not a finite number: the measurements contradict each other "
                  "or do not determine it (check their units and directions)");
    set_material_parameter(m, p.name, p.value, find_material_parameter(p.name)->dimension, file, p.name);
  }
  if (model == scene::ClothModel::mass_spring && m.mass_spring) m.mass_spring->damping = 0.005;  // as the shipped fabrics
  return m;
}

// Relative residuals of the used measurements (NaN-free: unused ones are skipped by the caller).
struct Problem : Eigen::DenseFunctor<double> {
  std::vector<Param>* params;
  std::vector<int> free;  // indices into params
  const std::vector<Measurement>* used;
  scene::ClothModel model;
  bool have_thickness;
  std::string file;
  Problem(std::vector<Param>& ps, std::vector<int> f, const std::vector<Measurement>& u, scene::ClothModel mo, bool th,
          std::string fi)
      : Eigen::DenseFunctor<double>(static_cast<int>(f.size()), static_cast<int>(u.size())),
        params(&ps), free(std::move(f)), used(&u), model(mo), have_thickness(th), file(std::move(fi)) {}
  void set(const Eigen::VectorXd& x) const {
    for (std::size_t k = 0; k < free.size(); ++k) {
      Param& p = (*params)[free[k]];
      p.value = p.log ? std::exp(x[k]) : x[k];
    }
  }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
    set(x);
    const scene::MaterialDef m = material_of(*params, model, have_thickness, file);
    for (std::size_t i = 0; i < used->size(); ++i) {
      const Measurement& ms = (*used)[i];
      r[i] = predict(ms, m, model) / ms.value - 1.0;
    }
    return 0;
  }
  // Central differences: the forward formulas are smooth and cheap.
  int df(const Eigen::VectorXd& x, Eigen::MatrixXd& J) const {
    Eigen::VectorXd a(values()), b(values());
    for (int k = 0; k < inputs(); ++k) {
      const double h = 1e-6 * std::max(1.0, std::abs(x[k]));
      Eigen::VectorXd xp = x, xm = x;
      xp[k] += h, xm[k] -= h;
      (*this)(xp, a), (*this)(xm, b);
      J.col(k) = (a - b) / (2 * h);
    }
    set(x);
    return 0;
  }
};

Eigen::VectorXd unknowns(const std::vector<Param>& ps, const std::vector<int>& free) {
  Eigen::VectorXd x(free.size());
  for (std::size_t k = 0; k < free.size(); ++k) x[k] = ps[free[k]].log ? std::log(ps[free[k]].value) : ps[free[k]].value;
  return x;
}

// Seven significant digits, what the XVC file holds.
double rounded(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.7g", v);
  return std::strtod(b, nullptr);
}

}  // namespace

FitResult fit(const std::vector<Measurement>& ms, scene::ClothModel model, const std::string& id, const std::string& file) {
  FitResult result;
  result.model = model;
  std::vector<Param> ps = start(ms, model);
  const bool have_thickness =
      std::any_of(ms.begin(), ms.end(), [](const Measurement& m) { return m.kind == Measure::thickness; });
  // The measurements the model can predict and that carry information (a
  // curve's origin does not).
  std::vector<Measurement> used;
  {
    for (auto& p : ps) p.free = p.required || (p.name == "thickness" && have_thickness);
    const scene::MaterialDef m0 = material_of(ps, model, have_thickness, file);
    for (const auto& m : ms) {
      if (m.value == 0.0) continue;
      if (std::isnan(predict(m, m0, model))) {
        result.notes.push_back("line " + std::to_string(m.line) + ": " + to_string(m.kind) + " at " +
                               format_fixed(m.angle_deg, 1) + " deg not used: the " + to_string(model) +
                               " model has no forward formula for it");
        continue;
      }
      used.push_back(m);
    }
  }
  // Which parameters the measurements determine: add them one by one (the
  // needed ones first) while the Jacobian's columns, each scaled to unit
  // length, stay independent; a needed one that is not determined is an error,
  // an optional one keeps its default.
  std::vector<int> all(ps.size());
  for (std::size_t k = 0; k < ps.size(); ++k) all[k] = static_cast<int>(k), ps[k].free = true;
  Eigen::MatrixXd J(used.size(), ps.size());
  if (!used.empty()) Problem(ps, all, used, model, have_thickness, file).df(unknowns(ps, all), J);
  std::vector<int> free;
  for (bool required : {true, false})
    for (std::size_t k = 0; k < ps.size(); ++k) {
      Param& p = ps[k];
      if (p.required != required) continue;
      p.free = false;
      if (p.name == "thickness" && !have_thickness) continue;
      std::vector<int> trial = free;
      trial.push_back(static_cast<int>(k));
      Eigen::MatrixXd A(used.size(), trial.size());
      bool independent = !used.empty();
      for (std::size_t c = 0; c < trial.size() && independent; ++c) {
        const double norm = J.col(trial[c]).norm();
        independent = norm > 1e-12;
        if (independent) A.col(c) = J.col(trial[c]) / norm;
      }
      if (independent) {
        Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
        qr.setThreshold(1e-6);
        independent = qr.rank() == static_cast<Eigen::Index>(trial.size());
      }
      if (independent) {
        free = trial, p.free = true;
      } else if (required) {
        throw Error(file, p.name,
                    "the measurements do not determine " + p.name + " (" + to_string(model) + " model): add " + p.need);
      } else if (p.name == "nu_warp_weft") {
        result.notes.push_back("nu_warp_weft not determined by these measurements: held at 0.3 (add " + p.need + ")");
      } else if (p.name == "D_twist") {
        result.notes.push_back("D_twist not determined (no bending off the yarns): derived, G thickness^2 / 12");
      }
    }
  Problem problem(ps, free, used, model, have_thickness, file);
  Eigen::VectorXd x = unknowns(ps, free);
  Eigen::LevenbergMarquardt<Problem> lm(problem);
  lm.setXtol(1e-14), lm.setFtol(1e-16), lm.setMaxfev(5000);
  lm.minimize(x);
  problem.set(x);
  result.iterations = static_cast<int>(lm.iterations());
  for (int k : free) result.fitted.push_back(ps[k].name), ps[k].value = rounded(ps[k].value);
  result.material = material_of(ps, model, have_thickness, file);
  result.material.name = id;
  if (model == scene::ClothModel::mass_spring)
    result.notes.push_back("spring.damping not fitted (statics do not see it): 0.005 kg/s as the shipped fabrics");
  double sum = 0.0;
  for (const auto& m : ms) {
    const bool is_used = std::any_of(used.begin(), used.end(), [&](const Measurement& u) { return u.line == m.line; });
    const double fitted = predict(m, result.material, model);
    const double rel = is_used ? fitted / m.value - 1.0 : std::nan("");
    if (is_used) sum += rel * rel;
    result.residuals.push_back({m, fitted, rel});
  }
  result.rms_rel_residual = used.empty() ? 0.0 : std::sqrt(sum / used.size());
  if (const std::string problem_text = model == scene::ClothModel::strain_rosette ? scene::orthotropic_problem(result.material)
                                                                            : scene::mass_spring_problem(result.material);
      !problem_text.empty())
    throw Error(file, id, "the fitted material is not usable: " + problem_text);
  return result;
}

std::string describe(const FitResidual& r) {
  const Measurement& m = r.measurement;
  char b[200];
  std::snprintf(b, sizeof b, "%d %s%s%s: measured %.7g, fitted %.7g, ", m.line, to_string(m.kind),
                info(m.kind).directional ? (" " + format_double(m.angle_deg) + " deg").c_str() : "",
                m.kind == Measure::tensile ? (" strain " + format_double(m.x)).c_str() : "", m.value, r.fitted);
  std::string s = b;
  if (std::isnan(r.rel_residual)) return s + "not used";
  std::snprintf(b, sizeof b, "%+.2e", r.rel_residual);
  return s + b;
}

std::string material_xvc(const FitResult& f, const std::string& id, const std::string& source) {
  xvc::Node material{"MATERIAL", {{"id", id}, {"name", id + " (fitted by vgd lab fit)"}}, {}};
  const scene::MaterialDef& m = f.material;
  std::vector<std::pair<std::string, double>> values;
  if (m.thickness > 0.0) values.emplace_back("thickness", m.thickness);
  values.emplace_back("density", m.density);
  if (m.orthotropic) {
    const auto& o = *m.orthotropic;
    values.insert(values.end(), {{"E_warp", o.E_warp}, {"E_weft", o.E_weft}, {"G", o.G},
                                 {"nu_warp_weft", o.nu_warp_weft}, {"B_warp", o.B_warp}, {"B_weft", o.B_weft}});
    if (!std::isnan(o.D_twist)) values.emplace_back("D_twist", o.D_twist);
  }
  if (m.mass_spring) {
    const auto& s = *m.mass_spring;
    values.insert(values.end(), {{"spring.warp", s.warp}, {"spring.weft", s.weft}, {"spring.shear", s.shear},
                                 {"spring.bend_warp", s.bend_warp}, {"spring.bend_weft", s.bend_weft},
                                 {"spring.damping", s.damping}});
  }
  int n = 0;
  for (const auto& [name, value] : values) {
    char b[32];
    std::snprintf(b, sizeof b, "%.7g", value);
    material.children.push_back({"PARAMETER",
                                 {{"id", "param" + std::to_string(++n)},
                                  {"name", name},
                                  {"value", b},
                                  {"unit", std::string(find_material_parameter(name)->unit)}},
                                 {}});
  }
  xvc::Node root = xvc::Document().root();
  for (auto& c : root.children)
    if (c.tag == "MATERIALS") c.children.push_back(material);
  root.set_attribute("name", id);
  std::string xml = xvc::save_string(xvc::Document(std::move(root), id));
  // A header comment (not kept by XVC loaders): where the values come from and how well they fit.
  std::string comment = "<!--\n  " + id + ": fitted by vgd lab fit (" + to_string(f.model) + " model) from " + source +
                        ".\n  Fitted: ";
  for (std::size_t k = 0; k < f.fitted.size(); ++k) comment += (k ? ", " : "") + f.fitted[k];
  char rms[32];
  std::snprintf(rms, sizeof rms, "%.2e", f.rms_rel_residual);
  comment += ". RMS relative residual " + std::string(rms) + ".\n";
  for (const auto& note : f.notes) comment += "  " + note + "\n";
  comment += "  Residuals (fitted / measured - 1), by line of the measurements:\n";
  for (const auto& r : f.residuals) comment += "    line " + describe(r) + "\n";
  comment += "-->\n";
  const auto end_of_declaration = xml.find("?>\n");
  xml.insert(end_of_declaration == std::string::npos ? 0 : end_of_declaration + 3, comment);
  return xml;
}

void write_material_xvc(const FitResult& f, const std::filesystem::path& file, const std::string& source) {
  write_file_atomic(file, material_xvc(f, file.stem().string(), source));
}

}  // namespace vgd::lab
