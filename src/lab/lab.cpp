// The virtual fabric lab: specimens, static equilibrium, measurement and
// comparison (include/vgd/lab/lab.hpp, docs/fabric-lab.md). The physics is
// the engine's effects; the lab only cuts, holds, loads and reads.
#include "vgd/lab/lab.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/data.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/bending.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/strain_rosette.hpp"
#include "vgd/sim/integrator.hpp"
#include "vgd/sim/run.hpp"

namespace vgd::lab {

namespace fs = std::filesystem;
using sim::Vec2;
using sim::VecX;

const char* to_string(Test t) {
  switch (t) {
    case Test::tip_cantilever: return "tip-cantilever";
    case Test::tensile: return "tensile";
    case Test::cantilever: return "cantilever";
    case Test::buckling: return "buckling";
    case Test::shear: return "shear";
    case Test::bending: return "bending";
    case Test::drape: return "drape";
  }
  return "?";
}

Test parse_test(const std::string& s) {
  for (Test t : {Test::tip_cantilever, Test::tensile, Test::cantilever, Test::buckling, Test::shear, Test::bending,
                 Test::drape})
    if (s == to_string(t)) return t;
  throw std::invalid_argument("unknown lab test '" + s +
                              "' (tip-cantilever, tensile, cantilever, buckling, shear, bending, drape)");
}

scene::MaterialDef lab_material(const std::string& name_or_file) {
  const fs::path given(name_or_file);
  const fs::path file = fs::is_regular_file(given) ? given : data_file("materials/" + name_or_file + ".xvc");
  return scene::load_xvc_material(file, file.stem().string());
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

// Sheet rest coordinates → warp/weft frame: the specimen's axis reads (cos θ, sin θ).
Eigen::Matrix2d to_material(double angle_deg) {
  const double c = std::cos(angle_deg * kDeg), s = std::sin(angle_deg * kDeg);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

// The fabric on a specimen whose particles and rest coordinates are set:
// lumped masses and the model's effects, built as a scene builds them.
void add_fabric(const LabSpec& spec, const scene::MaterialDef& mat, Specimen& s) {
  if (mat.density > 0.0) s.model.mass = sim::lump_masses(s.model.uv, s.model.triangles, mat.density);
  if (spec.model == scene::ClothModel::strain_rosette) {
    const sim::OrthotropicMaterial o = scene::orthotropic_of(mat);
    s.effects.push_back(sim::make_strain_rosette(s.model, {o}));
    s.effects.push_back(sim::make_bending(s.model, {o}));
  } else {
    s.effects.push_back(sim::make_mass_spring(s.model, {*mat.mass_spring}));
  }
}

Specimen make_specimen(const LabSpec& spec, const scene::MaterialDef& mat, int nu, int nv, double h, double width,
                       double x0) {
  Specimen s;
  s.nu = nu, s.nv = nv, s.h = h, s.w_cell = width / (nv - 1);
  s.model = sim::make_grid(nu, nv, h, s.w_cell, sim::Vec3(x0, 0, 0), sim::Vec3::UnitX(), sim::Vec3::UnitY(), 1e-6);
  const Eigen::Matrix2d to_warp = to_material(spec.angle_deg);
  for (int p = 0; p < s.model.num_particles(); ++p)
    s.model.uv[p] = to_warp * Vec2(s.model.x0[3 * p] - x0, s.model.x0[3 * p + 1]);
  add_fabric(spec, mat, s);
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
double strip_rigidity(const LabSpec& spec, const scene::MaterialDef& mat) {
  if (!mat.orthotropic)
    throw Error(mat.name, "B_warp", "the lab's bending references need the fabric's bending rigidities");
  return sim::bending_rigidity_strip(scene::orthotropic_of(mat), spec.angle_deg * kDeg);
}

// The specimen's forces on every particle at x (N): what the clamps hold back.
VecX specimen_forces(const Specimen& s, const VecX& x) {
  VecX f = VecX::Zero(s.model.num_dofs());
  for (const auto& e : s.effects) e->add_forces({s.model, 0.0, x, VecX::Zero(s.model.num_dofs())}, f);
  return f;
}

// The angles a test runs at: the one --angle, or `all` when it is negative.
std::vector<double> test_angles(const LabSpec& spec, std::vector<double> all) {
  return spec.angle_deg >= 0.0 ? std::vector<double>{spec.angle_deg} : all;
}

int cells_across(const LabSpec& spec) { return std::max(2, static_cast<int>(std::lround(spec.width / spec.resolution))); }

// A cantilever clamped by holding two columns of particles: the clamp acts at
// the middle of the held cell (docs/fabric-model.md §3), so n cells of
// h = L/(n + ½) lie beyond it and the free length is L from x = 0.
Specimen cantilever_specimen(const LabSpec& spec, const scene::MaterialDef& mat, double L, int n, std::vector<char>& fixed) {
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
  if (spec.model == scene::ClothModel::mass_spring)
    for (int p = 0; p < s.model.num_particles(); ++p) {
      const double a = std::max(0.0, x[3 * p]) / L;
      x[3 * p + 2] = -0.05 * L * a * a;
    }
  return x;
}

std::string no_equilibrium_note(const LabSpec& spec) {
  if (spec.model == scene::ClothModel::mass_spring)
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

void tip_cantilever(const LabSpec& spec, const scene::MaterialDef& mat, LabResult& r) {
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
    if (ok) ok = ramp(s, fixed, unit * (B / (L * L)), k - 1.0 / kSub, k, x, spec.model == scene::ClothModel::mass_spring);
    if (step % kSub) continue;
    const Elastica ref = tip_load_elastica(k);
    const Elastica got = ok ? tip_of(s, x, L) : Elastica{std::nan(""), std::nan(""), 0.0};
    add_point(r, "u/L", k, got.u_over_L, ref.u_over_L);
    add_point(r, "w/L", k, got.w_over_L, ref.w_over_L);
  }
  if (!ok) r.notes.push_back(no_equilibrium_note(spec));
}

void tensile(const LabSpec& spec, const scene::MaterialDef& mat, LabResult& r) {
  if (!mat.orthotropic) throw Error(mat.name, "E_warp", "the tensile reference needs the fabric's moduli");
  const sim::OrthotropicMaterial o = scene::orthotropic_of(mat);
  constexpr double kStrain = 1e-4;
  // The ISO 13934-1 strip: 200 mm between the clamps, 50 mm wide.
  constexpr double L = 0.2, kWidth = 0.05;
  const int n = std::max(2, static_cast<int>(std::lround(L / spec.resolution)));
  const int across = std::max(2, static_cast<int>(std::lround(kWidth / spec.resolution)));
  r.x_name = "angle deg", r.cells_along = n, r.cells_across = across;
  r.notes.push_back("reference: orthotropic off-axis modulus 1/E = c^4/E_x + (1/G - 2 nu_xy/E_x) s^2 c^2 + s^4/E_y "
                    "(mechanics.md 3); ISO 13934-1 strip 200 x 50 mm, strain 1e-4, ends held along the axis only (free to contract and shear)");
  for (double angle : test_angles(spec, {0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0})) {
    LabSpec at = spec;
    at.angle_deg = angle;
    const Specimen s = make_specimen(at, mat, n + 1, across + 1, L / n, kWidth, 0.0);
    std::vector<char> fixed(s.model.num_dofs(), 0);
    for (int p = 0; p < s.model.num_particles(); ++p) fixed[3 * p + 2] = 1;  // in-plane test
    for (int j = 0; j < s.nv; ++j) fixed[3 * s.index(0, j)] = fixed[3 * s.index(s.nu - 1, j)] = 1;
    fixed[3 * s.index(0, 0) + 1] = 1;  // no rigid sliding across
    // The machine's force per width (N/m) at an engineering strain: minus the
    // specimen's pull on the moving clamp. NaN when the solve fails.
    auto pull = [&](double strain) {
      VecX x = s.model.x0;
      for (int p = 0; p < s.model.num_particles(); ++p) x[3 * p] *= 1.0 + strain;
      if (!equilibrium(s, fixed, VecX::Zero(s.model.num_dofs()), x, false)) return std::nan("");
      const VecX f = specimen_forces(s, x);
      double force = 0.0;
      for (int j = 0; j < s.nv; ++j) force -= f[3 * s.index(s.nu - 1, j)];
      return force / kWidth;
    };
    add_point(r, "E_theta N/m", angle, pull(kStrain) / kStrain, sim::off_axis_modulus(o, angle * kDeg));
    // Along a yarn with a measured curve: the stress-strain curve, at its
    // points and half-way between them (piecewise linear in between).
    const sim::StressStrainCurve* curve = angle == 0.0 ? &o.curve_warp : angle == 90.0 ? &o.curve_weft : nullptr;
    if (!curve || curve->empty() || spec.model != scene::ClothModel::strain_rosette) continue;
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

void cantilever(const LabSpec& spec, const scene::MaterialDef& mat, LabResult& r) {
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
      ok = equilibrium(s, fixed, weight * (double(step) / steps), x, spec.model == scene::ClothModel::mass_spring);
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
// `mode` (optional): the eigenvector's z per particle (0 where z is held).
double lowest_out_of_plane_stiffness(const Specimen& s, const std::vector<char>& fixed, const VecX& x,
                                     Eigen::VectorXd* mode = nullptr) {
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
  if (!mode) return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Ks, Eigen::EigenvaluesOnly).eigenvalues()[0];
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Ks);
  mode->setZero(m.num_particles());
  for (int p = 0; p < m.num_particles(); ++p)
    if (slot[3 * p + 2] >= 0) (*mode)[p] = eig.eigenvectors()(slot[3 * p + 2], 0);
  return eig.eigenvalues()[0];
}

// Shear buckling of a long plate clamped on its long edges (the KES-FB1 shear
// specimen's geometry: 200 mm along the clamps, b = 50 mm between their
// middles; each clamp two held rows). One clamp is displaced parallel to the
// other: every held particle, and the start of the free ones, in uniform simple
// shear x += γ y (γ = tan φ), the short ends held in that state and in z
// (simply supported), the in-plane equilibrium solved. The critical shear
// N_xy (N/m, the moving clamp's reaction per length) is where the lowest
// out-of-plane stiffness vanishes, by bisection on γ as for Euler above.
// Reference: the classic plate result N_xy,cr = k_s π² D / b², k_s = 8.98 for
// an infinitely long isotropic plate with clamped long edges (Southwell &
// Skan 1924; Timoshenko & Gere, Theory of Elastic Stability, 2nd ed., §9.7);
// the 200 mm plate's simply supported ends raise it by less than ~2 %. Given
// only where it applies: isotropic bending (D₁₁ = D₂₂ = D₁₂ + 2D₆₆ = D) and a
// pure shear prestress (specimen along a yarn, angle 0 or 90°); otherwise NaN
// (no reference for the orthotropic plate here). Also reported, without a
// reference: the buckle's half-waves along the centre line and their wavelength.
void shear_buckling(const LabSpec& spec, const scene::MaterialDef& mat, LabResult& r) {
  constexpr double b = 0.05, a = 0.2, kS = 8.98;
  const int m = std::max(4, static_cast<int>(std::lround(b / spec.resolution)));
  const int n = std::max(8, static_cast<int>(std::lround(a / spec.resolution)));
  const double w = b / (m + 1);
  const Specimen s = make_specimen(spec, mat, n + 1, m + 3, a / n, (m + 2) * w, 0.0);
  std::vector<char> fixed(s.model.num_dofs(), 0);
  for (int i = 0; i < s.nu; ++i)
    for (int j : {0, 1, s.nv - 2, s.nv - 1})
      for (int c = 0; c < 3; ++c) fixed[3 * s.index(i, j) + c] = 1;
  for (int j = 0; j < s.nv; ++j)
    for (int i : {0, s.nu - 1})
      for (int c = 0; c < 3; ++c) fixed[3 * s.index(i, j) + c] = 1;
  std::vector<char> in_plane = fixed;
  for (int p = 0; p < s.model.num_particles(); ++p) in_plane[3 * p + 2] = 1;
  // The sheared state and the shear it carries: the top clamp's reaction per length (N/m).
  auto state_at = [&](double gamma, VecX& x) {
    x = s.model.x0;
    for (int p = 0; p < s.model.num_particles(); ++p) x[3 * p] += gamma * s.model.x0[3 * p + 1];
    if (!equilibrium(s, in_plane, VecX::Zero(s.model.num_dofs()), x, false)) return std::nan("");
    const VecX f = specimen_forces(s, x);
    double load = 0.0;
    for (int i = 0; i < s.nu; ++i)
      for (int j : {s.nv - 2, s.nv - 1}) load -= f[3 * s.index(i, j)];
    return load / a;
  };
  const sim::OrthotropicMaterial o = scene::orthotropic_of(mat);
  const double d11 = o.B_warp, d22 = o.B_weft, d3 = sim::nu_weft_warp(o) * o.B_warp + 2 * sim::twist_rigidity(o);
  const bool isotropic = std::abs(d22 / d11 - 1) < 1e-9 && std::abs(d3 / d11 - 1) < 1e-9;
  const bool along_yarn = std::abs(std::remainder(spec.angle_deg, 90.0)) < 1e-9;
  const double estimate = kS * std::numbers::pi * std::numbers::pi * std::sqrt(d11 * d22) / (b * b);
  const double expected = isotropic && along_yarn ? estimate : std::nan("");
  // Bracket on γ from the estimate and the sheet's shear stiffness, doubled until unstable.
  double lo = 0.0, hi = 2.0 * estimate / simple_shear_modulus(o, spec.angle_deg);
  VecX x;
  bool bracket = false;
  for (int k = 0; k < 8 && !bracket; ++k) {
    state_at(hi, x);
    bracket = lowest_out_of_plane_stiffness(s, fixed, x) < 0.0;
    if (!bracket) lo = hi, hi *= 2.0;
  }
  for (int it = 0; it < 40 && bracket; ++it) {
    const double mid = 0.5 * (lo + hi);
    state_at(mid, x);
    (lowest_out_of_plane_stiffness(s, fixed, x) > 0.0 ? lo : hi) = mid;
  }
  double load = std::nan(""), half_waves = std::nan(""), wavelength = std::nan("");
  if (bracket) {
    load = state_at(hi, x);
    Eigen::VectorXd mode;
    lowest_out_of_plane_stiffness(s, fixed, x, &mode);
    // Zero crossings of the buckle along the centre line (x of each crossing, interpolated).
    const int jc = s.nv / 2;
    const double tiny = 1e-6 * mode.cwiseAbs().maxCoeff();
    std::vector<double> crossings;
    for (int i = 1; i + 2 < s.nu; ++i) {
      const double z0 = mode[s.index(i, jc)], z1 = mode[s.index(i + 1, jc)];
      if (std::abs(z0) > tiny && std::abs(z1) > tiny && (z0 > 0) != (z1 > 0))
        crossings.push_back(s.h * (i + z0 / (z0 - z1)));
    }
    half_waves = static_cast<double>(crossings.size() + 1);
    if (crossings.size() >= 2)
      wavelength = 1000 * 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  }
  add_point(r, "N_xy,cr shear N/m", 1000 * b, load, expected);
  add_point(r, "shear wrinkle half-waves", 1000 * b, half_waves, std::nan(""));
  add_point(r, "shear wrinkle wavelength mm", 1000 * b, wavelength, std::nan(""));
  r.notes.push_back("shear: plate " + format_fixed(1000 * a, 0) + " x " + format_fixed(1000 * b, 0) +
                    " mm clamped on its long edges (two held rows each), one clamp moved parallel to the other, ends "
                    "simply supported; " + std::to_string(n) + " x " + std::to_string(m + 1) +
                    " cells; reference N_xy,cr = k_s pi^2 D / b^2, k_s = 8.98 (long plate, clamped edges; Timoshenko & "
                    "Gere 9.7), " + (std::isfinite(expected) ? "D = " + sig(d11) + " N.m"
                                                              : std::string("given only for isotropic bending "
                                                                            "(B_warp = B_weft = D12 + 2 D66) along a yarn: none here")) +
                    "; x = b mm; wrinkles: half-waves and wavelength along the centre line");
}

// Euler buckling (mechanics.md §4): the compressive line load (N/m) at which
// the straight strip loses its stiffness across the sheet, found by bisection
// on the load. clamped-free: a dead axial load on the free end; clamped-clamped:
// both ends held by two columns, the far clamp moved towards the near one, the
// load read as the clamp's reaction. Linearised about the straight state, so
// the load is the bifurcation load itself.
void buckling(const LabSpec& spec, const scene::MaterialDef& mat, LabResult& r) {
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
      // The state with the far clamp moved by −delta, and the load it carries (N/m).
      auto state_at = [&](double delta, VecX& x) {
        x = s.model.x0;
        for (int j = 0; j < s.nv; ++j)
          for (int i : {s.nu - 2, s.nu - 1}) x[3 * s.index(i, j)] -= delta;
        for (int i = 2; i < s.nu - 2; ++i)
          for (int j = 0; j < s.nv; ++j) x[3 * s.index(i, j)] -= delta * (i - 1) / double(s.nu - 3);
        if (!equilibrium(s, in_plane, VecX::Zero(s.model.num_dofs()), x, false)) return std::nan("");
        const VecX f = specimen_forces(s, x);
        double load = 0.0;
        for (int j = 0; j < s.nv; ++j)
          for (int i : {s.nu - 2, s.nu - 1}) load += f[3 * s.index(i, j)];
        return load / spec.width;
      };
      const double expected = 4 * std::numbers::pi * std::numbers::pi * B / (L * L);
      const double E = sim::off_axis_modulus(scene::orthotropic_of(mat), spec.angle_deg * kDeg);
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
  shear_buckling(spec, mat, r);
}

// The fabric's orthotropic values, which every reference is computed from.
sim::OrthotropicMaterial orthotropic_reference(const scene::MaterialDef& mat, const char* test) {
  if (!mat.orthotropic)
    throw Error(mat.name, "E_warp", std::string("the ") + test + " reference needs the fabric's orthotropic values");
  return scene::orthotropic_of(mat);
}

}  // namespace

// Q̄₆₆ (N/m): the sheet's stiffness in simple shear (strain (0, 0, γ) in the
// specimen's frame, the strains along and across held) at θ from the warp;
// G at 0 and 90°. Plane-stress Q of material.hpp rotated (Jones eq. 2.85).
double simple_shear_modulus(const sim::OrthotropicMaterial& o, double angle_deg) {
  const double nyx = sim::nu_weft_warp(o), d = 1.0 - o.nu_warp_weft * nyx;
  const double q11 = o.E_warp / d, q22 = o.E_weft / d, q12 = nyx * o.E_warp / d, q66 = o.G;
  const double c = std::cos(angle_deg * kDeg), s = std::sin(angle_deg * kDeg);
  return (q11 + q22 - 2 * q12 - 2 * q66) * s * s * c * c + q66 * (s * s * s * s + c * c * c * c);
}

namespace {

// The shear force per clamp length (N/m) of an ideal, end-free specimen in
// uniform simple shear y += t·x (t = tan φ, x across the gap) at finite
// strain: dW/dt of the material's energy density, by central difference.
double simple_shear_force(const sim::OrthotropicMaterial& o, double angle_deg, double t) {
  const Eigen::Matrix2d R = to_material(angle_deg);
  auto energy = [&](double tt) {
    const Eigen::Matrix2d F = (Eigen::Matrix2d() << 1.0, 0.0, tt, 1.0).finished();
    const Eigen::Matrix2d C = R * (F.transpose() * F) * R.transpose();
    const sim::Vec3 strain(std::sqrt(C(0, 0)) - 1.0, std::sqrt(C(1, 1)) - 1.0, C(0, 1) / std::sqrt(C(0, 0) * C(1, 1)));
    return sim::rosette_energy_density(o, strain);
  };
  constexpr double dt = 1e-5;
  return (energy(t + dt) - energy(t - dt)) / (2 * dt);
}

// KES-FB1 shear: a specimen 200 mm along its clamps, 50 mm between them,
// one clamp held, the other moved sideways by L tan φ at fixed distance (in
// the plane: a flat specimen). Shear force per clamp length against φ, and the
// rigidity G at φ = 0.5°.
void shear(const LabSpec& spec, const scene::MaterialDef& mat, LabResult& r) {
  const sim::OrthotropicMaterial o = orthotropic_reference(mat, "shear");
  constexpr double L = 0.05, kWidth = 0.2;
  const int n = std::max(4, static_cast<int>(std::lround(L / spec.resolution)));
  const int across = std::max(4, static_cast<int>(std::lround(kWidth / spec.resolution)));
  r.x_name = "shear angle deg", r.cells_along = n, r.cells_across = across;
  r.notes.push_back("reference: uniform simple shear of the material law at finite strain (force = dW/dtan(phi)); "
                    "G = Q66 rotated to the angle (G_xy at 0 and 90 deg, the sheet modulus: G_3D x thickness); "
                    "KES-FB1 specimen 200 mm along the clamps, 50 mm between them, held at that distance, in the plane");
  const double angle = spec.angle_deg;
  const Specimen s = make_specimen(spec, mat, n + 1, across + 1, L / n, kWidth, 0.0);
  std::vector<char> fixed(s.model.num_dofs(), 0);
  for (int p = 0; p < s.model.num_particles(); ++p) fixed[3 * p + 2] = 1;
  for (int j = 0; j < s.nv; ++j)
    for (int i : {0, s.nu - 1}) fixed[3 * s.index(i, j)] = fixed[3 * s.index(i, j) + 1] = 1;
  // The force per clamp length (N/m) at shear angle φ, over the whole moving
  // clamp (what KES reads) and over its middle half (away from the free ends,
  // where the specimen is in uniform simple shear); NaN when the solve fails.
  auto force_at = [&](double phi_deg, double& middle) {
    const double t = std::tan(phi_deg * kDeg);
    VecX x = s.model.x0;
    for (int p = 0; p < s.model.num_particles(); ++p) x[3 * p + 1] += t * x[3 * p];  // start from uniform shear
    middle = std::nan("");
    if (!equilibrium(s, fixed, VecX::Zero(s.model.num_dofs()), x, spec.model == scene::ClothModel::mass_spring))
      return std::nan("");
    const VecX f = specimen_forces(s, x);
    const int j0 = across / 4, j1 = across - across / 4;
    double force = 0.0;
    middle = 0.0;
    for (int j = 0; j < s.nv; ++j) {
      const double fy = -f[3 * s.index(s.nu - 1, j) + 1];
      force += fy;
      if (j >= j0 && j <= j1) middle += (j == j0 || j == j1) ? 0.5 * fy : fy;  // the end particles' half shares
    }
    middle /= (j1 - j0) * s.w_cell;
    return force / kWidth;
  };
  double G = std::nan(""), G_middle = std::nan("");
  for (double phi : {0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0}) {
    double middle = 0.0;
    const double force = force_at(phi, middle);
    if (phi == 0.5) G = force / std::tan(phi * kDeg), G_middle = middle / std::tan(phi * kDeg);
    add_point(r, "shear force N/m", phi, force, simple_shear_force(o, angle, std::tan(phi * kDeg)));
  }
  add_point(r, "G N/m", angle, G, simple_shear_modulus(o, angle));
  add_point(r, "G middle N/m", angle, G_middle, simple_shear_modulus(o, angle));
  r.notes.push_back("'G N/m' points: x is the specimen's angle to the warp, measured = force / tan(phi) at 0.5 deg over "
                    "the whole clamp ('G') and over its middle half ('G middle', clear of the free ends)");
  if (spec.model == scene::ClothModel::mass_spring)
    r.notes.push_back("mass-spring: its sheet shear modulus is spring.shear on the lattice (two diagonal springs per cell)");
}

// KES-FB2 pure bending: a specimen 10 mm between its clamps (as KES) and
// 50 mm wide, both clamps (two held columns each) set on an arc of curvature
// K, the rest free; the moment per width on a clamp against K, and
// B = the KES slope between |K| = 0.5 and 1.5 1/cm, both ways. A wide bend holds
// the transverse curvature at zero away from the free sides: the plate's B_θ.
void bending(const LabSpec& spec, const scene::MaterialDef& mat, LabResult& r) {
  const sim::OrthotropicMaterial o = orthotropic_reference(mat, "bending");
  constexpr double L = 0.01, kWidth = 0.05;
  // The short gap keeps at least 16 cells along (the moment's error falls as
  // h²: −2.7 / −0.77 / −0.21 % at 8 / 16 / 32 cells, ν = 0); across, the
  // resolution, since a uniform bend does not vary across.
  const int n = std::max(16, static_cast<int>(std::lround(L / spec.resolution)));
  const int across = std::max(4, static_cast<int>(std::lround(kWidth / spec.resolution)));
  const double h = L / (n + 1);  // n cells between the clamps' middles
  r.x_name = "K 1/cm", r.cells_along = n, r.cells_across = across;
  r.notes.push_back("reference: plate rigidity B_theta = D11 c^4 + 2 (D12 + 2 D66) c^2 s^2 + D22 s^4 (mechanics.md 3, "
                    "consistent D12); specimen 10 mm between the clamps x 50 mm wide, clamps = two held columns on an arc");
  for (double angle : test_angles(spec, {0.0, 90.0})) {
    LabSpec at = spec;
    at.angle_deg = angle;
    const Specimen s = make_specimen(at, mat, n + 3, across + 1, h, kWidth, -0.5 * h);
    std::vector<char> fixed(s.model.num_dofs(), 0);
    for (int j = 0; j < s.nv; ++j)
      for (int i : {0, 1, s.nu - 2, s.nu - 1})
        for (int c = 0; c < 3; ++c) fixed[3 * s.index(i, j) + c] = 1;
    // The moment per width (N·m/m) on the near clamp, about the middle of its
    // held cell, with the specimen on an arc of curvature K (1/m) symmetric
    // about its middle. Pure bending: no net force, any point would do.
    auto moment_at = [&](double K) {
      VecX x = s.model.x0;
      auto arc = [&](double along, double& X, double& Z) {
        const double a = K * (along - 0.5 * L);
        X = 0.5 * L + std::sin(a) / K, Z = (1.0 - std::cos(a)) / K;
      };
      for (int p = 0; p < s.model.num_particles(); ++p) arc(s.model.x0[3 * p], x[3 * p], x[3 * p + 2]);
      if (!equilibrium(s, fixed, VecX::Zero(s.model.num_dofs()), x, spec.model == scene::ClothModel::mass_spring))
        return std::nan("");
      const VecX f = specimen_forces(s, x);
      double cx = 0.0, cz = 0.0, moment = 0.0;
      arc(0.0, cx, cz);
      for (int j = 0; j < s.nv; ++j)
        for (int i : {0, 1}) {
          const int p = s.index(i, j);
          moment += (x[3 * p + 2] - cz) * f[3 * p] - (x[3 * p] - cx) * f[3 * p + 2];
        }
      return -moment / kWidth;
    };
    const double B = sim::bending_rigidity(o, angle * kDeg);
    const std::string quantity = angle == 0.0 ? "M warp N.m/m" : angle == 90.0 ? "M weft N.m/m"
                                                                               : "M " + sig(angle) + " deg N.m/m";
    std::map<double, double> M;  // K (1/cm) → moment
    for (double K : {-2.5, -2.0, -1.5, -1.0, -0.5, 0.5, 1.0, 1.5, 2.0, 2.5}) {
      M[K] = moment_at(100.0 * K);
      add_point(r, quantity, K, M[K], B * 100.0 * K);
    }
    const double kes = 0.5 * ((M[1.5] - M[0.5]) + (M[-0.5] - M[-1.5])) / 100.0;
    add_point(r, "B N.m", angle, kes, B);
  }
  r.notes.push_back("'B N.m' points: x is the specimen's angle to the warp, measured = KES slope of M between 0.5 and "
                    "1.5 1/cm, both ways");
  if (std::any_of(r.points.begin(), r.points.end(), [](const LabPoint& p) { return !std::isfinite(p.measured); }))
    r.notes.push_back("no static equilibrium found at some curvatures (NaN)");
}

// ---- drape (Cusick) ---------------------------------------------------------------

// The specimen hung to rest under gravity by the engine's own dynamics:
// implicit Euler (sparse Cholesky, 10 ms steps: 5 ms gave the same nodes and
// DC within 1e-3 at twice the cost), the held particles pinned, and a
// mass-proportional air drag of 10 /s (near critical for the hanging skirt's
// swing, √(g/6 cm) ≈ 13 /s). A Newton solve for statics would start
// on the unstable axisymmetric branch of a flat disc; the motion leaves it
// and settles in a stable, folded state. At rest: mean kinetic energy per
// particle below that of 0.1 mm/s for 10 frames at 50 fps. Consumes the
// specimen's effects; x is the start (in) and the rest (out).
bool hang_to_rest(Specimen& s, const std::vector<int>& held, VecX& x, double& simulated_s) {
  auto effects = std::move(s.effects);
  effects.push_back(sim::make_gravity({sim::Vec3(0, 0, -kGravity)}));
  effects.push_back(sim::make_viscosity({0.0, 10.0}));
  effects.push_back(sim::make_pins(s.model, {held}));
  sim::Model model = s.model;
  model.x0 = x;
  sim::System sys(std::move(model), std::move(effects));
  sim::IntegratorSettings integration;
  integration.method = sim::Method::implicit_euler, integration.step = 0.01;
  integration.linear_solver = sim::IntegratorSettings::LinearSolver::cholesky;
  const auto integrator = sim::make_integrator(integration);
  sim::State state = sim::initial_state(sys.model());
  sim::RunSettings run;
  run.fps = 50, run.duration = 10.0, run.rest_frames = 10;
  run.rest_energy = 0.5 * s.model.mass.mean() * 1e-8;
  const sim::RunSummary summary = sim::run(sys, *integrator, state, run, {});
  x = state.x, simulated_s = summary.simulated_s;
  return summary.ok && summary.at_rest;
}

// The number of nodes (folds) of a draped outline: the maxima of its radius
// ρ(i) round the hem (ρ smoothed over ±2.5°) that stand out from their
// neighbouring minima, so ripples of the mesh are not folds. 0 when the hem
// is round within a millimetre.
int count_nodes(const std::vector<double>& rho) {
  const int n = static_cast<int>(rho.size()), w = std::max(1, n / 144);
  std::vector<double> smooth(n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int k = -w; k <= w; ++k) smooth[i] += rho[((i + k) % n + n) % n];
    smooth[i] /= 2 * w + 1;
  }
  // The circular sequence of extrema (alternating maxima and minima), then the
  // shallowest wave (its smaller rise or fall) dropped until every wave stands
  // out by a tenth of the hem's range and at least a millimetre.
  std::vector<double> ext;
  for (int i = 0; i < n; ++i) {
    const double a = smooth[(i + n - 1) % n], b = smooth[i], c = smooth[(i + 1) % n];
    if ((b > a && b >= c) || (b < a && b <= c)) ext.push_back(b);
  }
  const auto [lo, hi] = std::minmax_element(smooth.begin(), smooth.end());
  const double threshold = std::max(1e-3, 0.1 * (*hi - *lo));
  while (ext.size() >= 4) {
    std::size_t worst = 0;
    double depth = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < ext.size(); ++i) {
      const double d = std::abs(ext[(i + 1) % ext.size()] - ext[i]);
      if (d < depth) depth = d, worst = i;
    }
    if (depth >= threshold) break;
    // Remove the pair (worst, worst + 1): the sequence keeps alternating.
    const std::size_t next = (worst + 1) % ext.size();
    ext.erase(ext.begin() + std::max(worst, next));
    ext.erase(ext.begin() + std::min(worst, next));
  }
  return ext.size() >= 4 ? static_cast<int>(ext.size() / 2) : 0;
}

// Cusick drape tester (BS 5058, ISO 9073-9; mechanics.md §6): a 300 mm disc
// of fabric clamped between two 180 mm disks hangs under its own weight to
// rest. The shadow from above gives DC = (A_s − A_d)/(A_D − A_d); the hem's
// waves the nodes. A polar mesh (rings of one count, so the hem is a regular
// polygon), two held rings for the clamp (acting at their middle, the disk's
// edge), a 0.1 mm random ripple to let the folds choose themselves.
void drape(const LabSpec& spec, const scene::MaterialDef& mat, LabResult& r) {
  if (mat.density <= 0.0) throw Error(mat.name, "density", "the drape test needs the fabric's density");
  constexpr double kD = 0.30, kDisk = 0.18, R = kD / 2, Rd = kDisk / 2;
  constexpr double kPixel = 0.0005;  // m, the shadow's raster
  const int rings = std::max(4, static_cast<int>(std::lround((R - Rd) / spec.resolution + 0.5)));
  const double dr = (R - Rd) / (rings - 0.5);
  const int around = std::max(48, static_cast<int>(std::lround(2 * std::numbers::pi * R / spec.resolution)));
  Specimen s;
  s.nu = around, s.nv = rings + 1, s.h = dr, s.w_cell = 2 * std::numbers::pi * R / around;
  r.x_name = "specimen diameter cm", r.cells_along = rings, r.cells_across = around;
  sim::Model& m = s.model;
  const int N = s.nu * s.nv;
  m.x0 = VecX::Zero(3 * N), m.v0 = VecX::Zero(3 * N), m.uv.resize(N);
  const Eigen::Matrix2d to_warp = to_material(spec.angle_deg);
  for (int j = 0; j < s.nv; ++j)
    for (int i = 0; i < s.nu; ++i) {
      const double rho = Rd - 0.5 * dr + j * dr, phi = 2 * std::numbers::pi * i / around;
      const int p = s.index(i, j);
      m.x0[3 * p] = rho * std::cos(phi), m.x0[3 * p + 1] = rho * std::sin(phi);
      m.uv[p] = to_warp * Eigen::Vector2d(m.x0[3 * p], m.x0[3 * p + 1]);
    }
  for (int j = 0; j + 1 < s.nv; ++j)
    for (int i = 0; i < s.nu; ++i) {
      const int a = s.index(i, j), b = s.index((i + 1) % s.nu, j), c = s.index((i + 1) % s.nu, j + 1),
                d = s.index(i, j + 1);
      m.triangles.push_back({a, d, c}), m.triangles.push_back({a, c, b});  // counter-clockwise
    }
  m.triangle_piece.assign(m.triangles.size(), 0), m.pieces = {"specimen"};
  add_fabric(spec, mat, s);
  std::vector<int> held(2 * s.nu);
  std::iota(held.begin(), held.end(), 0);  // the two inner rings
  VecX x = m.x0;
  std::mt19937 random(1);
  std::uniform_real_distribution<double> ripple(-1e-4, 1e-4);
  for (int p = 2 * s.nu; p < N; ++p) x[3 * p + 2] += ripple(random);
  double simulated = 0.0;
  const bool ok = hang_to_rest(s, held, x, simulated);

  // The shadow: the triangles' projection (z-buffered, shaded by slope) and the disk.
  const int size = static_cast<int>(std::ceil((kD + 0.01) / kPixel));
  const double origin = -0.5 * size * kPixel;
  std::vector<float> depth(std::size_t(size) * size, -std::numeric_limits<float>::infinity());
  r.top_view.assign(std::size_t(size) * size, 255), r.top_view_size = size;
  for (const auto& t : m.triangles) {
    sim::Vec3 q[3];
    for (int k = 0; k < 3; ++k) q[k] = x.segment<3>(3 * t[k]);
    const sim::Vec3 normal = (q[1] - q[0]).cross(q[2] - q[0]);
    const double area2 = normal.z();  // twice the projected signed area
    if (std::abs(area2) < 1e-16) continue;
    const auto shade = static_cast<std::uint8_t>(70 + 130 * std::abs(normal.normalized().z()));
    const int i0 = std::max(0, static_cast<int>((std::min({q[0].x(), q[1].x(), q[2].x()}) - origin) / kPixel));
    const int i1 = std::min(size - 1, static_cast<int>((std::max({q[0].x(), q[1].x(), q[2].x()}) - origin) / kPixel));
    const int j0 = std::max(0, static_cast<int>((std::min({q[0].y(), q[1].y(), q[2].y()}) - origin) / kPixel));
    const int j1 = std::min(size - 1, static_cast<int>((std::max({q[0].y(), q[1].y(), q[2].y()}) - origin) / kPixel));
    for (int pj = j0; pj <= j1; ++pj)
      for (int pi = i0; pi <= i1; ++pi) {
        const double px = origin + (pi + 0.5) * kPixel, py = origin + (pj + 0.5) * kPixel;
        double w[3];
        for (int k = 0; k < 3; ++k) {
          const sim::Vec3 &a = q[(k + 1) % 3], &b = q[(k + 2) % 3];
          w[k] = ((b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x())) / area2;
        }
        if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
        const auto z = static_cast<float>(w[0] * q[0].z() + w[1] * q[1].z() + w[2] * q[2].z());
        const std::size_t at = std::size_t(size - 1 - pj) * size + pi;  // image rows from the top (+y up)
        if (z > depth[at]) depth[at] = z, r.top_view[at] = shade;
      }
  }
  long covered = 0;
  for (int pj = 0; pj < size; ++pj)
    for (int pi = 0; pi < size; ++pi) {
      const double px = origin + (pi + 0.5) * kPixel, py = origin + (pj + 0.5) * kPixel;
      std::uint8_t& pixel = r.top_view[std::size_t(size - 1 - pj) * size + pi];
      if (pixel == 255 && px * px + py * py <= Rd * Rd) pixel = 225;  // the disk, where no fabric lies over it
      covered += pixel != 255;
    }
  const double shadow = covered * kPixel * kPixel;
  std::vector<double> hem(s.nu);
  for (int i = 0; i < s.nu; ++i) hem[i] = x.segment<2>(3 * s.index(i, s.nv - 1)).norm();
  const double nan = std::nan("");
  add_point(r, "DC", 100 * kD, ok ? drape_coefficient(shadow, kD, kDisk) : nan, nan);
  add_point(r, "nodes", 100 * kD, ok ? count_nodes(hem) : nan, nan);
  add_point(r, "shadow area cm2", 100 * kD, ok ? 1e4 * shadow : nan, nan);
  r.notes.push_back("Cusick drape (mechanics.md 6): " + format_fixed(100 * kD, 0) + " cm specimen on a " +
                    format_fixed(100 * kDisk, 0) + " cm disk, static rest under its own weight, shadow on a " +
                    format_fixed(1000 * kPixel, 1) + " mm raster; no contact (folds may pass through each other)");
  r.notes.push_back("no analytic reference (expected = NaN): typical DC at 30/18 cm (mechanics.md 6, recalled ranges) "
                    "0.15-0.40 limp (chiffon, silk crepe, jersey), 0.40-0.70 apparel wovens, 0.70-0.95 stiff "
                    "(denim, canvas); 4-10 nodes");
  r.notes.push_back("hung to rest by the engine's implicit Euler in " + format_fixed(simulated, 2) + " s simulated");
  if (!ok) r.notes.push_back("the specimen did not come to rest within 10 s simulated (NaN)");
}

}  // namespace

LabResult run(const LabSpec& spec, const scene::MaterialDef& given) {
  scene::MaterialDef material = given;
  if (spec.poisson_free && material.orthotropic) {
    material.orthotropic->nu_warp_weft = 0.0;
    material.orthotropic->nu_weft_warp = sim::kDerived;
  }
  if (!(spec.resolution > 0.0) || !(spec.length > 0.0) || !(spec.width > 0.0))
    throw Error(material.name, "lab", "resolution, length and width must be positive");
  if (spec.model == scene::ClothModel::strain_rosette) {
    if (const std::string problem = scene::orthotropic_problem(material); !problem.empty())
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
    case Test::shear: shear(spec, material, r); break;
    case Test::bending: bending(spec, material, r); break;
    case Test::drape: drape(spec, material, r); break;
    case Test::buckling:
      if (spec.model != scene::ClothModel::strain_rosette)
        throw Error(material.name, "buckling", "the buckling test needs the strain-rosette model (mass-spring has no "
                                               "bending stiffness at the straight state)");
      buckling(spec, material, r);
      break;
  }
  if (spec.poisson_free) r.notes.push_back("Poisson coupling off (nu_xy = 0): B_strip = B_plate");
  bool referenced = false;
  for (const auto& p : r.points) {
    if (!std::isfinite(p.expected)) continue;  // no reference (drape)
    referenced = true;
    r.max_rel_error = std::isfinite(p.rel_error) ? std::max(r.max_rel_error, std::abs(p.rel_error))
                                                 : std::numeric_limits<double>::infinity();
  }
  if (!referenced) r.max_rel_error = std::nan("");
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void write_csv(const LabResult& r, const fs::path& file) {
  std::ostringstream out;
  out << "test,material,model,quantity,x,measured,expected,rel_error\n";
  out.precision(10);
  for (const auto& p : r.points)
    out << r.test << ',' << csv_field(r.material) << ',' << r.model << ',' << p.quantity << ',' << p.x << ',' << p.measured << ','
        << p.expected << ',' << p.rel_error << '\n';
  write_file_atomic(file, out.str());
}

const char* describe(Test t) {
  switch (t) {
    case Test::tip_cantilever:
      return "Strip 100 x 10 mm clamped at one end under a dead tip load P per width (seed 002 Fig. 15, after "
             "Eichen): tip shortening u/L and deflection w/L for k = PL^2/B = 1...10 against the elastica "
             "(mechanics.md 1), B = B_strip.";
    case Test::tensile:
      return "ISO 13934-1 strip 200 x 50 mm stretched by 0.01 %, ends free to contract and shear (Instron / "
             "KES-FB1): E_theta at 0, 15, ..., 90 deg against the orthotropic off-axis modulus (mechanics.md 3).";
    case Test::cantilever:
      return "Strip 10 mm wide under its own weight (ASTM D1388 / FAST-2), g = wL^3/B = 1...20: chord angle against "
             "the heavy elastica (mechanics.md 2), and the bending length by Peirce's formula as FAST computes it.";
    case Test::buckling:
      return "Strips 50 and 100 mm, clamped-free (dead end load) and clamped-clamped (end shortening): the load at "
             "which the straight strip loses its stiffness across the sheet against Euler's C B / L^2 (mechanics.md 4); "
             "and a 200 x 50 mm plate clamped on its long edges in shear: critical N_xy and wrinkles, against "
             "k_s pi^2 D / b^2, k_s = 8.98, where the bending is isotropic.";
    case Test::shear:
      return "KES-FB1 shear, 200 mm along the clamps, 50 mm between them, phi = 0.5...8 deg: shear force per clamp "
             "length against uniform simple shear of the law, G at 0.5 deg against Q66 (G_xy).";
    case Test::bending:
      return "KES-FB2 pure bending, 10 mm between clamps set on an arc, K = +-0.5...2.5 1/cm: moment per width "
             "against the plate's B_theta K, and B (the KES slope) warp and weft.";
    case Test::drape:
      return "Cusick drape tester (BS 5058 / ISO 9073-9): a 300 mm disc on a 180 mm disk hung to rest by the "
             "engine's implicit Euler: drape coefficient, nodes, shadow area. No analytic reference.";
  }
  return "?";
}

std::vector<LabSpec> all_specs(scene::ClothModel model, double resolution, double drape_resolution, bool poisson_free) {
  std::vector<LabSpec> specs;
  for (Test t : {Test::tip_cantilever, Test::tensile, Test::cantilever, Test::buckling, Test::shear, Test::bending,
                 Test::drape}) {
    if (t == Test::buckling && model != scene::ClothModel::strain_rosette) continue;
    LabSpec s;
    s.test = t, s.model = model, s.poisson_free = poisson_free;
    s.resolution = t == Test::drape ? drape_resolution : resolution;
    // As `vgd lab TEST` without --angle: tensile and bending at all their angles.
    if (t == Test::tensile || t == Test::bending) s.angle_deg = -1.0;
    specs.push_back(s);
  }
  return specs;
}

namespace {

// A number for the report's tables; "–" where there is none.
std::string cell(double v, const char* format) {
  if (std::isnan(v)) return "–";
  if (std::isinf(v)) return v > 0 ? "inf (failed solve)" : "-inf";
  char b[48];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

}  // namespace

std::string report_markdown(const std::vector<ReportEntry>& runs, const std::string& command,
                            const std::vector<std::string>& notes, double total_wall_s) {
  std::ostringstream md;
  const LabResult* first = runs.empty() ? nullptr : &runs.front().result;
  md << "# Fabric lab report: " << (first ? first->material : "") << ", " << (first ? first->model : "")
     << " model\n\n";
  md << "Generated by `" << command << "`. Largest |relative error| over each test's points with a "
     << "reference; wall times are each test's own (single thread unless --threads).\n\n";
  md << "| test | grid | resolution mm | points | max rel. error | wall s |\n|---|---|---|---|---|---|\n";
  for (const auto& e : runs)
    md << "| [" << e.result.test << "](#" << e.result.test << ") | " << e.result.cells_along << " x "
       << e.result.cells_across << " | " << cell(1000 * e.spec.resolution, "%g") << " | " << e.result.points.size()
       << " | " << cell(e.result.max_rel_error, "%.3e") << " | " << cell(e.result.wall_s, "%.2f") << " |\n";
  md << "\nTotal wall time " << cell(total_wall_s, "%.2f") << " s.\n";
  for (const auto& n : notes) md << "\n- " << n;
  if (!notes.empty()) md << "\n";
  for (const auto& e : runs) {
    const LabResult& r = e.result;
    md << "\n## " << r.test << "\n\n" << describe(parse_test(r.test)) << "\n\n";
    md << "Grid " << r.cells_along << " x " << r.cells_across << " cells at " << cell(1000 * e.spec.resolution, "%g")
       << " mm" << (e.spec.poisson_free ? ", nu_xy = 0" : "") << ". Notes:\n\n";
    for (const auto& n : r.notes) md << "- " << n << "\n";
    md << "\n| quantity | " << r.x_name << " | measured | expected | rel. error |\n|---|---|---|---|---|\n";
    for (const auto& p : r.points)
      md << "| " << p.quantity << " | " << cell(p.x, "%g") << " | " << cell(p.measured, "%.7g") << " | "
         << cell(p.expected, "%.7g") << " | " << cell(p.rel_error, "%+.2e") << " |\n";
    md << "\nMax |rel. error| " << cell(r.max_rel_error, "%.3e") << ", wall " << cell(r.wall_s, "%.2f")
       << " s. Data: [" << e.csv << "](" << e.csv << ").\n\n![" << r.test << "](" << e.png << ")\n";
  }
  return md.str();
}

}  // namespace vgd::lab
