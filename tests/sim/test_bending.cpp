// Bending across interior edges against plate and beam theory: flat sheets,
// exact curvature of quadratic surfaces, cylinders carrying B_θ/R, the
// cantilever's tip deflection, energy/Jacobian against finite differences,
// momentum, threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <cmath>
#include <cstdio>
#include <random>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/bending.hpp"
#include "vgd/sim/integrator.hpp"
#include "vgd/sim/effects/strain_rosette.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

OrthotropicMaterial reference() { return OrthotropicMaterial{}; }

// A grid in uv with its inner particles jittered (an irregular mesh), flat at z = 0.
Model irregular(int nu, int nv, double d, double jitter, unsigned seed) {
  Model m = make_grid(nu, nv, d, d, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1e-4);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * d, jitter * d);
  for (int j = 1; j + 1 < nv; ++j)
    for (int i = 1; i + 1 < nu; ++i) {
      const int p = j * nu + i;
      m.uv[p] += Vec2(u(rng), u(rng));
      at(m.x0, p) = Vec3(m.uv[p].x(), m.uv[p].y(), 0.0);
    }
  return m;
}

double energy(const Effect& e, const Model& m, const VecX& x) { return e.energy({m, 0.0, x, m.v0}); }

// The pattern wrapped on a cylinder of curvature k (1/m) whose curvature runs
// along the direction at angle theta to the warp (the fold lines across it).
VecX cylinder(const Model& m, double k, double theta) {
  const Vec2 n(std::cos(theta), std::sin(theta)), t(-std::sin(theta), std::cos(theta));
  VecX x(m.num_dofs());
  for (int i = 0; i < m.num_particles(); ++i) {
    const double a = m.uv[i].dot(n), b = m.uv[i].dot(t);
    const double xa = std::sin(k * a) / k, z = (1.0 - std::cos(k * a)) / k;
    at(x, i) = Vec3(xa * n.x() + b * t.x(), xa * n.y() + b * t.y(), z);
  }
  return x;
}

double pattern_area(const Model& m) {
  double a = 0.0;
  for (const auto& t : m.triangles) {
    const Vec2 p = m.uv[t[1]] - m.uv[t[0]], q = m.uv[t[2]] - m.uv[t[0]];
    a += 0.5 * std::abs(p.x() * q.y() - p.y() * q.x());
  }
  return a;
}

// Moment per width (N·m/m) of a sheet held on a cylinder: M = (1/A) dU/dk.
double cylinder_moment(const Effect& e, const Model& m, double k, double theta) {
  const double dk = 1e-4 * k;
  return (energy(e, m, cylinder(m, k + dk, theta)) - energy(e, m, cylinder(m, k - dk, theta))) / (2 * dk) /
         pattern_area(m);
}

// A random bent, stretched state of a flat model.
VecX crumpled(const Model& m, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n01;
  VecX x = m.x0;
  for (int i = 0; i < m.num_particles(); ++i) {
    const Vec2 p = m.uv[i];
    x[3 * i + 2] += 0.3 * p.x() * p.x() - 0.5 * p.x() * p.y() + 0.2 * p.y() * p.y();
    for (int c = 0; c < 3; ++c) x[3 * i + c] += amplitude * n01(rng);
  }
  return x;
}

// Static equilibrium by Newton with the exact Jacobians; `fixed` particles stay.
void solve_static(const std::vector<Effect*>& effects, const Model& m, VecX& x, const std::vector<bool>& fixed,
                  const VecX& f_ext) {
  std::vector<int> dofs, slot(m.num_dofs(), -1);
  for (int p = 0; p < m.num_particles(); ++p)
    if (!fixed[p])
      for (int c = 0; c < 3; ++c) slot[3 * p + c] = static_cast<int>(dofs.size()), dofs.push_back(3 * p + c);
  for (int it = 0; it < 40; ++it) {
    VecX f = f_ext;
    for (auto* e : effects) e->add_forces({m, 0.0, x, m.v0}, f);
    VecX r(dofs.size());
    for (std::size_t k = 0; k < dofs.size(); ++k) r[k] = f[dofs[k]];
    if (r.norm() < 1e-13 * f_ext.norm()) break;
    Triplets jx, jv, red;
    for (auto* e : effects) e->add_jacobian({m, 0.0, x, m.v0}, jx, jv);
    for (const auto& t : jx)
      if (slot[t.row()] >= 0 && slot[t.col()] >= 0) red.emplace_back(slot[t.row()], slot[t.col()], t.value());
    SparseMatrix J(dofs.size(), dofs.size());
    J.setFromTriplets(red.begin(), red.end());
    Eigen::SparseLU<SparseMatrix> lu(J);
    const VecX dx = lu.solve(-r);
    for (std::size_t k = 0; k < dofs.size(); ++k) x[dofs[k]] += dx[k];
  }
}

