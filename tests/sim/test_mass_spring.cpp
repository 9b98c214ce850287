// The mass-spring cloth (seed 000 §4.1) against the laws it states: topology
// of Figure 1, the force law's derivatives, momentum, rigid-motion invariance,
// Hooke's law at equilibrium, energy under symplectic Euler, Provot's limit,
// stiffness bounds, deterministic and parallel sums, refusals.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <omp.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <random>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/integrator.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

// An nu × nv grid of spacing d (m) in the z = 0 plane, 0.1 kg particles.
Model grid(int nu, int nv, double d = 0.1) {
  return make_grid(nu, nv, d, d, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 0.1);
}

// The unit square meshed with triangles of mixed orientation: n × n nodes,
// interior ones moved by up to ±30 % of the spacing, each cell cut along a
// random diagonal. Placed flat at z = 0, 0.1 kg particles.
Model mixed_square(int n, unsigned seed = 3) {
  Model m = grid(n, n, 1.0 / (n - 1));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3 / (n - 1), 0.3 / (n - 1));
  for (int j = 1; j + 1 < n; ++j)
    for (int i = 1; i + 1 < n; ++i) m.uv[j * n + i] += Vec2(jitter(rng), jitter(rng));
  m.triangles.clear();
  std::bernoulli_distribution flip(0.5);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      if (flip(rng)) {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({a, d, c});
      } else {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({b, d, c});
      }
    }
  for (int p = 0; p < m.num_particles(); ++p) at(m.x0, p) = Vec3(m.uv[p].x(), m.uv[p].y(), 0.0);
  return m;
}

// A random deformed state: every particle moved by up to `amp` (m) per axis,
// random velocities of up to `speed` (m/s) per axis.
void deform(const Model& m, double amp, double speed, unsigned seed, VecX& x, VecX& v) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  x = m.x0;
  v = VecX::Zero(m.num_dofs());
  for (int k = 0; k < m.num_dofs(); ++k) x[k] += amp * u(rng), v[k] = speed * u(rng);
}

Mat3 rotation() { return Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix(); }

// Materials with distinct constants, so that a spring given the wrong one shows.
MassSpringMaterial distinct_material() {
  MassSpringMaterial mat;
  mat.warp = 1800, mat.weft = 1200, mat.shear = 400, mat.bend_warp = 300, mat.bend_weft = 200, mat.damping = 2.0;
  return mat;
}

// In-plane stiffness (N/m) of a cloth on the unit square under a small uniform
// stretch along the warp (u) or the weft (v): 2 E / (ε² A), A = 1 m².
double sheet_stiffness(const Model& m, const MassSpringMaterial& mat, bool along_warp) {
  auto e = make_mass_spring(m, {mat});
  const double eps = 1e-4;
  VecX x(m.num_dofs());
  for (int p = 0; p < m.num_particles(); ++p)
    at(x, p) = Vec3(m.uv[p].x() * (along_warp ? 1 + eps : 1), m.uv[p].y() * (along_warp ? 1 : 1 + eps), 0.0);
  return 2.0 * e->energy({m, 0.0, x, m.v0}) / (eps * eps);
}

}  // namespace

// ---- topology ----------------------------------------------------------------

