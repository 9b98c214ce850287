// The environment's effects against the laws they state.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/integrator.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {
// A flat square plate of side 1 m in the z = 0 plane, normal +z.
Model plate() { return make_grid(2, 2, 1.0, 1.0, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 0.1); }

Vec3 total(const VecX& f) {
  Vec3 s = Vec3::Zero();
  for (int i = 0; i < f.size() / 3; ++i) s += at(f, i);
  return s;
}

}  // namespace

TEST(Gravity, ForceIsMassTimesG) {
  Model m = particles(2, 3.0);
  auto g = make_gravity({Vec3(0, -9.81, 0)});
  EXPECT_NEAR(total(forces(*g, m, m.x0, m.v0)).y(), -2 * 3.0 * 9.81, 1e-12);
}

TEST(Viscosity, TerminalVelocityIsMgOverK) {
  Model m = particles(1, 0.1);
  System sys(m, effects(make_gravity({}), make_viscosity({0.2, 0.0})));
  IntegratorSettings st;
  st.method = Method::rk4;
  st.step = 0.01;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->advance(sys, s, 10.0);  // 20 time constants m/k = 0.5 s
  EXPECT_NEAR(s.v[1], -0.1 * 9.81 / 0.2, 1e-6);
}

TEST(Wind, PlateFacingTheWindFeelsCAwnAndEdgeOnFeelsNothing) {
  const Model m = plate();
  auto w = make_wind({Vec3(0, 0, 10.0), 0.5});
  const Vec3 f = total(forces(*w, m, m.x0, m.v0));
  EXPECT_NEAR(f.z(), 0.5 * 1.0 * 10.0, 1e-12);  // c A (w·n)
  EXPECT_NEAR(f.head<2>().norm(), 0.0, 1e-12);
  auto edge_on = make_wind({Vec3(10.0, 0, 0), 0.5});
  EXPECT_NEAR(total(forces(*edge_on, m, m.x0, m.v0)).norm(), 0.0, 1e-12);
}

TEST(Wind, PlateMovingWithTheWindFeelsNothing) {
  const Model m = plate();
  auto w = make_wind({Vec3(0, 0, 3.0), 1.0});
  VecX v = m.v0;
  for (int i = 0; i < m.num_particles(); ++i) at(v, i) = Vec3(0, 0, 3.0);
  EXPECT_NEAR(total(forces(*w, m, m.x0, v)).norm(), 0.0, 1e-12);
}

TEST(Wind, TurbulenceIsDeterministicAndAveragesToTheMeanWind) {
  WindDef d{Vec3(5, 0, 0), 1.0, 0.3, 1.0, 7};
  EXPECT_EQ(wind_at(d, 1.234, Vec3(1, 2, 3)), wind_at(d, 1.234, Vec3(1, 2, 3)));
  WindDef other = d;
  other.seed = 8;
  EXPECT_NE(wind_at(d, 1.234, Vec3::Zero()), wind_at(other, 1.234, Vec3::Zero()));
  Vec3 mean = Vec3::Zero();
  double max_dev = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const Vec3 w = wind_at(d, k * 0.01, Vec3::Zero());
    mean += w / n;
    max_dev = std::max(max_dev, (w - d.velocity).norm());
  }
  EXPECT_NEAR((mean - d.velocity).norm(), 0.0, 0.1);
  EXPECT_GT(max_dev, 0.5);           // it does gust
  EXPECT_LE(max_dev, 0.3 * 5 * std::sqrt(3.0) + 1e-9);  // within the stated amplitude
}

TEST(Damping, RigidMotionIsNotDamped) {
  const Model m = plate();
  auto d = make_damping(m, {2.0});
  VecX v = VecX::Zero(m.num_dofs());
  for (int i = 0; i < m.num_particles(); ++i) at(v, i) = Vec3(1, 2, 3) + Vec3(0, 0, 1).cross(at(m.x0, i));
  EXPECT_LT(forces(*d, m, m.x0, v).norm(), 1e-12);
}

TEST(Damping, StretchingIsDampedAndMomentumKept) {
  const Model m = plate();
  auto d = make_damping(m, {2.0});
  VecX v = VecX::Zero(m.num_dofs());
  at(v, 3) = Vec3(1.0, 1.0, 0.0);  // one corner flies off diagonally
  const VecX f = forces(*d, m, m.x0, v);
  EXPECT_LT(at(f, 3).dot(at(v, 3)), 0.0);
  EXPECT_LT(total(f).norm(), 1e-12);  // internal forces
}

