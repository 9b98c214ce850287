// The virtual fabric lab: specimens, static equilibrium, measurement and
// comparison (include/vgd/scene/lab.hpp, docs/fabric-lab.md). The physics is
// the engine's effects; the lab only cuts, holds, loads and reads.
#include "vgd/scene/lab.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/scene/data.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/bending.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/strain_rosette.hpp"

namespace vgd::scene::lab {

namespace fs = std::filesystem;
using sim::Vec2;
using sim::VecX;

const char* to_string(Test t) {
  switch (t) {
    case Test::tip_cantilever: return "tip-cantilever";
    case Test::tensile: return "tensile";
    case Test::cantilever: return "cantilever";
    case Test::buckling: return "buckling";
  }
  return "?";
}

Test parse_test(const std::string& s) {
  for (Test t : {Test::tip_cantilever, Test::tensile, Test::cantilever, Test::buckling})
    if (s == to_string(t)) return t;
  throw std::invalid_argument("unknown lab test '" + s + "' (tip-cantilever, tensile, cantilever, buckling)");
}

MaterialDef lab_material(const std::string& name_or_file) {
  const fs::path given(name_or_file);
  const fs::path file = fs::is_regular_file(given) ? given : data_file("materials/" + name_or_file + ".xvc");
  return load_xvc_material(file, file.stem().string());
}

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kGravity = 9.81;  // m/s²

// ---- the specimen -------------------------------------------------------------

// A strip along x in the plane z = 0, nu × nv particles, spacing h along and
// w_cell across, its first particle at (x0, 0, 0). The warp runs at `angle`
// (rad) from the strip's axis: uv = R(−angle)·(x, y) expressed in the
// warp/weft frame, so the axis reads (cos angle, sin angle) in the pattern.
struct Specimen {
  sim::Model model;
  std::vector<std::unique_ptr<sim::Effect>> effects;
  int nu = 0, nv = 0;
  double h = 0.0, w_cell = 0.0;
  int index(int i, int j) const { return j * nu + i; }
};

Specimen make_specimen(const LabSpec& spec, const MaterialDef& mat, int nu, int nv, double h, double width,
                       double x0) {
  Specimen s;
  s.nu = nu, s.nv = nv, s.h = h, s.w_cell = width / (nv - 1);
  s.model = sim::make_grid(nu, nv, h, s.w_cell, sim::Vec3(x0, 0, 0), sim::Vec3::UnitX(), sim::Vec3::UnitY(), 1e-6);
  const double c = std::cos(spec.angle_deg * kDeg), sn = std::sin(spec.angle_deg * kDeg);
  for (int p = 0; p < s.model.num_particles(); ++p) {
    const double x = s.model.x0[3 * p] - x0, y = s.model.x0[3 * p + 1];
    s.model.uv[p] = Vec2(c * x - sn * y, sn * x + c * y);
  }
  if (mat.density > 0.0) s.model.mass = sim::lump_masses(s.model.uv, s.model.triangles, mat.density);
  if (spec.model == ClothModel::strain_rosette) {
    const sim::OrthotropicMaterial o = orthotropic_of(mat);
    s.effects.push_back(sim::make_strain_rosette(s.model, {o}));
    s.effects.push_back(sim::make_bending(s.model, {o}));
  } else {
    s.effects.push_back(sim::make_mass_spring(s.model, {*mat.mass_spring}));
  }
  return s;
}

// ---- static equilibrium ---------------------------------------------------------

// Newton on the free degrees of freedom with the effects' exact Jacobians,
// f_ext + Σ f(x) = 0, full steps (a line search on |residual| or on energy
// stalls a bending strip: the linear predictor stretches it, the next step
// takes the stretch back). A step that blows up or leaves a non-finite state
// is retried with a Levenberg shift μ·max diag(K). `monotone` (mass-spring)
// accepts only steps that lower |residual| (Levenberg-Marquardt): a flat
// mass-spring sheet has no stiffness across its plane. Converged when
// |residual| ≤ 1e-9 of the load and reactions (or stalled below 1e-6 of it,
// the round-off floor). Returns false when it does not converge.
bool equilibrium(const Specimen& s, const std::vector<char>& fixed, const VecX& f_ext, VecX& x, bool monotone) {
  const sim::Model& m = s.model;
  std::vector<int> dofs, slot(m.num_dofs(), -1);
  for (int d = 0; d < m.num_dofs(); ++d)
    if (!fixed[d]) slot[d] = static_cast<int>(dofs.size()), dofs.push_back(d);
  const int n = static_cast<int>(dofs.size());
  const VecX v = VecX::Zero(m.num_dofs());
  auto residual = [&](const VecX& at, double& scale) {
    VecX f = f_ext;
    for (const auto& e : s.effects) e->add_forces({m, 0.0, at, v}, f);
    VecX r(n);
    for (int k = 0; k < n; ++k) r[k] = f[dofs[k]];
    // Scale: the load and the reactions at the held degrees of freedom.
    scale = f_ext.norm();
    for (int d = 0; d < m.num_dofs(); ++d)
      if (fixed[d]) scale = std::max(scale, std::abs(f[d]));
    return r;
  };
  double scale = 0.0, shift = 0.0;
  VecX r = residual(x, scale);
  const double start = std::max(r.norm(), f_ext.norm());
  double best = r.norm();
  int stalled = 0;
  for (int it = 0; it < (monotone ? 200 : 100); ++it) {
    if (r.norm() <= 1e-9 * std::max(scale, 1e-12)) return true;
    // Round-off floor: no progress for a while, yet a millionth of the scale.
    if (stalled >= 5 && r.norm() <= 1e-6 * scale) return true;
    sim::Triplets jx, jv, red;
    for (const auto& e : s.effects) e->add_jacobian({m, 0.0, x, v}, jx, jv);
    double diag = 0.0;
    for (const auto& t : jx)
      if (slot[t.row()] >= 0 && slot[t.col()] >= 0) {
        red.emplace_back(slot[t.row()], slot[t.col()], -t.value());
        if (t.row() == t.col()) diag = std::max(diag, -t.value());
      }
    bool stepped = false;
    for (int attempt = 0; attempt < 16 && !stepped; ++attempt) {
      sim::Triplets k = red;
      if (shift > 0.0)
        for (int d = 0; d < n; ++d) k.emplace_back(d, d, shift * diag);
      sim::SparseMatrix K(n, n);
      K.setFromTriplets(k.begin(), k.end());
      Eigen::SparseLU<sim::SparseMatrix> lu(K);
      if (lu.info() == Eigen::Success) {
        const VecX dx = lu.solve(r);
        VecX trial = x;
        for (int q = 0; q < n; ++q) trial[dofs[q]] += dx[q];
        double trial_scale = 0.0;
        const VecX tr = residual(trial, trial_scale);
        if (dx.allFinite() && tr.allFinite() && tr.norm() < (monotone ? r.norm() : 1e3 * start))
          x = trial, r = tr, scale = trial_scale, stepped = true;
      }
      if (stepped) shift *= monotone ? 0.3 : 0.1;
      else shift = std::max(10.0 * shift, 1e-10);
    }
    if (!stepped) return false;
    if (r.norm() < 0.5 * best) best = r.norm(), stalled = 0;
    else ++stalled;
  }
  return false;
}

// Applies the load `load`·λ for λ from `from` to `to`, starting at x (in
// equilibrium at `from`), halving the increment where a solve fails (at most 5
// times; not for the mass-spring model, whose failures are not about step size).
bool ramp(const Specimen& s, const std::vector<char>& fixed, const VecX& load, double from, double to, VecX& x,
          bool monotone, int depth = 0) {
  VecX trial = x;
  if (equilibrium(s, fixed, load * to, trial, monotone)) {
    x = trial;
    return true;
  }
  if (monotone || depth >= 5) return false;
  const double mid = 0.5 * (from + to);
  return ramp(s, fixed, load, from, mid, x, monotone, depth + 1) && ramp(s, fixed, load, mid, to, x, monotone, depth + 1);
}

std::string sig(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

// A CSV field, quoted when it holds a comma or a quote.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

double rel_error(double measured, double expected) { return measured / expected - 1.0; }

void add_point(LabResult& r, std::string quantity, double x, double measured, double expected) {
  r.points.push_back({std::move(quantity), x, measured, expected, rel_error(measured, expected)});
}

// The bending reference: B_strip of the fabric's orthotropic values at the angle.
double strip_rigidity(const LabSpec& spec, const MaterialDef& mat) {
  if (!mat.orthotropic)
    throw Error(mat.name, "B_warp", "the lab's bending references need the fabric's bending rigidities");
  return sim::bending_rigidity_strip(orthotropic_of(mat), spec.angle_deg * kDeg);
}

int cells_across(const LabSpec& spec) { return std::max(2, static_cast<int>(std::lround(spec.width / spec.resolution))); }

// A cantilever clamped by holding two columns of particles: the clamp acts at
// the middle of the held cell (docs/fabric-model.md §3), so n cells of
// h = L/(n + ½) lie beyond it and the free length is L from x = 0.
Specimen cantilever_specimen(const LabSpec& spec, const MaterialDef& mat, double L, int n, std::vector<char>& fixed) {
  const double h = L / (n + 0.5);
  Specimen s = make_specimen(spec, mat, n + 2, cells_across(spec) + 1, h, spec.width, -0.5 * h);
  fixed.assign(s.model.num_dofs(), 0);
  for (int j = 0; j < s.nv; ++j)
    for (int i : {0, 1})
      for (int c = 0; c < 3; ++c) fixed[3 * s.index(i, j) + c] = 1;
  return s;
}

// The start of a bending solve. A flat mass-spring strip has no stiffness
// across its plane (its bending springs lie in it), so Newton starts it from
// a gentle arc (tip slope 0.1) instead.
sim::VecX bending_start(const LabSpec& spec, const Specimen& s, double L) {
  VecX x = s.model.x0;
  if (spec.model == ClothModel::mass_spring)
    for (int p = 0; p < s.model.num_particles(); ++p) {
      const double a = std::max(0.0, x[3 * p]) / L;
      x[3 * p + 2] = -0.05 * L * a * a;
    }
  return x;
}

std::string no_equilibrium_note(const LabSpec& spec) {
  if (spec.model == ClothModel::mass_spring)
    return "no static equilibrium found (NaN): the mass-spring strip has no linear bending stiffness, its "
           "bending springs lie in the sheet";
  return "the static solve did not converge at every load: NaN marks the loads it missed";
}

// Mean tip (u/L, w/L) over the last column.
Elastica tip_of(const Specimen& s, const VecX& x, double L) {
  Elastica e;
  for (int j = 0; j < s.nv; ++j) {
    const int p = s.index(s.nu - 1, j);
    e.u_over_L += (L - x[3 * p]) / L / s.nv;
    e.w_over_L -= x[3 * p + 2] / L / s.nv;
  }
  return e;
}

// ---- the tests ------------------------------------------------------------------

void tip_cantilever(const LabSpec& spec, const MaterialDef& mat, LabResult& r) {
  const double B = strip_rigidity(spec, mat), L = spec.length;
  const int n = std::max(2, static_cast<int>(std::lround(L / spec.resolution)));
  std::vector<char> fixed;
  const Specimen s = cantilever_specimen(spec, mat, L, n, fixed);
  r.x_name = "k = PL^2/B", r.cells_along = n, r.cells_across = s.nv - 1;
  r.notes.push_back("reference: elastica with a dead tip load (mechanics.md 1), B = B_strip = " + sig(B) +
                    " N.m; strip " + format_fixed(L * 1000, 1) + " x " + format_fixed(spec.width * 1000, 1) +
                    " mm, clamp = two held columns");
  // The tip load per width P, shared over the tip column (half at the corners).
  VecX unit = VecX::Zero(s.model.num_dofs());
  for (int j = 0; j < s.nv; ++j)
    unit[3 * s.index(s.nu - 1, j) + 2] = -spec.width / (s.nv - 1) * ((j == 0 || j == s.nv - 1) ? 0.5 : 1.0);
  VecX x = bending_start(spec, s, L);
  constexpr int kSub = 4;  // load increments per unit of k
  bool ok = true;
  for (int step = 1; step <= 10 * kSub; ++step) {
    const double k = double(step) / kSub;
    if (ok) ok = ramp(s, fixed, unit * (B / (L * L)), k - 1.0 / kSub, k, x, spec.model == ClothModel::mass_spring);
    if (step % kSub) continue;
    const Elastica ref = tip_load_elastica(k);
    const Elastica got = ok ? tip_of(s, x, L) : Elastica{std::nan(""), std::nan(""), 0.0};
    add_point(r, "u/L", k, got.u_over_L, ref.u_over_L);
    add_point(r, "w/L", k, got.w_over_L, ref.w_over_L);
  }
  if (!ok) r.notes.push_back(no_equilibrium_note(spec));
}

void tensile(const LabSpec& spec, const MaterialDef& mat, LabResult& r) {
  if (!mat.orthotropic) throw Error(mat.name, "E_warp", "the tensile reference needs the fabric's moduli");
  const sim::OrthotropicMaterial o = orthotropic_of(mat);
  constexpr double kStrain = 1e-4;
  // The ISO 13934-1 strip: 200 mm between the clamps, 50 mm wide.
  constexpr double L = 0.2, kWidth = 0.05;
  const int n = std::max(2, static_cast<int>(std::lround(L / spec.resolution)));
  const int across = std::max(2, static_cast<int>(std::lround(kWidth / spec.resolution)));
  r.x_name = "angle deg", r.cells_along = n, r.cells_across = across;
  r.notes.push_back("reference: orthotropic off-axis modulus 1/E = c^4/E_x + (1/G - 2 nu_xy/E_x) s^2 c^2 + s^4/E_y "
                    "(mechanics.md 3); ISO 13934-1 strip 200 x 50 mm, strain 1e-4, ends held along the axis only (free to contract and shear)");
  std::vector<double> angles;
  if (spec.angle_deg >= 0.0) angles.push_back(spec.angle_deg);
  else
    for (int a = 0; a <= 90; a += 15) angles.push_back(a);
  for (double angle : angles) {
    LabSpec at = spec;
    at.angle_deg = angle;
    const Specimen s = make_specimen(at, mat, n + 1, across + 1, L / n, kWidth, 0.0);
    std::vector<char> fixed(s.model.num_dofs(), 0);
    for (int p = 0; p < s.model.num_particles(); ++p) fixed[3 * p + 2] = 1;  // in-plane test
    for (int j = 0; j < s.nv; ++j) fixed[3 * s.index(0, j)] = fixed[3 * s.index(s.nu - 1, j)] = 1;
    fixed[3 * s.index(0, 0) + 1] = 1;  // no rigid sliding across
    // The machine's force per width (N/m) at an engineering strain: minus the
    // specimen's pull on the moving clamp. NaN when the solve fails.
    const VecX v = VecX::Zero(s.model.num_dofs());
    auto pull = [&](double strain) {
      VecX x = s.model.x0;
      for (int p = 0; p < s.model.num_particles(); ++p) x[3 * p] *= 1.0 + strain;
      if (!equilibrium(s, fixed, VecX::Zero(s.model.num_dofs()), x, false)) return std::nan("");
      VecX f = VecX::Zero(s.model.num_dofs());
      for (const auto& e : s.effects) e->add_forces({s.model, 0.0, x, v}, f);
      double force = 0.0;
      for (int j = 0; j < s.nv; ++j) force -= f[3 * s.index(s.nu - 1, j)];
      return force / kWidth;
    };
    add_point(r, "E_theta N/m", angle, pull(kStrain) / kStrain, sim::off_axis_modulus(o, angle * kDeg));
    // Along a yarn with a measured curve: the stress-strain curve, at its
    // points and half-way between them (piecewise linear in between).
    const sim::StressStrainCurve* curve = angle == 0.0 ? &o.curve_warp : angle == 90.0 ? &o.curve_weft : nullptr;
    if (!curve || curve->empty() || spec.model != ClothModel::strain_rosette) continue;
    const std::string quantity = angle == 0.0 ? "stress warp N/m" : "stress weft N/m";
    for (std::size_t i = 1; i < curve->strain.size(); ++i)
      for (double t : {0.5, 1.0}) {
        const double e = curve->strain[i - 1] + t * (curve->strain[i] - curve->strain[i - 1]);
        const double expected = curve->stress[i - 1] + t * (curve->stress[i] - curve->stress[i - 1]);
        if (e > 0.0 && expected > 0.0) r.points.push_back({quantity, e, pull(e), expected, 0.0});
      }
    r.notes.push_back("'" + quantity + "' points: x is the engineering strain, expected the fabric's measured curve");
  }
  for (auto& p : r.points) p.rel_error = rel_error(p.measured, p.expected);
}

void cantilever(const LabSpec& spec, const MaterialDef& mat, LabResult& r) {
  const double B = strip_rigidity(spec, mat);
  if (mat.density <= 0.0) throw Error(mat.name, "density", "the cantilever test needs the fabric's density");
  const double q = mat.density * kGravity;  // N/m², weight per area
  const double c_true = std::cbrt(B / q);
  r.x_name = "g = wL^3/B";
  r.notes.push_back("reference: heavy elastica (mechanics.md 2), B = B_strip = " + sig(B) +
                    " N.m, weight " + format_fixed(mat.density * 1000, 1) + " g/m2, true bending length c = (B/w)^(1/3) = " +
                    format_fixed(c_true * 1000, 2) + " mm");
  r.notes.push_back("bending length: FAST / ASTM D1388 read the chord angle and apply Peirce's formula "
                    "c = L (cos(theta/2) / (8 tan theta))^(1/3); expected = the same formula at the exact chord angle");
  // Short specimens (g = 1: L = c) keep at least this many cells along.
  constexpr int kMinCells = 16;
  const auto gravity = sim::make_gravity({sim::Vec3(0, 0, -kGravity)});
  for (double g : {1.0, 2.0, 5.0, 8.0, 10.0, 20.0}) {
    const double L = c_true * std::cbrt(g);
    const int n = std::max(kMinCells, static_cast<int>(std::lround(L / spec.resolution)));
    std::vector<char> fixed;
    const Specimen s = cantilever_specimen(spec, mat, L, n, fixed);
    r.cells_along = std::max(r.cells_along, n), r.cells_across = s.nv - 1;
    VecX weight = VecX::Zero(s.model.num_dofs());
    gravity->add_forces({s.model, 0.0, s.model.x0, s.model.v0}, weight);
    VecX x = bending_start(spec, s, L);
    bool ok = true;
    const int steps = std::max(4, static_cast<int>(std::ceil(2 * g)));
    for (int step = 1; step <= steps && ok; ++step) 
      ok = equilibrium(s, fixed, weight * (double(step) / steps), x, spec.model == ClothModel::mass_spring);
    if (!ok && r.notes.back() != no_equilibrium_note(spec)) r.notes.push_back(no_equilibrium_note(spec));
    const Elastica ref = heavy_elastica(g);
    const Elastica got = ok ? tip_of(s, x, L) : Elastica{std::nan(""), std::nan(""), 0.0};
    add_point(r, "chord deg", g, got.chord_deg(), ref.chord_deg());
    add_point(r, "bending length mm", g, 1000 * L * peirce_bending_length_over_L(got.chord_deg() * kDeg),
              1000 * L * peirce_bending_length_over_L(ref.chord_deg() * kDeg));
  }
}

// The smallest eigenvalue (N/m) of the stiffness −∂f/∂x across the sheet (z
// degrees of freedom of the free particles) at x: zero where the straight
// strip buckles. In the flat state z decouples from the in-plane motion.
double lowest_out_of_plane_stiffness(const Specimen& s, const std::vector<char>& fixed, const VecX& x) {
  const sim::Model& m = s.model;
  std::vector<int> slot(m.num_dofs(), -1);
  int n = 0;
  for (int p = 0; p < m.num_particles(); ++p)
    if (!fixed[3 * p + 2]) slot[3 * p + 2] = n++;
  const VecX v = VecX::Zero(m.num_dofs());
  sim::Triplets jx, jv;
  for (const auto& e : s.effects) e->add_jacobian({m, 0.0, x, v}, jx, jv);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (const auto& t : jx)
    if (slot[t.row()] >= 0 && slot[t.col()] >= 0) K(slot[t.row()], slot[t.col()]) -= t.value();
  const Eigen::MatrixXd Ks = 0.5 * (K + K.transpose());
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Ks, Eigen::EigenvaluesOnly).eigenvalues()[0];
}

// Euler buckling (mechanics.md §4): the compressive line load (N/m) at which
// the straight strip loses its stiffness across the sheet, found by bisection
// on the load. clamped-free: a dead axial load on the free end; clamped-clamped:
// both ends held by two columns, the far clamp moved towards the near one, the
// load read as the clamp's reaction. Linearised about the straight state, so
// the load is the bifurcation load itself.
void buckling(const LabSpec& spec, const MaterialDef& mat, LabResult& r) {
  const double B = strip_rigidity(spec, mat);
  r.x_name = "L mm";
  r.notes.push_back("reference: P_cr = C B / L^2 (mechanics.md 4), C = pi^2/4 clamped-free, 4 pi^2 clamped-clamped; "
                    "B = B_strip = " + sig(B) + " N.m; 10 mm wide strips, clamps = two held columns");
  for (double L : {0.05, 0.1}) {
    const int n = std::max(8, static_cast<int>(std::lround(L / spec.resolution)));
    // ---- clamped-free: dead load along −x on the tip column ----
    {
      std::vector<char> fixed;
      const Specimen s = cantilever_specimen(spec, mat, L, n, fixed);
      r.cells_along = std::max(r.cells_along, n), r.cells_across = s.nv - 1;
      VecX unit = VecX::Zero(s.model.num_dofs());
      for (int j = 0; j < s.nv; ++j)
        unit[3 * s.index(s.nu - 1, j)] = -spec.width / (s.nv - 1) * ((j == 0 || j == s.nv - 1) ? 0.5 : 1.0);
      std::vector<char> in_plane = fixed;
      for (int p = 0; p < s.model.num_particles(); ++p) in_plane[3 * p + 2] = 1;
      auto stiffness_at = [&](double P) {
        VecX x = s.model.x0;
        if (!equilibrium(s, in_plane, unit * P, x, false)) return std::nan("");
        return lowest_out_of_plane_stiffness(s, fixed, x);
      };
      const double expected = std::numbers::pi * std::numbers::pi / 4 * B / (L * L);
      double lo = 0.0, hi = 2.0 * expected;
      const bool bracket = stiffness_at(hi) < 0.0;
      for (int it = 0; it < 50 && bracket; ++it) {
        const double mid = 0.5 * (lo + hi);
        (stiffness_at(mid) > 0.0 ? lo : hi) = mid;
      }
      add_point(r, "P_cr clamped-free N/m", 1000 * L, bracket ? 0.5 * (lo + hi) : std::nan(""), expected);
    }
    // ---- clamped-clamped: n cells of h = L/(n + 1) between the clamps' middles ----
    {
      const double h = L / (n + 1);
      const Specimen s = make_specimen(spec, mat, n + 3, cells_across(spec) + 1, h, spec.width, -0.5 * h);
      std::vector<char> fixed(s.model.num_dofs(), 0);
      for (int j = 0; j < s.nv; ++j)
        for (int i : {0, 1, s.nu - 2, s.nu - 1})
          for (int c = 0; c < 3; ++c) fixed[3 * s.index(i, j) + c] = 1;
      std::vector<char> in_plane = fixed;
      for (int p = 0; p < s.model.num_particles(); ++p) in_plane[3 * p + 2] = 1;
      const VecX v = VecX::Zero(s.model.num_dofs());
      // The state with the far clamp moved by −delta, and the load it carries (N/m).
      auto state_at = [&](double delta, VecX& x) {
        x = s.model.x0;
        for (int j = 0; j < s.nv; ++j)
          for (int i : {s.nu - 2, s.nu - 1}) x[3 * s.index(i, j)] -= delta;
        for (int i = 2; i < s.nu - 2; ++i)
          for (int j = 0; j < s.nv; ++j) x[3 * s.index(i, j)] -= delta * (i - 1) / double(s.nu - 3);
        if (!equilibrium(s, in_plane, VecX::Zero(s.model.num_dofs()), x, false)) return std::nan("");
        VecX f = VecX::Zero(s.model.num_dofs());
        for (const auto& e : s.effects) e->add_forces({s.model, 0.0, x, v}, f);
        double load = 0.0;
        for (int j = 0; j < s.nv; ++j)
          for (int i : {s.nu - 2, s.nu - 1}) load += f[3 * s.index(i, j)];
        return load / spec.width;
      };
      const double expected = 4 * std::numbers::pi * std::numbers::pi * B / (L * L);
      const double E = sim::off_axis_modulus(orthotropic_of(mat), spec.angle_deg * kDeg);
      double lo = 0.0, hi = 2.0 * expected * L / E;
      VecX x;
      state_at(hi, x);
      const bool bracket = lowest_out_of_plane_stiffness(s, fixed, x) < 0.0;
      for (int it = 0; it < 50 && bracket; ++it) {
        const double mid = 0.5 * (lo + hi);
        state_at(mid, x);
        (lowest_out_of_plane_stiffness(s, fixed, x) > 0.0 ? lo : hi) = mid;
      }
      const double load = bracket ? state_at(0.5 * (lo + hi), x) : std::nan("");
      add_point(r, "P_cr clamped-clamped N/m", 1000 * L, load, expected);
    }
  }
}

}  // namespace

