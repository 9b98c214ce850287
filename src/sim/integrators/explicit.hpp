#pragma once
#include "fixed_step.hpp"

namespace vgd::sim::detail {

class SymplecticEuler final : public FixedStepIntegrator {
 public:
  using FixedStepIntegrator::FixedStepIntegrator;

 private:
  void do_step(System& sys, State& s, double h) override;
  VecX a_;
};

class Midpoint final : public FixedStepIntegrator {
 public:
  using FixedStepIntegrator::FixedStepIntegrator;

 private:
  void do_step(System& sys, State& s, double h) override;
  VecX a_, xm_, vm_;
};

class RungeKutta4 final : public FixedStepIntegrator {
 public:
  using FixedStepIntegrator::FixedStepIntegrator;

 private:
  void do_step(System& sys, State& s, double h) override;
  VecX a1_, a2_, a3_, a4_, x2_, x3_, x4_, v2_, v3_, v4_;
};

}  // namespace vgd::sim::detail
