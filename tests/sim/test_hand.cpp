// The hand (sim/effects/hand.hpp): a particle pulled towards a point the user
// moves, and pins holding particles where they were pinned.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/sim/effects/basic.hpp"
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
  auto hand = make_hand({.stiffness = 5.0, .damping = 0.03, .control = control});
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
  EXPECT_THROW(make_hand({.stiffness = 5.0, .damping = 0.03, .control = nullptr}), vgd::Error);
}

// A free 40 mg particle held critically damped (c = 2 sqrt(k m)) comes to
// the point under implicit Euler (10 ms steps) within 10 time constants
// sqrt(m/k), and follows it when it moves.
TEST(Hand, AHeldParticleComesToThePointAndFollowsIt) {
  Model m = particles(1, 4e-5);
  const double k = 5.0, c = 2 * std::sqrt(k * 4e-5);
  auto control = std::make_shared<HandControl>();
  System sys(m, effects(make_hand({.stiffness = k, .damping = c, .control = control})));
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

// Pins: each pinned particle gets k_pin (a - x) - c_pin v towards where it was
// pinned, the held one the hand's spring besides; Jacobian blocks -k I, -c I
// for each; the energy their sum. Pinned again, a particle takes its new
// place; unpinned, it is free. Pins do not keep the run from resting; the
// explicit stability bound counts both springs on every particle.
TEST(Hand, PinsHoldTheirParticlesBesideTheGrip) {
  Model m = particles(3, 0.04);
  auto control = std::make_shared<HandControl>();
  const HandDef def{.stiffness = 5.0, .damping = 0.03, .pin_stiffness = 150.0, .pin_damping = 0.2, .control = control};
  auto hand = make_hand(def);
  VecX v = VecX::Zero(m.num_dofs());
  at(v, 0) = Vec3(0, 0.1, 0);
  const Vec3 d0(0.01, 0, -0.02), d2(0, 0.003, 0), g(0.1, 0, 0);
  control->pin({{0, at(m.x0, 0) + d0}, {2, at(m.x0, 2) + 2 * d2}});
  control->pin({{2, at(m.x0, 2) + d2}});  // pinned again: the new place
  EXPECT_EQ(control->pin_count(), 2u);
  EXPECT_FALSE(hand->blocks_rest()) << "pins alone do not keep it from resting";
  control->grab(1, at(m.x0, 1) + g);
  const VecX f = forces(*hand, m, m.x0, v);
  EXPECT_LT((at(f, 0) - (150.0 * d0 - 0.2 * Vec3(0, 0.1, 0))).norm(), 1e-12);
  EXPECT_LT((at(f, 1) - 5.0 * g).norm(), 1e-12);
  EXPECT_LT((at(f, 2) - 150.0 * d2).norm(), 1e-12);
  Triplets dx, dv;
  ASSERT_TRUE(hand->add_jacobian({m, 0.0, m.x0, v}, dx, dv));
  SparseMatrix kx(m.num_dofs(), m.num_dofs()), kv(m.num_dofs(), m.num_dofs());
  kx.setFromTriplets(dx.begin(), dx.end());
  kv.setFromTriplets(dv.begin(), dv.end());
  EXPECT_DOUBLE_EQ(kx.coeff(0, 0), -150.0);
  EXPECT_DOUBLE_EQ(kx.coeff(4, 4), -5.0);
  EXPECT_DOUBLE_EQ(kv.coeff(8, 8), -0.2);
  EXPECT_EQ(kx.nonZeros(), 9);
  EXPECT_NEAR(hand->energy({m, 0.0, m.x0, v}), 0.5 * 150.0 * (d0.squaredNorm() + d2.squaredNorm()) + 0.5 * 5.0 * g.squaredNorm(), 1e-15);
  VecX kb = VecX::Zero(3), cb = VecX::Zero(3);
  hand->add_stiffness_bound(m, kb, cb);
  EXPECT_DOUBLE_EQ(kb[1], 155.0);
  EXPECT_DOUBLE_EQ(cb[2], 0.23);
  control->unpin({0});
  EXPECT_EQ(at(forces(*hand, m, m.x0, v), 0).norm(), 0.0) << "unpinned";
  control->release();
  control->unpin_all();
  EXPECT_EQ(forces(*hand, m, m.x0, v).norm(), 0.0);
  EXPECT_THROW(make_hand({.pin_stiffness = 0.0, .control = control}), vgd::Error);
}

// A 50 g particle pinned where it starts, under gravity, implicit Euler at
// 10 ms: it comes to rest m g / k_pin below the pin (0.49 mm at the default
// 1000 N/m), the static balance, to 1 %.
TEST(Hand, APinnedParticleHangsItsWeightBelowThePin) {
  Model m = particles(1, 0.05);
  auto control = std::make_shared<HandControl>();
  std::vector<std::unique_ptr<Effect>> list;
  list.push_back(make_gravity({}));
  const HandDef def{.control = control};
  list.push_back(make_hand(def));
  System sys(m, std::move(list));
  IntegratorSettings st;
  st.method = Method::implicit_euler;
  st.step = 0.01;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  const Vec3 start = at(s.x, 0);
  control->pin({{0, start}});
  integ->advance(sys, s, 5.0);
  const double sag = 0.05 * 9.81 / def.pin_stiffness;
  EXPECT_NEAR((start - at(s.x, 0)).y(), sag, 0.01 * sag);
  EXPECT_NEAR(std::hypot(at(s.x, 0).x() - start.x(), at(s.x, 0).z() - start.z()), 0.0, 1e-9);
  EXPECT_LT(at(s.v, 0).norm(), 1e-4);
}