// A cantilever strip along the warp, w cells across width W, loaded at its tip
// by a dead line load P (N/m of width) downwards and clamped by holding two
// columns of particles. Such a clamp acts at the middle of the held cell, so
// the cells are laid out to give the free length L from there: n cells of
// h = L/(n + ½) beyond the held cell. Returns the tip deflection / L (mean over
// the tip particles) and the tip's horizontal shortening / L.
struct Tip {
  double w_over_L, u_over_L;
};
Tip cantilever(const OrthotropicMaterial& mat, double L, double W, int n, int w, double P, int load_steps) {
  const double h = L / (n + 0.5);
  const int nu = n + 2, nv = w + 1;
  Model m = make_grid(nu, nv, h, W / w, Vec3(-0.5 * h, 0, 0), Vec3::UnitX(), Vec3::UnitY(), 1e-4);
  for (int i = 0; i < m.num_particles(); ++i) m.uv[i] = at(m.x0, i).head<2>();
  // Newton: the exact Jacobians (quadratic convergence).
  auto rosette = make_strain_rosette(m, {mat}, {.definite_jacobian = false});
  auto bending = make_bending(m, {mat}, {.definite_jacobian = false});
  std::vector<bool> fixed(m.num_particles(), false);
  for (int j = 0; j < nv; ++j) fixed[j * nu] = fixed[j * nu + 1] = true;
  VecX x = m.x0;
  for (int step = 1; step <= load_steps; ++step) {
    VecX f = VecX::Zero(m.num_dofs());
    // P·W over the tip particles, half shares at the corners.
    for (int j = 0; j < nv; ++j) f[3 * (j * nu + nu - 1) + 2] = -P * W / w * ((j == 0 || j == nv - 1) ? 0.5 : 1.0);
    solve_static({rosette.get(), bending.get()}, m, x, fixed, f * (double(step) / load_steps));
  }
  Tip tip{0, 0};
  for (int j = 0; j < nv; ++j) {
    tip.w_over_L -= x[3 * (j * nu + nu - 1) + 2] / L / nv;
    tip.u_over_L += (at(m.x0, j * nu + nu - 1).x() - x[3 * (j * nu + nu - 1)]) / L / nv;
  }
  return tip;
}

}  // namespace

// ---- zero states ----

