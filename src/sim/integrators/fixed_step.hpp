#pragma once
// Shared frame of the fixed-step methods: equal steps no longer than the
// requested one up to each frame time, prescribed motion, after-step hooks and
// a state check after every step.
#include "vgd/sim/integrator.hpp"

namespace vgd::sim::detail {

class FixedStepIntegrator : public Integrator {
 public:
  explicit FixedStepIntegrator(const IntegratorSettings& s) : settings_(s), h_(s.step) {}
  Method method() const override { return settings_.method; }
  void prepare(System& sys, const State& s) override;
  void advance(System& sys, State& s, double t_end) override;
  IntegratorStats stats() const override { return stats_; }
  double step() const override { return h_; }

 protected:
  // One step of size h from s.t; must not change s.t.
  virtual void do_step(System& sys, State& s, double h) = 0;
  IntegratorSettings settings_;
  double h_;
  IntegratorStats stats_;
};

}  // namespace vgd::sim::detail
