// The seed's explicit methods (seed 000 §4.1.4) on the first-order system
// y = (x, v), y' = (v, M⁻¹ f(x, v)).
#include "explicit.hpp"

namespace vgd::sim::detail {

// Semi-implicit (symplectic) Euler, as the seed implements "Euler": the new
// velocity moves the particle. Order 1; preserves a shadow energy.
void SymplecticEuler::do_step(System& sys, State& s, double h) {
  a_.resize(s.x.size());
  sys.acceleration(s.t, s.x, s.v, a_);
  ++stats_.rhs_evaluations;
  s.v += h * a_;
  s.x += h * s.v;
}

// Midpoint: y(t+h) = y + h f(t + h/2, y + h/2 f(t, y)). Order 2.
void Midpoint::do_step(System& sys, State& s, double h) {
  a_.resize(s.x.size());
  sys.acceleration(s.t, s.x, s.v, a_);
  xm_ = s.x + 0.5 * h * s.v;
  vm_ = s.v + 0.5 * h * a_;
  sys.acceleration(s.t + 0.5 * h, xm_, vm_, a_);
  stats_.rhs_evaluations += 2;
  s.x += h * vm_;
  s.v += h * a_;
}

// Classical fourth-order Runge–Kutta (seed 000's k1..k4). Order 4.
void RungeKutta4::do_step(System& sys, State& s, double h) {
  const auto n = s.x.size();
  a1_.resize(n), a2_.resize(n), a3_.resize(n), a4_.resize(n);
  sys.acceleration(s.t, s.x, s.v, a1_);
  v2_ = s.v + 0.5 * h * a1_;
  x2_ = s.x + 0.5 * h * s.v;
  sys.acceleration(s.t + 0.5 * h, x2_, v2_, a2_);
  v3_ = s.v + 0.5 * h * a2_;
  x3_ = s.x + 0.5 * h * v2_;
  sys.acceleration(s.t + 0.5 * h, x3_, v3_, a3_);
  v4_ = s.v + h * a3_;
  x4_ = s.x + h * v3_;
  sys.acceleration(s.t + h, x4_, v4_, a4_);
  stats_.rhs_evaluations += 4;
  s.x += (h / 6.0) * (s.v + 2.0 * v2_ + 2.0 * v3_ + v4_);
  s.v += (h / 6.0) * (a1_ + 2.0 * a2_ + 2.0 * a3_ + a4_);
}

}  // namespace vgd::sim::detail
