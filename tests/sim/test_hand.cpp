// The hand (sim/effects/hand.hpp): a particle pulled towards a point the user moves.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/sim/effects/hand.hpp"
#include "vgd/sim/integrator.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

// The force is k (p - x) - c v on the held particle and nothing elsewhere;
// its Jacobian blocks are -k I and -c I; its energy is k |p - x|² / 2;
// released, or holding a particle the model does not have, it does nothing.
TEST(Hand, PullsTheHeldParticleOnlyWithAZeroLengthSpring) {
  Model m = particles(3, 0.04);
  auto control = std::make_shared<HandControl>();
  auto hand = make_hand({5.0, 0.03, control});
  VecX v = VecX::Zero(m.num_dofs());
  at(v, 1) = Vec3(0.5, 0, 0);
  EXPECT_EQ(forces(*hand, m, m.x0, v).norm(), 0.0) << "nothing held";
  EXPECT_FALSE(hand->blocks_rest());
  const Vec3 p = at(m.x0, 1) + Vec3(0.1, -0.2, 0.05);
  control->grab(1, p);
  const VecX f = forces(*hand, m, m.x0, v);
  EXPECT_LT((at(f, 1) - (5.0 * Vec3(0.1, -0.2, 0.05) - 0.03 * Vec3(0.5, 0, 0))).norm(), 1e-12);
  EXPECT_EQ(at(f, 0).norm() + at(f, 2).norm(), 0.0);
  EXPECT_TRUE(hand->blocks_rest());
  Triplets dx, dv;
  ASSERT_TRUE(hand->add_jacobian({m, 0.0, m.x0, v}, dx, dv));
  SparseMatrix kx(m.num_dofs(), m.num_dofs()), kv(m.num_dofs(), m.num_dofs());
  kx.setFromTriplets(dx.begin(), dx.end());
  kv.setFromTriplets(dv.begin(), dv.end());
  EXPECT_DOUBLE_EQ(kx.coeff(3, 3), -5.0);
  EXPECT_DOUBLE_EQ(kv.coeff(5, 5), -0.03);
  EXPECT_EQ(kx.nonZeros(), 3);
  EXPECT_NEAR(hand->energy({m, 0.0, m.x0, v}), 0.5 * 5.0 * (0.01 + 0.04 + 0.0025), 1e-12);
  control->grab(7, p);
  EXPECT_EQ(forces(*hand, m, m.x0, v).norm(), 0.0) << "a particle the model does not have";
  control->release();
  EXPECT_FALSE(hand->blocks_rest());
  EXPECT_THROW(make_hand({5.0, 0.03, nullptr}), vgd::Error);
}

// A free 40 mg particle held critically damped (c = 2 sqrt(k m)) comes to
// the point under implicit Euler (10 ms steps) within 10 time constants
// sqrt(m/k), and follows it when it moves.
TEST(Hand, AHeldParticleComesToThePointAndFollowsIt) {
  Model m = particles(1, 4e-5);
  const double k = 5.0, c = 2 * std::sqrt(k * 4e-5);
  auto control = std::make_shared<HandControl>();
  System sys(m, effects(make_hand({k, c, control})));
  IntegratorSettings st;
  st.method = Method::implicit_euler;
  st.step = 0.01;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  const Vec3 start = at(s.x, 0);
  control->grab(0, start + Vec3(0.1, 0, 0));
  integ->advance(sys, s, 0.5);  // to t = 0.5 s: 175 time constants of 2.8 ms
  EXPECT_LT((at(s.x, 0) - (start + Vec3(0.1, 0, 0))).norm(), 1e-4);
  control->move(start + Vec3(0.1, 0.1, 0));
  integ->advance(sys, s, 1.0);
  EXPECT_LT((at(s.x, 0) - (start + Vec3(0.1, 0.1, 0))).norm(), 1e-4);
  control->release();
  const Vec3 left = at(s.x, 0);
  integ->advance(sys, s, 1.5);
  EXPECT_LT((at(s.x, 0) - left).norm(), 1e-3) << "released: it stays about where it was (no gravity here)";
}