TEST(MassSpringTopology, GridHasFigure1SpringsOfEachKind) {
  const int nu = 7, nv = 5;
  const Model m = make_grid(nu, nv, 0.1, 0.05, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ(), 0.1);
  const SpringTopology t = mass_spring_topology(m, {distinct_material()});
  EXPECT_EQ(t.lattice_pieces, std::vector<int>{0});
  EXPECT_EQ(t.count(SpringKind::warp), (nu - 1) * nv);
  EXPECT_EQ(t.count(SpringKind::weft), nu * (nv - 1));
  EXPECT_EQ(t.count(SpringKind::shear), 2 * (nu - 1) * (nv - 1));
  EXPECT_EQ(t.count(SpringKind::bend_warp), (nu - 2) * nv);
  EXPECT_EQ(t.count(SpringKind::bend_weft), nu * (nv - 2));
  // Each kind joins the particles Figure 1 says, with its constant and rest length from uv.
  for (int s = 0; s < t.size(); ++s) {
    const int di = t.b[s] % nu - t.a[s] % nu, dj = t.b[s] / nu - t.a[s] / nu;
    const double du = di * 0.1, dv = dj * 0.05;
    EXPECT_NEAR(t.rest[s], std::hypot(du, dv), 1e-15);
    switch (t.kind[s]) {
      case SpringKind::warp: EXPECT_TRUE(di == 1 && dj == 0 && t.k[s] == 1800); break;
      case SpringKind::weft: EXPECT_TRUE(di == 0 && dj == 1 && t.k[s] == 1200); break;
      case SpringKind::shear: EXPECT_TRUE(std::abs(di) == 1 && dj == 1 && t.k[s] == 400); break;
      case SpringKind::bend_warp: EXPECT_TRUE(di == 2 && dj == 0 && t.k[s] == 300); break;
      case SpringKind::bend_weft: EXPECT_TRUE(di == 0 && dj == 2 && t.k[s] == 200); break;
    }
  }
  // No spring twice.
  for (int s = 1; s < t.size(); ++s) EXPECT_TRUE(t.a[s - 1] != t.a[s] || t.b[s - 1] != t.b[s]);
}

TEST(MassSpringTopology, MixedTriangleSquareHasAllKindsAndGridLikeInPlaneStiffness) {
  const Model mesh = mixed_square(11);
  const Model lattice = grid(11, 11);
  const MassSpringMaterial mat;  // the seed's constants
  const SpringTopology t = mass_spring_topology(mesh, {mat});
  EXPECT_TRUE(t.lattice_pieces.empty());
  for (int k = 0; k < kSpringKinds; ++k)
    EXPECT_GT(t.count(static_cast<SpringKind>(k)), 20) << to_string(static_cast<SpringKind>(k));
  // Blended constants stay between the extremes of their family.
  for (int s = 0; s < t.size(); ++s) {
    EXPECT_GE(t.k[s], 400.0 - 1e-9);
    EXPECT_LE(t.k[s], 1800.0 + 1e-9);
  }
  // What is checked: the sheet's stiffness under a uniform stretch along the
  // warp and along the weft, 2E/(ε²A), is within a factor 1.5 of the grid's
  // with the same constants and spacing (0.1 m).
  for (bool warp : {true, false}) {
    const double ym = sheet_stiffness(mesh, mat, warp), yg = sheet_stiffness(lattice, mat, warp);
    EXPECT_GT(ym / yg, 1 / 1.5) << (warp ? "warp" : "weft") << ": mesh " << ym << " N/m, grid " << yg << " N/m";
    EXPECT_LT(ym / yg, 1.5) << (warp ? "warp" : "weft") << ": mesh " << ym << " N/m, grid " << yg << " N/m";
  }
  // And a fabric twice as stiff along the warp is so on both.
  MassSpringMaterial aniso = mat;
  aniso.warp = 3600, aniso.weft = 900, aniso.bend_warp = 600, aniso.bend_weft = 150;
  for (const Model* m : {&mesh, &lattice})
    EXPECT_GT(sheet_stiffness(*m, aniso, true) / sheet_stiffness(*m, aniso, false), 2.0);
}

TEST(MassSpringTopology, MeshSpringConstantsBlendByDirectionInMaterialSpace) {
  // Two triangles: (0,0) (1,0) (0,1) and, across the hypotenuse, a vertex p at
  // 20° from the warp seen from the origin. With c = cos 2φ (computed here with
  // trigonometry), k = c² k_yarn + (1 − c²) k_shear: the edges along u and v get
  // warp and weft, the hypotenuse (135°) shear, the opposite-vertex spring
  // (0,0)–p at 20° mostly bend_warp.
  const double a = 20.0 * M_PI / 180.0;
  Model m = particles(4, 0.1);
  m.uv = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), 1.2 * Vec2(std::cos(a), std::sin(a))};
  m.triangles = {{0, 1, 2}, {1, 3, 2}};
  const MassSpringMaterial mat = distinct_material();
  const SpringTopology t = mass_spring_topology(m, {mat});
  ASSERT_EQ(t.size(), 6);
  auto k_of = [&](int i, int j) {
    for (int s = 0; s < t.size(); ++s)
      if (t.a[s] == std::min(i, j) && t.b[s] == std::max(i, j)) return t.k[s];
    return -1.0;
  };
  auto blended = [](const Vec2& d, double warp, double weft, double shear) {
    const double c = std::cos(2.0 * std::atan2(d.y(), d.x()));
    return c * c * (c > 0 ? warp : weft) + (1.0 - c * c) * shear;
  };
  EXPECT_DOUBLE_EQ(k_of(0, 1), mat.warp);
  EXPECT_DOUBLE_EQ(k_of(0, 2), mat.weft);
  EXPECT_NEAR(k_of(1, 2), mat.shear, 1e-9);
  EXPECT_NEAR(k_of(1, 3), blended(m.uv[3] - m.uv[1], mat.warp, mat.weft, mat.shear), 1e-9);
  EXPECT_NEAR(k_of(2, 3), blended(m.uv[3] - m.uv[2], mat.warp, mat.weft, mat.shear), 1e-9);
  EXPECT_NEAR(k_of(0, 3), blended(m.uv[3], mat.bend_warp, mat.bend_weft, mat.shear), 1e-9);
  EXPECT_EQ(t.count(SpringKind::bend_warp), 1);
}