TEST(Jacobians, ViscosityAndDampingMatchFiniteDifferencesInVelocity) {
  Model m = plate();
  VecX x = m.x0;
  x[2] = 0.1;  // out of plane, so edge directions are general
  VecX v = VecX::Random(m.num_dofs());
  for (auto* e : {make_viscosity({0.3, 0.7}).release(), make_damping(m, {1.5}).release()}) {
    std::unique_ptr<Effect> eff(e);
    Triplets jx, jv;
    eff->add_jacobian({m, 0.0, x, v}, jx, jv);
    SparseMatrix J(m.num_dofs(), m.num_dofs());
    J.setFromTriplets(jv.begin(), jv.end());
    const double h = 1e-6;
    for (int c = 0; c < m.num_dofs(); ++c) {
      VecX vp = v, vm = v;
      vp[c] += h, vm[c] -= h;
      const VecX col = (forces(*eff, m, x, vp) - forces(*eff, m, x, vm)) / (2 * h);
      EXPECT_LT((col - VecX(J.col(c))).norm(), 1e-6) << eff->name() << " column " << c;
    }
  }
}

TEST(Wind, GustsOnTheClothMatchTheWindFieldAtTheFaces) {
  // A single face: the force must equal c A ((w(t, centre) - v)·n) n with the
  // documented wind field evaluated at the face's rest centroid.
  const Model m = make_grid(2, 2, 1.0, 1.0, Vec3(0.3, -0.2, 0.0), Vec3::UnitX(), Vec3::UnitY(), 0.1);
  Model one = m;
  one.triangles.resize(1);
  const WindDef d{Vec3(2.0, 0.0, 6.0), 0.7, 0.4, 1.5, 3};
  auto w = make_wind(d);
  const auto& t = one.triangles[0];
  const Vec3 centre = (at(one.x0, t[0]) + at(one.x0, t[1]) + at(one.x0, t[2])) / 3.0;
  // The field is sampled along the wind and interpolated: within 0.125 % of the
  // gust amplitude (0.4 x |w|) of the exact field.
  const double tol = 0.7 * 0.5 * 0.00125 * 0.4 * d.velocity.norm() * std::sqrt(3.0);
  for (double time : {0.0, 0.37, 1.9}) {
    const Vec3 f = total(forces(*w, one, one.x0, one.v0, time));
    const Vec3 expected = Vec3(0, 0, 0.7 * 0.5 * wind_at(d, time, centre).z());
    EXPECT_LE((f - expected).norm(), tol) << "t = " << time;
  }
  // On a wide cloth the faces far apart along the wind feel different gusts.
  const Model wide = make_grid(3, 2, 40.0, 1.0, Vec3::Zero(), Vec3(0.3, 0, 0.95), Vec3::UnitY(), 0.1);
  VecX fw = forces(*make_wind(d), wide, wide.x0, wide.v0, 0.5);
  EXPECT_GT((at(fw, 0) - at(fw, 2)).norm(), 1e-3);
}

// The speed limit clamps the velocity to max_speed and the step's
// displacement to max_speed × h, along the motion; slower particles are
// untouched; after a merge the next step starts from the merged position.
TEST(SpeedLimit, ClampsVelocityAndDisplacementAlongTheMotion) {
  Model m = particles(2, 0.001);
  auto e = make_speed_limit(m, {1.0});
  State s = initial_state(m);
  e->after_step(m, s);  // first call: remembers the positions
  const Vec3 x0 = at(s.x, 0), x1 = at(s.x, 1);
  s.t = 0.01;
  at(s.v, 0) = Vec3(30, 40, 0);          // 50 m/s
  at(s.x, 0) = x0 + Vec3(0.3, 0.4, 0);   // 0.5 m in 10 ms
  at(s.v, 1) = Vec3(0, 0.5, 0);          // under the limit
  at(s.x, 1) = x1 + Vec3(0, 0.005, 0);
  e->after_step(m, s);
  EXPECT_NEAR(at(s.v, 0).norm(), 1.0, 1e-12);
  EXPECT_NEAR(at(s.v, 0).normalized().dot(Vec3(0.6, 0.8, 0)), 1.0, 1e-12);
  EXPECT_NEAR((at(s.x, 0) - x0).norm(), 0.01, 1e-12);  // 1 m/s × 10 ms
  EXPECT_NEAR((at(s.x, 0) - x0).normalized().dot(Vec3(0.6, 0.8, 0)), 1.0, 1e-12);
  EXPECT_EQ(at(s.v, 1), Vec3(0, 0.5, 0));
  EXPECT_EQ(at(s.x, 1), x1 + Vec3(0, 0.005, 0));
  // Particles 0 and 1 merge: both jump to their mass-weighted mean, 0.25 m
  // for particle 0. The next step starts there: the jump is not pulled back,
  // and a step from there is still limited.
  e->particles_merged(m, {0, 0});
  const Vec3 mid = (m.mass[0] * at(s.x, 0) + m.mass[1] * at(s.x, 1)) / (m.mass[0] + m.mass[1]);
  at(s.x, 0) = at(s.x, 1) = mid;
  s.t = 0.02;
  e->after_step(m, s);
  EXPECT_LT((at(s.x, 0) - mid).norm(), 1e-12);
  at(s.x, 0) = at(s.x, 1) = mid + Vec3(0.1, 0, 0);
  s.t = 0.03;
  e->after_step(m, s);
  EXPECT_NEAR((at(s.x, 0) - mid).norm(), 0.01, 1e-12);
  EXPECT_THROW(make_speed_limit(m, {0.0}), SimulationError);
}
