#include "vgd/sim/system.hpp"

#include <algorithm>
#include <cmath>

namespace vgd::sim {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

System::System(Model model, std::vector<std::unique_ptr<Effect>> effects)
    : model_(std::move(model)), effects_(std::move(effects)) {
  validate(model_);
  const int n = model_.num_particles();
  profile_.resize(effects_.size());
  active_.assign(effects_.size(), true);
  for (std::size_t i = 0; i < effects_.size(); ++i) profile_[i].name = effects_[i]->name();

  // Prescribed particles (pins) and the per-dof inverse mass.
  for (const auto& e : effects_) e->prescribed_particles(prescribed_);
  std::sort(prescribed_.begin(), prescribed_.end());
  prescribed_.erase(std::unique(prescribed_.begin(), prescribed_.end()), prescribed_.end());
  free_ = VecX::Ones(3 * n);
  for (int p : prescribed_) at(free_, p).setZero();
  inv_mass_dof_.resize(3 * n);
  for (int i = 0; i < n; ++i) at(inv_mass_dof_, i).setConstant(1.0 / model_.mass[i]);
  inv_mass_dof_ = inv_mass_dof_.cwiseProduct(free_);

  // Stiffness bounds: which particle and effect limit explicit steps.
  VecX k = VecX::Zero(n), c = VecX::Zero(n);
  std::vector<VecX> k_by_effect;
  for (const auto& e : effects_) {
    VecX ke = VecX::Zero(n), ce = VecX::Zero(n);
    e->add_stiffness_bound(model_, ke, ce);
    k += ke;
    c += ce;
    k_by_effect.push_back(std::move(ke));
  }
  for (int i = 0; i < n; ++i) {
    if (free_[3 * i] == 0.0) continue;  // a pinned particle does not oscillate
    const double w2 = k[i] / model_.mass[i], rate = c[i] / model_.mass[i];
    if (w2 > stiffness_.omega2) {
      stiffness_.omega2 = w2;
      stiffness_.particle = i;
    }
    stiffness_.damping_rate = std::max(stiffness_.damping_rate, rate);
  }
  if (stiffness_.particle >= 0) {
    double best = -1.0;
    for (std::size_t e = 0; e < effects_.size(); ++e)
      if (k_by_effect[e][stiffness_.particle] > best) {
        best = k_by_effect[e][stiffness_.particle];
        stiffness_.effect = effects_[e]->name();
      }
  }
}

void System::force(double t, const VecX& x, const VecX& v, VecX& f) {
  sum_forces(t, x, v, f);
  if (!prescribed_.empty()) f = f.cwiseProduct(free_);
}

void System::acceleration(double t, const VecX& x, const VecX& v, VecX& a) {
  // inv_mass_dof_ is zero on prescribed dofs: one pass scales and masks.
  sum_forces(t, x, v, a);
  a = a.cwiseProduct(inv_mass_dof_);
}

void System::sum_forces(double t, const VecX& x, const VecX& v, VecX& f) {
  f.setZero(num_dofs());
  const Eval e{model_, t, x, v};
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    if (!active_[i]) continue;
    const auto t0 = Clock::now();
    effects_[i]->add_forces(e, f);
    profile_[i].seconds += seconds_since(t0);
    ++profile_[i].force_calls;
  }
  ++force_evals_;
}

bool System::jacobian(double t, const VecX& x, const VecX& v, SparseMatrix& dfdx, SparseMatrix& dfdv) {
  dfdx_t_.clear();
  dfdv_t_.clear();
  const Eval e{model_, t, x, v};
  bool complete = true;
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    if (!active_[i]) continue;
    const auto t0 = Clock::now();
    complete = effects_[i]->add_jacobian(e, dfdx_t_, dfdv_t_) && complete;
    profile_[i].seconds += seconds_since(t0);
    ++profile_[i].jacobian_calls;
  }
  // Prescribed dofs neither move nor feel forces: drop their rows and columns.
  if (!prescribed_.empty()) {
    auto drop = [&](Triplets& ts) {
      ts.erase(std::remove_if(ts.begin(), ts.end(),
                              [&](const Triplet& tr) { return free_[tr.row()] == 0.0 || free_[tr.col()] == 0.0; }),
               ts.end());
    };
    drop(dfdx_t_);
    drop(dfdv_t_);
  }
  const int n = num_dofs();
  dfdx.resize(n, n);
  dfdv.resize(n, n);
  dfdx.setFromTriplets(dfdx_t_.begin(), dfdx_t_.end());
  dfdv.setFromTriplets(dfdv_t_.begin(), dfdv_t_.end());
  ++jacobian_evals_;
  return complete;
}

void System::apply_prescribed(State& s) const {
  if (prescribed_.empty()) return;
  for (const auto& e : effects_) e->prescribe(s.t, s.x, s.v);
}

void System::after_step(State& s) {
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    if (!active_[i]) continue;
    const auto t0 = Clock::now();
    effects_[i]->after_step(model_, s);
    profile_[i].seconds += seconds_since(t0);
    ++profile_[i].after_step_calls;
    // An effect that has done its work stops costing time.
    if (effects_[i]->finished()) active_[i] = false;
  }
}

double System::kinetic_energy(const VecX& v) const {
  double e = 0.0;
  for (int i = 0; i < model_.num_particles(); ++i) e += 0.5 * model_.mass[i] * at(v, i).squaredNorm();
  return e;
}

double System::potential_energy(double t, const VecX& x, const VecX& v) const {
  const Eval e{model_, t, x, v};
  double u = 0.0;
  for (std::size_t i = 0; i < effects_.size(); ++i)
    if (active_[i]) u += effects_[i]->energy(e);
  return u;
}

void System::check_state(const State& s, double max_speed) const {
  // One cheap pass on every step (no square roots); the particle is looked up
  // only when something is wrong.
  const double limit2 = max_speed * max_speed;
  const int n = model_.num_particles();
  const double* x = s.x.data();
  const double* v = s.v.data();
  bool ok = true;
  for (int k = 0; k < 3 * n; k += 3) {
    const double v2 = v[k] * v[k] + v[k + 1] * v[k + 1] + v[k + 2] * v[k + 2];
    // NaN fails every comparison: `!(v2 <= limit2)` also catches non-finite velocities.
    ok &= (v2 <= limit2) & std::isfinite(x[k] + x[k + 1] + x[k + 2]);
  }
  if (ok) return;
  for (int i = 0; i < n; ++i) {
    if (!at(s.x, i).allFinite() || !at(s.v, i).allFinite())
      throw SimulationError("the simulation diverged at t = " + std::to_string(s.t) + " s: particle " +
                            std::to_string(i) + " has a non-finite position or velocity (try a smaller step, "
                            "more iterations per frame, RK4, implicit Euler or BDF)");
    const double speed = at(s.v, i).norm();
    if (speed > max_speed)
      throw SimulationError("the simulation is blowing up at t = " + std::to_string(s.t) + " s: particle " +
                            std::to_string(i) + " moves at " + std::to_string(speed) + " m/s (limit " +
                            std::to_string(max_speed) + " m/s); try a smaller step or an implicit method");
  }
}

}  // namespace vgd::sim