TEST(MassSpringTopology, RestShapeComesFromThePatternNotThePlacement) {
  // A grid wrapped onto a cylinder of radius 0.3 m: springs still rest at their uv lengths.
  Model m = grid(6, 4);
  for (int p = 0; p < m.num_particles(); ++p) {
    const double a = m.uv[p].x() / 0.3;
    at(m.x0, p) = Vec3(0.3 * std::sin(a), m.uv[p].y(), 0.3 * (1 - std::cos(a)));
  }
  const SpringTopology t = mass_spring_topology(m, {MassSpringMaterial{}});
  for (int s = 0; s < t.size(); ++s) EXPECT_DOUBLE_EQ(t.rest[s], (m.uv[t.a[s]] - m.uv[t.b[s]]).norm());
  auto e = make_mass_spring(m, {MassSpringMaterial{}});
  EXPECT_GT(forces(*e, m, m.x0, m.v0).norm(), 1.0);  // curved: the bending springs pull it flat
}

// ---- force law ------------------------------------------------------------------

TEST(MassSpring, ForceEqualsMinusEnergyGradient) {
  // Central differences of the energy, h = 1e-6 m: truncation ~h² E''' < 1e-8 N,
  // round-off ~1e-16 E / h < 1e-8 N; forces are ~10–100 N. Tolerance 1e-6 N.
  for (const Model& m : {grid(5, 4), mixed_square(5)}) {
    MassSpringMaterial mat = distinct_material();
    mat.damping = 0.0;  // the damping term has no potential
    auto e = make_mass_spring(m, {mat});
    VecX x, v;
    deform(m, 0.03, 0.0, 11, x, v);
    const VecX f = forces(*e, m, x, v);
    const double h = 1e-6;
    for (int k = 0; k < m.num_dofs(); ++k) {
      VecX xp = x, xm = x;
      xp[k] += h, xm[k] -= h;
      const double grad = (e->energy({m, 0, xp, v}) - e->energy({m, 0, xm, v})) / (2 * h);
      EXPECT_NEAR(f[k], -grad, 1e-6) << "dof " << k;
    }
    EXPECT_GT(f.lpNorm<Eigen::Infinity>(), 10.0);  // the state is really deformed
  }
}