TEST(Bending, FlatSheetFeelsNoBendingForceInAnyPlacement) {
  const Model m = irregular(6, 5, 0.02, 0.2, 1);
  auto b = make_bending(m, {reference()});
  EXPECT_EQ(forces(*b, m, m.x0).cwiseAbs().maxCoeff(), 0.0);
  // Turned, moved and stretched in its plane: still flat, still no force.
  const Mat3 R = Eigen::AngleAxisd(2.0, Vec3(1, -1, 0.5).normalized()).toRotationMatrix();
  VecX x(m.num_dofs());
  for (int i = 0; i < m.num_particles(); ++i)
    at(x, i) = R * Vec3(1.1 * m.uv[i].x() + 0.05 * m.uv[i].y(), 0.95 * m.uv[i].y(), 0.0) + Vec3(3, 2, 1);
  EXPECT_LT(forces(*b, m, x).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT(energy(*b, m, x), 1e-25);
}

// ---- the curvature rosette ----

TEST(Bending, CurvatureOfAQuadraticSurfaceIsMeasuredExactlyOnAnIrregularMesh) {
  // Away from free edges (which carry no moment, whatever the imposed shape).
  const int n = 8;
  const double d = 0.02;
  const Model m = irregular(n + 1, n + 1, d, 0.25, 2);
  auto b = make_bending(m, {reference()});
  // z = ½ xᵀKx + a tilt, small deflection: K_xx 0.002, K_yy −0.0013, K_xy 0.0007 (1/m).
  const double Kxx = 0.002, Kyy = -0.0013, Kxy = 0.0007;
  VecX x = m.x0;
  for (int i = 0; i < m.num_particles(); ++i) {
    const double u = m.uv[i].x(), v = m.uv[i].y();
    x[3 * i + 2] = 0.5 * (Kxx * u * u + 2 * Kxy * u * v + Kyy * v * v) + 1e-4 * u - 2e-4 * v;
  }
  const auto curv = bending_curvatures(*b, x);
  int inner = 0;
  for (std::size_t t = 0; t < curv.size(); ++t) {
    Vec2 c = Vec2::Zero();
    for (int k : m.triangles[t]) c += m.uv[k] / 3.0;
    if (std::min({c.x(), c.y(), n * d - c.x(), n * d - c.y()}) < 2.0 * d) continue;
    ++inner;
    EXPECT_LT((curv[t].kappa - Vec3(Kxx, Kyy, 2 * Kxy)).norm(), 1e-6 * std::abs(Kxx)) << "triangle " << t;
  }
  EXPECT_GT(inner, 30);
}

TEST(Bending, UniformCurvatureLeavesInnerParticlesWithoutForce) {
  // The patch test: Σ_T A_T κ_T depends on the boundary only, so a uniform
  // moment is carried to the free edges and nowhere else.
  const int n = 8;
  const double d = 0.02;
  const Model m = irregular(n + 1, n + 1, d, 0.25, 3);
  auto b = make_bending(m, {reference()});
  VecX x = m.x0;
  for (int i = 0; i < m.num_particles(); ++i) {
    const double u = m.uv[i].x(), v = m.uv[i].y();
    x[3 * i + 2] = 0.5 * (0.002 * u * u + 2 * 0.0007 * u * v - 0.0013 * v * v);
  }
  const VecX f = forces(*b, m, x);
  const double edge_scale = f.cwiseAbs().maxCoeff();
  for (int j = 3; j <= n - 3; ++j)
    for (int i = 3; i <= n - 3; ++i)
      EXPECT_LT(std::abs(f[3 * (j * (n + 1) + i) + 2]), 1e-6 * edge_scale) << "particle (" << i << ", " << j << ")";
}

TEST(Bending, HingeForcesAreTheSeedsCantileverLoads) {
  // Two triangles folded by an angle about their shared edge: the force at
  // each opposite vertex is M/h along its triangle's normal (seed 002: F_θ =
  // M_θ/L₁ with L₁ the beam from the edge to the vertex), and the edge's
  // reactions cancel force and torque.
  Model m = make_grid(2, 2, 0.03, 0.02, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1e-4);
  auto b = make_bending(m, {reference()});
  ASSERT_EQ(m.triangles[0], (std::array<int, 3>{0, 1, 3}));  // hinge 0–3, opposite vertices 1 and 2
  VecX x = m.x0;
  x[3 * 1 + 2] = 0.004;  // lift vertex 1
  const VecX f = forces(*b, m, x);
  const Vec3 N = (at(x, 1) - at(x, 0)).cross(at(x, 3) - at(x, 0));  // triangle (0, 1, 3)
  const double h = N.norm() / (at(x, 3) - at(x, 0)).norm();
  // M = dU/dθ from the energy, by the change of θ under a small lift of vertex 1.
  const double eps = 1e-7;
  VecX xp = x, xm = x;
  xp[3 * 1 + 2] += eps, xm[3 * 1 + 2] -= eps;
  const double dU = (energy(*b, m, xp) - energy(*b, m, xm)) / (2 * eps);  // = M dθ/dz = M n_z / h
  const double M = dU * h / (N.normalized().z());
  EXPECT_LT((at(f, 1) + M / h * N.normalized()).norm(), 1e-5 * at(f, 1).norm());
  Vec3 sum = Vec3::Zero(), torque = Vec3::Zero();
  for (int i = 0; i < 4; ++i) sum += at(f, i), torque += at(x, i).cross(at(f, i));
  EXPECT_LT(sum.norm(), 1e-14 * f.norm());
  EXPECT_LT(torque.norm(), 1e-14 * f.norm());
}

// ---- plate and beam ----

TEST(Bending, CylinderCarriesMomentBThetaOverRConvergingWithTheMesh) {
  // A 6 cm square sheet on a cylinder of radius 5 cm along θ; the moment per
  // width from dU/dκ against the consistent B_θ/R. Boundary triangles relax
  // (free edges), so the error falls like the share of boundary triangles.
  const OrthotropicMaterial mat = reference();
  const double R = 0.05, side = 0.06;
  for (int deg : {0, 30, 45, 90}) {
    const double th = deg * M_PI / 180.0, expected = bending_rigidity(mat, th) / R;
    double last = 1.0;
    for (int n : {4, 8, 16, 32}) {
      const Model m = make_grid(n + 1, n + 1, side / n, side / n, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1e-4);
      auto b = make_bending(m, {mat});
      const double err = std::abs(cylinder_moment(*b, m, 1.0 / R, th) / expected - 1.0);
      RecordProperty("cylinder_" + std::to_string(deg) + "deg_n" + std::to_string(n) + "_rel_error", sci(err));
      EXPECT_LT(err, last) << deg << "°, " << n << " cells: the error must fall with refinement";
      last = err;
    }
    EXPECT_LT(last, 0.06) << deg << "° at 32 × 32 cells";
  }
}

TEST(Bending, InteriorOfACylinderMeasuresItsCurvature) {
  // Away from free edges the gauges read the cylinder's curvature to O(h²).
  const OrthotropicMaterial mat = reference();
  const double R = 0.05, th = 30 * M_PI / 180.0;
  const Vec3 exact(std::pow(std::cos(th), 2) / R, std::pow(std::sin(th), 2) / R, 2 * std::cos(th) * std::sin(th) / R);
  double last = 1.0;
  for (int n : {6, 12, 24}) {
    const Model m = irregular(n + 1, n + 1, 0.06 / n, 0.15, 3);
    auto b = make_bending(m, {mat});
    double worst = 0.0;
    const auto curv = bending_curvatures(*b, cylinder(m, 1.0 / R, th));
    for (std::size_t t = 0; t < curv.size(); ++t) {
      // Two cells or more from the free edges, where no moment may cross.
      Vec2 c = Vec2::Zero();
      for (int k : m.triangles[t]) c += m.uv[k] / 3.0;
      if (std::min({c.x(), c.y(), 0.06 - c.x(), 0.06 - c.y()}) < 2.0 * 0.06 / n) continue;
      worst = std::max(worst, (curv[t].kappa - exact).norm() / exact.norm());
    }
    EXPECT_LT(worst, last) << n;
    last = worst;
  }
  EXPECT_LT(last, 0.01);
}

TEST(Bending, CantileverTipDeflectionConvergesToBeamTheory) {
  // Small load (k = PL²/B = 0.01): w = PL³/(3B) to 4e-5 (mechanics.md §5).
  // ν = 0 so that the strip's and the plate's rigidity agree. Second order in h.
  OrthotropicMaterial mat = reference();
  mat.nu_warp_weft = 0.0;
  const double L = 0.1, W = 0.02, k = 0.01, P = k * mat.B_warp / (L * L);
  double last = 1.0;
  for (int n : {5, 10, 20}) {
    const Tip tip = cantilever(mat, L, W, n, 2, P, 1);
    const double err = std::abs(tip.w_over_L / (k / 3.0) - 1.0);
    RecordProperty("cantilever_n" + std::to_string(n) + "_rel_error", sci(err));
    EXPECT_LT(err, 0.35 * last) << n << " cells: the error must fall like h²";
    last = err;
  }
  EXPECT_LT(last, 0.002);
}

TEST(Bending, LargeDeflectionCantileverFollowsTheElastica) {
  // k = 1 (../shared/reference/cantilever_tip_load.csv: w/L = 0.30172077,
  // u/L = 0.05643324), 20 cells: within 2 %.
  OrthotropicMaterial mat = reference();
  mat.nu_warp_weft = 0.0;
  const double L = 0.1, W = 0.02, P = 1.0 * mat.B_warp / (L * L);
  const Tip tip = cantilever(mat, L, W, 20, 2, P, 4);
  RecordProperty("elastica_k1_w_rel_error", sci(tip.w_over_L / 0.30172077 - 1.0));
  EXPECT_NEAR(tip.w_over_L / 0.30172077, 1.0, 0.02);
  EXPECT_NEAR(tip.u_over_L / 0.05643324, 1.0, 0.04);
}

// ---- energy, Jacobian, momentum, invariance ----

TEST(Bending, ForceIsMinusEnergyGradientAndJacobianMatchesFiniteDifferences) {
  const Model m = irregular(4, 4, 0.03, 0.2, 4);
  auto b = make_bending(m, {reference()}, {.definite_jacobian = false});  // the exact one
  const VecX x = crumpled(m, 0.003, 5);
  const VecX f = forces(*b, m, x);
  Triplets jx, jv;
  ASSERT_TRUE(b->add_jacobian({m, 0.0, x, m.v0}, jx, jv));
  SparseMatrix Js(m.num_dofs(), m.num_dofs());
  Js.setFromTriplets(jx.begin(), jx.end());
  const Eigen::MatrixXd J(Js);
  const double h = 1e-7;
  VecX grad(m.num_dofs());
  Eigen::MatrixXd Jfd(m.num_dofs(), m.num_dofs());
  for (int k = 0; k < m.num_dofs(); ++k) {
    VecX xp = x, xm = x;
    xp[k] += h, xm[k] -= h;
    grad[k] = (energy(*b, m, xp) - energy(*b, m, xm)) / (2 * h);
    Jfd.col(k) = (forces(*b, m, xp) - forces(*b, m, xm)) / (2 * h);
  }
  EXPECT_LT((f + grad).norm(), 1e-6 * f.norm());
  EXPECT_LT((J - Jfd).norm(), 1e-6 * J.norm());
  EXPECT_LT((J - J.transpose()).norm(), 1e-12 * J.norm());
}

TEST(Bending, ForcesKeepMomentumAndTurnWithTheCloth) {
  const Model m = irregular(6, 5, 0.02, 0.2, 6);
  auto b = make_bending(m, {reference()});
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const VecX x = crumpled(m, 0.002, seed);
    const VecX f = forces(*b, m, x);
    Vec3 sum = Vec3::Zero(), torque = Vec3::Zero();
    double scale = 0.0;
    for (int i = 0; i < m.num_particles(); ++i) {
      sum += at(f, i), torque += at(x, i).cross(at(f, i));
      scale += at(f, i).norm() * (1.0 + at(x, i).norm());
    }
    EXPECT_LT(sum.norm(), 1e-13 * scale);
    EXPECT_LT(torque.norm(), 1e-13 * scale);
    const Mat3 R = Eigen::AngleAxisd(0.9, Vec3(2, 1, -1).normalized()).toRotationMatrix();
    VecX xr = x;
    for (int i = 0; i < m.num_particles(); ++i) at(xr, i) = R * at(x, i) + Vec3(-1, 4, 2);
    const VecX fr = forces(*b, m, xr);
    for (int i = 0; i < m.num_particles(); ++i) EXPECT_LT((at(fr, i) - R * at(f, i)).norm(), 1e-10 * f.norm());
    EXPECT_NEAR(energy(*b, m, xr), energy(*b, m, x), 1e-12 * energy(*b, m, x));
  }
}