LabResult run(const LabSpec& spec, const MaterialDef& given) {
  MaterialDef material = given;
  if (spec.poisson_free && material.orthotropic) {
    material.orthotropic->nu_warp_weft = 0.0;
    material.orthotropic->nu_weft_warp = sim::kDerived;
  }
  if (!(spec.resolution > 0.0) || !(spec.length > 0.0) || !(spec.width > 0.0))
    throw Error(material.name, "lab", "resolution, length and width must be positive");
  if (spec.model == ClothModel::strain_rosette) {
    if (const std::string problem = orthotropic_problem(material); !problem.empty())
      throw Error(material.name, to_string(spec.model), problem);
  } else if (!material.mass_spring) {
    throw Error(material.name, to_string(spec.model), "the material has no spring.* values");
  }
  const auto t0 = std::chrono::steady_clock::now();
  LabResult r;
  r.test = to_string(spec.test), r.material = material.name, r.model = to_string(spec.model);
  switch (spec.test) {
    case Test::tip_cantilever: tip_cantilever(spec, material, r); break;
    case Test::tensile: tensile(spec, material, r); break;
    case Test::cantilever: cantilever(spec, material, r); break;
    case Test::buckling:
      if (spec.model != ClothModel::strain_rosette)
        throw Error(material.name, "buckling", "the buckling test needs the strain-rosette model (mass-spring has no "
                                               "bending stiffness at the straight state)");
      buckling(spec, material, r);
      break;
  }
  if (spec.poisson_free) r.notes.push_back("Poisson coupling off (nu_xy = 0): B_strip = B_plate");
  for (const auto& p : r.points)
    r.max_rel_error = std::isfinite(p.rel_error) ? std::max(r.max_rel_error, std::abs(p.rel_error))
                                                 : std::numeric_limits<double>::infinity();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void write_csv(const LabResult& r, const fs::path& file) {
  std::ofstream out(file);
  if (!out) throw Error(file.string(), "", "cannot write");
  out << "test,material,model,quantity,x,measured,expected,rel_error\n";
  out.precision(10);
  for (const auto& p : r.points)
    out << r.test << ',' << csv_field(r.material) << ',' << r.model << ',' << p.quantity << ',' << p.x << ',' << p.measured << ','
        << p.expected << ',' << p.rel_error << '\n';
  if (!out) throw Error(file.string(), "", "write failed");
}

}  // namespace vgd::scene::lab