TEST(MassSpring, JacobianMatchesFiniteDifferencesOfTheForces) {
  // Central differences, h = 1e-6 (m and m/s). Entries are up to ~4000 N/m;
  // truncation ~h² f''' ~ 1e-12 · k r / L³ < 1e-6 N/m, round-off ~1e-16 |f| / h
  // < 1e-7 N/m. Tolerance 1e-5 N/m per entry. The damping constant is large
  // (5 N·s/m, speeds of 1 m/s) so that the damping term's x-dependence
  // (~k_d |l′|/L ≈ 50 N/m) would fail the test if it were missing.
  for (const Model& m : {grid(4, 4), mixed_square(4)}) {
    MassSpringMaterial mat = distinct_material();
    mat.damping = 5.0;
    auto e = make_mass_spring(m, {mat});
    VecX x, v;
    // Every spring stretched: under compression the Jacobian's transverse
    // term is clamped on purpose (next test), so it is not the derivative.
    deform(m, 0.01, 1.0, 5, x, v);
    x *= 1.5;
    Triplets tx, tv;
    ASSERT_TRUE(e->add_jacobian({m, 0, x, v}, tx, tv));
    SparseMatrix Jx(m.num_dofs(), m.num_dofs()), Jv(m.num_dofs(), m.num_dofs());
    Jx.setFromTriplets(tx.begin(), tx.end());
    Jv.setFromTriplets(tv.begin(), tv.end());
    const double h = 1e-6;
    double worst_x = 0, worst_v = 0, damping_part = 0;
    for (int c = 0; c < m.num_dofs(); ++c) {
      VecX xp = x, xm = x, vp = v, vm = v;
      xp[c] += h, xm[c] -= h, vp[c] += h, vm[c] -= h;
      const VecX fdx = (forces(*e, m, xp, v) - forces(*e, m, xm, v)) / (2 * h);
      const VecX fdv = (forces(*e, m, x, vp) - forces(*e, m, x, vm)) / (2 * h);
      const VecX fd0 = (forces(*e, m, xp, VecX::Zero(m.num_dofs())) - forces(*e, m, xm, VecX::Zero(m.num_dofs()))) / (2 * h);
      worst_x = std::max(worst_x, (fdx - VecX(Jx.col(c))).lpNorm<Eigen::Infinity>());
      worst_v = std::max(worst_v, (fdv - VecX(Jv.col(c))).lpNorm<Eigen::Infinity>());
      damping_part = std::max(damping_part, (fdx - fd0).lpNorm<Eigen::Infinity>());
    }
    EXPECT_LT(worst_x, 1e-5);
    EXPECT_LT(worst_v, 1e-5);
    EXPECT_GT(damping_part, 1.0);  // the x-dependence of the damping is really exercised
  }
}

TEST(MassSpring, CompressedSpringsGiveADefiniteStepMatrix) {
  // A cloth squeezed to 70 % with its springs' transverse stiffness k (1 − r/L)
  // negative: the implicit step matrix M − h² ∂f/∂x stays positive definite
  // for any h, because the Jacobian clamps that term at 0 (Choi & Ko 2002).
  const Model m = grid(5, 5);
  auto e = make_mass_spring(m, {distinct_material()});
  VecX x = 0.7 * m.x0, v = VecX::Zero(m.num_dofs());
  for (int i = 0; i < m.num_particles(); ++i) x[3 * i + 2] += 0.01 * std::sin(1.7 * i);  // out of plane
  Triplets tx, tv;
  ASSERT_TRUE(e->add_jacobian({m, 0, x, v}, tx, tv));
  SparseMatrix K(m.num_dofs(), m.num_dofs());
  K.setFromTriplets(tx.begin(), tx.end());
  const Eigen::MatrixXd negK = -Eigen::MatrixXd(K);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (negK + negK.transpose()));
  // −K is positive semi-definite: its smallest eigenvalue is 0 (rigid motions) up to round-off.
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-9 * eig.eigenvalues().maxCoeff());
}

TEST(MassSpring, InternalForcesConserveLinearAndAngularMomentum) {
  for (const Model& m : {grid(6, 5), mixed_square(6)}) {
    auto e = make_mass_spring(m, {distinct_material()});
    for (unsigned seed : {1u, 2u, 3u}) {
      VecX x, v;
      deform(m, 0.2, 3.0, seed, x, v);  // large, arbitrary: compressed and stretched springs
      const VecX f = forces(*e, m, x, v);
      Vec3 total = Vec3::Zero(), torque = Vec3::Zero();
      for (int p = 0; p < m.num_particles(); ++p) total += at(f, p), torque += at(x, p).cross(at(f, p));
      const double scale = f.lpNorm<Eigen::Infinity>();
      EXPECT_GT(scale, 10.0);
      EXPECT_LT(total.norm(), 1e-12 * scale * m.num_particles());
      EXPECT_LT(torque.norm(), 1e-12 * scale * m.num_particles());
    }
  }
}