// ---- threads, bounds, refusals ----

TEST(Bending, ThreadedForcesEqualSerialBitForBit) {
  const Model m = irregular(30, 30, 0.02, 0.2, 7);
  auto b = make_bending(m, {reference()}, {.parallel_min_hinges = 0});
  const VecX x = crumpled(m, 0.003, 8);
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  const VecX serial = forces(*b, m, x);
  EXPECT_EQ(forces(*b, m, x), serial);
  omp_set_num_threads(2);
  const VecX threaded = forces(*b, m, x);
  omp_set_num_threads(before);
  EXPECT_EQ(threaded, serial);
}

TEST(Bending, StiffnessBoundCoversTheLargestEigenvalue) {
  Model m = irregular(6, 5, 0.02, 0.2, 9);
  m.mass = lump_masses(m.uv, m.triangles, 0.2);
  auto b = make_bending(m, {reference()});
  VecX k = VecX::Zero(m.num_particles()), c = VecX::Zero(m.num_particles());
  b->add_stiffness_bound(m, k, c);
  double bound = 0.0;
  for (int i = 0; i < m.num_particles(); ++i) bound = std::max(bound, k[i] / m.mass[i]);
  Triplets jx, jv;
  b->add_jacobian({m, 0.0, m.x0, m.v0}, jx, jv);
  SparseMatrix Js(m.num_dofs(), m.num_dofs());
  Js.setFromTriplets(jx.begin(), jx.end());
  VecX s(m.num_dofs());
  for (int i = 0; i < m.num_particles(); ++i) at(s, i).setConstant(1.0 / std::sqrt(m.mass[i]));
  const Eigen::MatrixXd A = -(s.asDiagonal() * Eigen::MatrixXd(Js) * s.asDiagonal());
  const double lmax = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues().maxCoeff();
  EXPECT_LE(lmax, bound * (1 + 1e-12));
  EXPECT_GT(lmax, 0.1 * bound);
}

