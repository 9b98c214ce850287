#pragma once
// The system an integrator advances: a model plus the effects a scene called
// for. It sums forces, assembles Jacobians, applies prescribed motion, checks
// states, and counts and times every effect (the per-effect profile).
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "vgd/sim/effect.hpp"

namespace vgd::sim {

// Calls and time per effect and verb.
struct EffectProfile {
  std::string name;
  long force_calls = 0;
  long jacobian_calls = 0;
  long after_step_calls = 0;
  double seconds = 0.0;  // wall time in this effect, all verbs
};

// The stiffest place of the system, for the explicit stability limits.
struct Stiffness {
  double omega2 = 0.0;         // max_i k_i / m_i (1/s²): squared highest angular frequency bound
  double damping_rate = 0.0;   // max_i c_i / m_i (1/s)
  int particle = -1;           // where omega2 is reached
  std::string effect;          // the effect contributing most there
};

class System {
 public:
  System(Model model, std::vector<std::unique_ptr<Effect>> effects);

  const Model& model() const { return model_; }
  int num_dofs() const { return model_.num_dofs(); }
  const std::vector<std::unique_ptr<Effect>>& effects() const { return effects_; }

  // Sum of all effects' forces (N); rows of prescribed particles are zero.
  void force(double t, const VecX& x, const VecX& v, VecX& f);
  // a = M⁻¹ f (m/s²); zero for prescribed particles.
  void acceleration(double t, const VecX& x, const VecX& v, VecX& a);
  // df/dx (N/m) and df/dv (N·s/m), 3N x 3N, with prescribed rows and columns
  // removed (zero). Returns false if some force effect has no Jacobian.
  bool jacobian(double t, const VecX& x, const VecX& v, SparseMatrix& dfdx, SparseMatrix& dfdv);

  // 1 for free degrees of freedom, 0 for prescribed ones (3N).
  const VecX& free_dofs() const { return free_; }
  bool has_prescribed() const { return !prescribed_.empty(); }
  // Overwrites prescribed particles' positions and velocities with their values at s.t.
  void apply_prescribed(State& s) const;
  // After-step hooks of all active effects; drops effects that report finished().
  void after_step(State& s);

  // ½ Σ m v² (J) and Σ effect potential energies (J).
  double kinetic_energy(const VecX& v) const;
  double potential_energy(double t, const VecX& x, const VecX& v) const;

  // Gershgorin bounds at the rest shape (computed once).
  const Stiffness& stiffness() const { return stiffness_; }

  // Throws SimulationError if x or v holds a non-finite value or a particle
  // moves faster than max_speed (m/s): the signature of a blow-up.
  void check_state(const State& s, double max_speed) const;

  const std::vector<EffectProfile>& profile() const { return profile_; }
  long force_evaluations() const { return force_evals_; }
  long jacobian_evaluations() const { return jacobian_evals_; }

 private:
  // Σ effect forces, unmasked; counts and times every effect.
  void sum_forces(double t, const VecX& x, const VecX& v, VecX& f);

  Model model_;
  std::vector<std::unique_ptr<Effect>> effects_;
  std::vector<EffectProfile> profile_;  // parallel to effects_
  std::vector<bool> active_;
  std::vector<int> prescribed_;
  VecX free_;
  VecX inv_mass_dof_;  // 3N: 1/m for free dofs, 0 for prescribed ones
  Stiffness stiffness_;
  long force_evals_ = 0, jacobian_evals_ = 0;
  Triplets dfdx_t_, dfdv_t_;
};

}  // namespace vgd::sim