TEST(MassSpring, RigidMotionsOfTheRestShapeGiveZeroForce) {
  // The rest shape (uv at z = 0), rotated, translated and spinning: no force.
  for (const Model& m : {grid(6, 5), mixed_square(6)}) {
    auto e = make_mass_spring(m, {distinct_material()});
    const Mat3 R = rotation();
    const Vec3 shift(0.3, -1.2, 2.0), omega(0.5, -2.0, 1.5), drift(1.0, 2.0, -0.5);
    VecX x(m.num_dofs()), v(m.num_dofs());
    for (int p = 0; p < m.num_particles(); ++p) {
      at(x, p) = R * Vec3(m.uv[p].x(), m.uv[p].y(), 0.0) + shift;
      at(v, p) = drift + omega.cross(at(x, p) - shift);
    }
    EXPECT_LT(forces(*e, m, x, v).lpNorm<Eigen::Infinity>(), 1e-11);
    EXPECT_LT(e->energy({m, 0, x, v}), 1e-20);
    // ... while a uniform stretch of 1 % is felt.
    EXPECT_GT(forces(*e, m, 1.01 * x, v).lpNorm<Eigen::Infinity>(), 1.0);
  }
}

// ---- physics --------------------------------------------------------------------

TEST(MassSpring, HangingStripStretchesAsHookesLawSays) {
  // Two columns of 10 particles (0.1 kg, 0.1 m apart) hanging from their top
  // pair, structural springs only (k = 1800 N/m). At rest the weft spring
  // below row j carries the weight of the rows below it:
  //   extension_j = (nv − 1 − j) m g / k   (top spring: 9 × 0.981 / 1800 = 4.9 mm).
  // Tolerance 1e-9 m: the run stops when every particle is slower than
  // 1e-10 m/s, so the remaining oscillation is below 1e-10 / ω_min (ω_min ≈ 22 rad/s)
  // ≈ 5e-12 m, far under it; the residual viscous force k_v |v| ~ 1e-10 N moves
  // the equilibrium by ~1e-13 m.
  const int nv = 10;
  const double m_p = 0.1, k = 1800.0, g = 9.81;
  Model m = make_grid(2, nv, 0.1, 0.1, Vec3::Zero(), Vec3::UnitX(), -Vec3::UnitY(), m_p);
  MassSpringMaterial mat;
  mat.warp = mat.weft = k;
  mat.shear = mat.bend_warp = mat.bend_weft = 0.0;
  System sys(m, effects(make_mass_spring(m, {mat}), make_gravity({Vec3(0, -g, 0)}), make_viscosity({1.0, 0.0}),
                        make_pins(m, {{0, 1}})));
  IntegratorSettings st;
  st.method = Method::symplectic_euler;
  st.step = 0.001;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  double speed = 1.0;
  while (speed > 1e-10 && s.t < 60.0) {
    integ->advance(sys, s, s.t + 1.0);
    speed = 0.0;
    for (int p = 0; p < m.num_particles(); ++p) speed = std::max(speed, at(s.v, p).norm());
  }
  ASSERT_LE(speed, 1e-10) << "not at rest after " << s.t << " s";
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j + 1 < nv; ++j) {
      const double length = (at(s.x, j * 2 + i) - at(s.x, (j + 1) * 2 + i)).norm();
      EXPECT_NEAR(length - 0.1, (nv - 1 - j) * m_p * g / k, 1e-9) << "column " << i << ", row " << j;
    }
}

TEST(MassSpring, UndampedOscillationKeepsItsEnergyWithSymplecticEuler) {
  // A 8 × 8 cloth, released from a random deformation with no damping, no
  // gravity: 20 000 steps at 1/10 of the stability limit. Symplectic Euler
  // keeps a shadow energy, so the true energy oscillates by O(h ω) without drift.
  Model m = grid(8, 8);
  VecX x, v;
  deform(m, 0.02, 0.0, 9, x, v);
  m.x0 = x;
  MassSpringMaterial mat;
  mat.damping = 0.0;
  System sys(m, effects(make_mass_spring(m, {mat})));
  IntegratorSettings st;
  st.step = 0.1 * stability_limit(Method::symplectic_euler, sys.stiffness());
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  const double e0 = sys.potential_energy(0, s.x, s.v);
  ASSERT_GT(e0, 0.1);
  double lo = e0, hi = e0, early = 0, late = 0;
  const int steps = 20000, window = 2000;
  for (int k = 1; k <= steps; ++k) {
    integ->advance(sys, s, k * st.step);
    const double e = sys.kinetic_energy(s.v) + sys.potential_energy(s.t, s.x, s.v);
    lo = std::min(lo, e), hi = std::max(hi, e);
    if (k <= window) early += e / window;
    if (k > steps - window) late += e / window;
  }
  EXPECT_LT(hi / e0, 1.05);
  EXPECT_GT(lo / e0, 0.95);
  EXPECT_NEAR(late / early, 1.0, 0.005);  // no drift
}