TEST(Bending, OverlappingTrianglesAreRefused) {
  Model m = make_grid(2, 2, 0.1, 0.1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1e-3);
  m.uv[2] = Vec2(0.2, 0.05);  // vertex 2 pulled across the diagonal 0–3
  EXPECT_THROW(make_bending(m, {reference()}), SimulationError);
}

// ---- in a simulation ----

TEST(Bending, FlagWithRosetteAndBendingRunsStablyAtTheComputedStepLimit) {
  // A 15 × 15 flag hanging from two corners; symplectic Euler at 0.9 × the
  // limit from the Gershgorin bounds of both effects, no damping: the total
  // energy may only wander by the integrator's bounded shadow-energy error
  // (here ~1e-5 of the potential energy).
  Model m = make_grid(15, 15, 0.02, 0.02, Vec3(0, 0.28, 0), Vec3::UnitX(), -Vec3::UnitY(), 1.0);
  m.mass = lump_masses(m.uv, m.triangles, 0.2);
  for (int i = 0; i < m.num_particles(); ++i) m.x0[3 * i + 2] = 0.002 * std::sin(9.0 * m.uv[i].x());  // a ripple
  std::vector<std::unique_ptr<Effect>> fx;
  fx.push_back(make_gravity({}));
  fx.push_back(make_pins(m, {{0, 14}}));
  // Serial: this test is about stability, and threads on a busy machine only slow it.
  fx.push_back(make_strain_rosette(m, {reference()}, {.parallel_min_triangles = 1 << 30}));
  fx.push_back(make_bending(m, {reference()}, {.parallel_min_hinges = 1 << 30}));
  System sys(m, std::move(fx));
  IntegratorSettings st;
  st.method = Method::symplectic_euler;
  st.step = 0.9 * stability_limit(st.method, sys.stiffness());
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  const double e0 = sys.kinetic_energy(s.v) + sys.potential_energy(s.t, s.x, s.v);
  double kinetic = 0.0;
  for (int k = 1; k <= 20; ++k) {
    ASSERT_NO_THROW(integ->advance(sys, s, k * 0.005));
    const double e = sys.kinetic_energy(s.v) + sys.potential_energy(s.t, s.x, s.v);
    kinetic = std::max(kinetic, sys.kinetic_energy(s.v));
    EXPECT_LT(std::abs(e - e0), 1e-3 * std::abs(e0)) << "t = " << s.t;
  }
  EXPECT_GT(kinetic, 1e-7);  // it did move (the ripple and the sag)
}
