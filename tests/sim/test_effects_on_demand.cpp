// Effects on demand: the System holds exactly the effects it was
// given, evaluates only those, and an effect that has finished its work (a
// seam after its last merge) leaves the step — its call counts stop growing
// while the others' keep growing.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/seam.hpp"
#include "vgd/sim/run.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

std::vector<std::string> names(const System& sys) {
  std::vector<std::string> out;
  for (const auto& p : sys.profile()) out.push_back(p.name);
  return out;
}

const EffectProfile& entry(const System& sys, const std::string& name) {
  const auto& prof = sys.profile();
  const auto it = std::find_if(prof.begin(), prof.end(), [&](const EffectProfile& p) { return p.name == name; });
  EXPECT_NE(it, prof.end()) << "no effect " << name;
  return *it;
}

// An effect that has done its work after `steps` after-step calls.
class Countdown final : public Effect {
 public:
  explicit Countdown(int steps) : left_(steps) {}
  int force_calls = 0;
  const char* name() const override { return "countdown"; }
  void add_forces(const Eval&, VecX&) override { ++force_calls; }
  void after_step(const Model&, State&) override { --left_; }
  bool finished() const override { return left_ <= 0; }

 private:
  int left_;
};

}  // namespace

TEST(EffectsOnDemand, OnlyTheGivenEffectsAreListedAndEvaluated) {
  const Model m = make_grid(6, 5, 0.1, 0.1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 0.01);
  // Without wind: the profile names exactly mass-spring and gravity.
  System still(m, effects(make_mass_spring(m, {soft_cloth()}), make_gravity({})));
  auto integ = make_integrator({});
  State s = initial_state(m);
  ASSERT_TRUE(run(still, *integ, s, {30.0, 0.2}, {}).ok);
  EXPECT_EQ(names(still), (std::vector<std::string>{"mass-spring", "gravity"}));
  EXPECT_EQ(still.effects().size(), 2u);
  // Every listed effect is evaluated once per force evaluation of the system.
  for (const auto& p : still.profile()) EXPECT_EQ(p.force_calls, still.force_evaluations()) << p.name;

  // With wind: a third entry, evaluated as often as the others.
  WindDef wind;
  wind.velocity = Vec3(0, 0, 5);
  System windy(m, effects(make_mass_spring(m, {soft_cloth()}), make_gravity({}), make_wind(wind)));
  s = initial_state(m);
  ASSERT_TRUE(run(windy, *integ, s, {30.0, 0.2}, {}).ok);
  EXPECT_EQ(names(windy), (std::vector<std::string>{"mass-spring", "gravity", "wind"}));
  EXPECT_EQ(entry(windy, "wind").force_calls, windy.force_evaluations());
}

TEST(EffectsOnDemand, AFinishedEffectIsNoLongerEvaluated) {
  const Model m = particles(3);
  auto countdown = std::make_unique<Countdown>(5);
  Countdown* c = countdown.get();
  System sys(m, effects(make_gravity({}), std::move(countdown)));
  IntegratorSettings st;
  st.step = 0.01;
  auto integ = make_integrator(st);
  State s = initial_state(m);
  integ->prepare(sys, s);
  integ->advance(sys, s, 0.2);  // 20 steps: the countdown finishes after the 5th
  EXPECT_EQ(c->force_calls, 5);
  EXPECT_EQ(entry(sys, "countdown").after_step_calls, 5);
  EXPECT_EQ(entry(sys, "gravity").force_calls, 20);
}

TEST(EffectsOnDemand, ASeamStopsCostingTimeAfterItsLastMerge) {
  const int nu = 3, nv = 4;
  const Model m = two_grids(nu, nv, 0.05);
  SeamDef def;
  def.law = SeamLaw::linear;
  def.stiffness = 1.0;
  def.damping = 0.25;
  SeamPairs side{"side", {}};
  for (int j = 0; j < nv; ++j) side.pairs.push_back({j * nu + nu - 1, nu * nv + j * nu});
  def.seams = {side};
  System sys(m, effects(make_mass_spring(m, {soft_cloth()}), make_seam(m, def)));
  IntegratorSettings st;
  st.step = 0.002;
  auto integ = make_integrator(st);
  State s = initial_state(m);
  // Sew: after 2 s every pair has merged (test_seam.cpp, SeamRun).
  ASSERT_TRUE(run(sys, *integ, s, {30.0, 2.0}, {}).ok);
  ASSERT_EQ(sys.num_particles(), 2 * nu * nv - nv);
  ASSERT_TRUE(sys.effects()[1]->finished());
  const EffectProfile seam_then = entry(sys, "seam");
  const long cloth_then = entry(sys, "mass-spring").force_calls;
  EXPECT_GT(seam_then.force_calls, 0);
  // Half a second more: the cloth keeps being evaluated, the seam not at all.
  ASSERT_TRUE(run(sys, *integ, s, {30.0, 0.5}, {}).ok);
  const EffectProfile& seam_now = entry(sys, "seam");
  EXPECT_EQ(seam_now.force_calls, seam_then.force_calls);
  EXPECT_EQ(seam_now.after_step_calls, seam_then.after_step_calls);
  EXPECT_EQ(seam_now.seconds, seam_then.seconds);
  EXPECT_GE(entry(sys, "mass-spring").force_calls, cloth_then + 250);  // 0.5 s in 2 ms steps
  EXPECT_TRUE(sys.may_rest());
}