TEST(MassSpring, ProvotLimitKeepsEveryStructuralSpringWithinMaxStrain) {
  // The seed's cloth (its constants, 0.1 kg particles) as a 12 × 12 flag of
  // 1 m hanging from two corners: without the limit its corner springs stretch
  // by ~40 %; with max_strain = 0.1, no warp or weft spring is longer than
  // 1.1 r (1 + limit_tolerance) after any step, and the limiter converged
  // within its passes every time.
  const int n = 12;
  struct Outcome {
    double worst = 0.0;  // largest strain of a warp or weft spring after any step
    MassSpringStats stats;
  };
  const MassSpringOptions defaults;
  auto run = [&](double max_strain) {
    Model m = make_grid(n, n, 1.0 / (n - 1), 1.0 / (n - 1), Vec3::Zero(), Vec3::UnitX(), -Vec3::UnitY(), 0.1);
    MassSpringMaterial mat;
    mat.max_strain = max_strain;
    MassSpringOptions opt;
    opt.fixed = {0, n - 1};
    const SpringTopology top = mass_spring_topology(m, {mat});
    System sys(m, effects(make_mass_spring(m, {mat}, opt), make_gravity({}), make_viscosity({0.2, 0.0}),
                          make_pins(m, {opt.fixed})));
    Outcome out;
    step_through(sys, 0.002, 500, [&](int, const State& s) {  // 1 s, checked after every step
      for (int q = 0; q < top.size(); ++q)
        if (top.kind[q] == SpringKind::warp || top.kind[q] == SpringKind::weft)
          out.worst = std::max(out.worst, (at(s.x, top.a[q]) - at(s.x, top.b[q])).norm() / top.rest[q] - 1.0);
      EXPECT_EQ(at(s.x, 0), at(m.x0, 0));  // the pinned corner stays put
      return true;
    });
    out.stats = *mass_spring_stats(*sys.effects()[0]);
    return out;
  };
  const Outcome free = run(0.0), limited = run(0.1);
  EXPECT_EQ(free.stats.corrections, 0);
  EXPECT_GT(free.worst, 0.3);
  EXPECT_LE(limited.worst, 1.1 * (1.0 + defaults.limit_tolerance) - 1.0 + 1e-12);
  EXPECT_GT(limited.worst, 0.1);  // the limit was reached: the check above is not idle
  EXPECT_GT(limited.stats.corrections, 0);
  EXPECT_EQ(limited.stats.unresolved_steps, 0);
  EXPECT_EQ(limited.stats.limited_springs, 2 * n * (n - 1));
  EXPECT_EQ(mass_spring_stats(*make_gravity({})), nullptr);
}

TEST(MassSpring, ProvotCorrectionKeepsMomentumAndLeavesFixedParticlesAlone) {
  // Three particles in a row along the warp, the outer springs stretched by
  // 50 % and flying apart: one call shortens both to 1.1 r, removes the
  // separating velocity, and conserves momentum; a fixed particle does not move.
  Model m = grid(3, 2);
  MassSpringMaterial mat;
  mat.max_strain = 0.1;
  for (bool fix_first : {false, true}) {
    MassSpringOptions opt;
    if (fix_first) opt.fixed = {0};
    opt.limit_tolerance = 0.0;
    opt.limit_passes = 200;
    auto e = make_mass_spring(m, {mat}, opt);
    State s = initial_state(m);
    for (int p : {0, 3}) at(s.x, p) -= Vec3(0.05, 0, 0), at(s.v, p) = Vec3(-1, 0, 0);
    for (int p : {2, 5}) at(s.x, p) += Vec3(0.05, 0, 0), at(s.v, p) = Vec3(1, 0, 0);
    const VecX x_before = s.x;
    Vec3 p_before = Vec3::Zero(), p_after = Vec3::Zero();
    for (int p = 0; p < m.num_particles(); ++p) p_before += m.mass[p] * at(s.v, p);
    e->after_step(m, s);
    for (int p = 0; p < m.num_particles(); ++p) p_after += m.mass[p] * at(s.v, p);
    EXPECT_NEAR((at(s.x, 1) - at(s.x, 0)).norm(), 0.11, 1e-9);
    EXPECT_NEAR((at(s.x, 2) - at(s.x, 1)).norm(), 0.11, 1e-9);
    EXPECT_LE((at(s.v, 2) - at(s.v, 1)).x(), 1e-12);  // no longer separating
    if (fix_first) {
      EXPECT_EQ(at(s.x, 0), at(x_before, 0));
    } else {
      EXPECT_LT((p_after - p_before).norm(), 1e-12);
    }
    EXPECT_GT(mass_spring_stats(*e)->corrections, 0);
  }
}

TEST(MassSpring, StiffnessBoundCoversTheHighestFrequency) {
  // λ_max(M⁻¹ ∂f/∂x) ≤ max_i k_i / m_i at the rest shape and at deformed states
  // (every spring between 0.5 r and 2 r), and the bound is within 2.5x of the
  // truth at rest, not uselessly loose (measured: 2.02x on the grid, 2.36x on
  // the mixed mesh; Gershgorin adds the norms of orthogonal springs' blocks).
  Model triangle = particles(3, 0.1);  // one equilateral triangle: 3 springs, λ_max = 3k/m, bound 4k/m
  triangle.uv = {Vec2(0, 0), Vec2(0.1, 0), Vec2(0.05, 0.05 * std::sqrt(3.0))};
  triangle.triangles = {{0, 1, 2}};
  for (int p = 0; p < 3; ++p) at(triangle.x0, p) = Vec3(triangle.uv[p].x(), triangle.uv[p].y(), 0.0);
  for (const Model& m : {grid(8, 8), mixed_square(7), triangle}) {
    auto e = make_mass_spring(m, {distinct_material()});
    VecX kr = VecX::Zero(m.num_particles()), cr = VecX::Zero(m.num_particles());
    e->add_stiffness_bound(m, kr, cr);
    double bound = 0.0;
    for (int p = 0; p < m.num_particles(); ++p) bound = std::max(bound, kr[p] / m.mass[p]);
    auto highest = [&](const VecX& x) {
      Triplets tx, tv;
      const VecX v = VecX::Zero(m.num_dofs());
      e->add_jacobian({m, 0, x, v}, tx, tv);
      SparseMatrix J(m.num_dofs(), m.num_dofs());
      J.setFromTriplets(tx.begin(), tx.end());
      Eigen::MatrixXd A = -Eigen::MatrixXd(J);
      for (int r = 0; r < m.num_dofs(); ++r) A.row(r) /= m.mass[r / 3];  // equal masses: stays symmetric
      return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues().cwiseAbs().maxCoeff();
    };
    const double at_rest = highest(m.x0);
    EXPECT_LE(at_rest, bound);
    EXPECT_GT(at_rest, bound / 2.5);
    const SpringTopology t = mass_spring_topology(m, {distinct_material()});
    const double shortest = *std::min_element(t.rest.begin(), t.rest.end());
    for (unsigned seed : {1u, 2u, 3u, 4u}) {
      VecX x, v;
      deform(m, 0.12 * shortest, 0.0, seed, x, v);
      for (int s = 0; s < t.size(); ++s) {
        const double L = (at(x, t.a[s]) - at(x, t.b[s])).norm();
        ASSERT_TRUE(L >= 0.5 * t.rest[s] && L <= 2 * t.rest[s]);
      }
      EXPECT_LE(highest(x), bound) << "seed " << seed;
    }
  }
}

// ---- sums -------------------------------------------------------------------------

TEST(MassSpring, TheSumIsBitForBitTheSameForAnyThreadCount) {
  // The seed's 30 × 30 flag (5 102 springs: above the parallel threshold).
  const Model m = make_grid(30, 30, 1.0 / 29, 1.0 / 29, Vec3::Zero(), Vec3::UnitX(), -Vec3::UnitY(), 0.1);
  auto e = make_mass_spring(m, {MassSpringMaterial{}});
  VecX x, v;
  deform(m, 0.01, 1.0, 21, x, v);
  const int saved = omp_get_max_threads();
  auto with_threads = [&](int n) {
    omp_set_num_threads(n);
    VecX f = VecX::Constant(m.num_dofs(), 0.25);  // the sum adds into what is there
    e->add_forces({m, 0, x, v}, f);
    return f;
  };
  const VecX serial = with_threads(1), again = with_threads(1);
  EXPECT_EQ(std::memcmp(serial.data(), again.data(), sizeof(double) * serial.size()), 0);
  for (int n : {2, 3, 4}) {
    const VecX par = with_threads(n), par_again = with_threads(n);
    // Fixed chunks: the thread count only decides who sums which chunk.
    EXPECT_EQ(std::memcmp(par.data(), serial.data(), sizeof(double) * par.size()), 0) << n << " threads";
    EXPECT_EQ(std::memcmp(par.data(), par_again.data(), sizeof(double) * par.size()), 0) << n << " threads";
  }
  omp_set_num_threads(saved);
}

// ---- refusals ---------------------------------------------------------------------

TEST(MassSpring, InvalidMaterialsAreRefusedNamingTheField) {
  const Model m = grid(3, 3);
  auto message = [&](const std::vector<MassSpringMaterial>& mats) -> std::string {
    try {
      make_mass_spring(m, mats);
    } catch (const SimulationError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  const std::pair<const char*, double MassSpringMaterial::*> fields[] = {
      {"warp", &MassSpringMaterial::warp},           {"weft", &MassSpringMaterial::weft},
      {"shear", &MassSpringMaterial::shear},         {"bend_warp", &MassSpringMaterial::bend_warp},
      {"bend_weft", &MassSpringMaterial::bend_weft}, {"damping", &MassSpringMaterial::damping},
      {"max_strain", &MassSpringMaterial::max_strain}};
  for (const auto& [name, field] : fields)
    for (double bad : {-1.0, std::nan(""), HUGE_VAL}) {
      MassSpringMaterial mat;
      mat.*field = bad;
      const std::string msg = message({mat});
      EXPECT_NE(msg.find(std::string(name) + " = "), std::string::npos) << msg;
    }
  EXPECT_NE(message({}).find("no material"), std::string::npos);
  EXPECT_NE(message({MassSpringMaterial{}, MassSpringMaterial{}}).find("2 materials for 1 pieces"), std::string::npos);
  Model bad_piece = m;
  bad_piece.triangle_piece[3] = 4;
  try {
    make_mass_spring(bad_piece, {MassSpringMaterial{}});
    ADD_FAILURE() << "piece 4 accepted";
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 3 belongs to piece 4"), std::string::npos) << e.what();
  }
  EXPECT_EQ(message({MassSpringMaterial{}}), "(accepted)");
}

TEST(MassSpring, EachPieceGetsItsOwnMaterial) {
  // Two grids side by side as two pieces: the second one's springs carry its constants.
  Model a = grid(3, 3), b = grid(3, 3);
  Model m = a;
  const int n = a.num_particles();
  m.x0.conservativeResize(2 * a.num_dofs());
  m.v0 = VecX::Zero(2 * a.num_dofs());
  m.mass = VecX::Constant(2 * n, 0.1);
  for (int p = 0; p < n; ++p) {
    m.uv.push_back(b.uv[p] + Vec2(1.0, 0.0));
    at(m.x0, n + p) = at(b.x0, p) + Vec3(1.0, 0.0, 0.0);
  }
  for (const auto& t : b.triangles) m.triangles.push_back({t[0] + n, t[1] + n, t[2] + n}), m.triangle_piece.push_back(1);
  m.pieces = {"front", "back"};
  MassSpringMaterial soft;
  soft.warp = 10.0;
  const SpringTopology t = mass_spring_topology(m, {MassSpringMaterial{}, soft});
  EXPECT_EQ(t.lattice_pieces, (std::vector<int>{0, 1}));
  for (int s = 0; s < t.size(); ++s) {
    if (t.kind[s] == SpringKind::warp) {
      EXPECT_EQ(t.k[s], t.a[s] < n ? 1800.0 : 10.0);
    }
  }
}
