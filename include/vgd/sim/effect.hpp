#pragma once
// One physical effect = one Effect (docs/architecture.md, "Effect"). A scene
// lists the effects it calls for; the engine builds its step from exactly those,
// so an effect the scene does not list is never constructed nor evaluated.
//
// Every effect implements the same small set of verbs (IPC Toolkit's Potential,
// MuJoCo's passive forces): forces, optionally their Jacobian, its potential
// energy, a stiffness bound for the explicit stability limit, prescribed motion
// (pins), an after-step hook (deformation limits, collisions) and the seams'
// merge verbs (merge_requests, particles_merged).
#include <array>
#include <vector>

#include "vgd/sim/model.hpp"

namespace vgd::sim {

// What an effect evaluates at: an integrator stage, not necessarily State.
struct Eval {
  const Model& model;
  double t;     // s
  const VecX& x;  // 3N positions (m)
  const VecX& v;  // 3N velocities (m/s)
};

class Effect {
 public:
  virtual ~Effect() = default;
  // Short name used in profiles and messages ("gravity", "mass-spring", ...).
  virtual const char* name() const = 0;

  // Adds this effect's forces (N) into f (3N).
  virtual void add_forces(const Eval& e, VecX& f) = 0;

  // Adds df/dx (N/m) and df/dv (N·s/m) as 3x3 particle blocks, for the implicit
  // integrators. Returns false when the effect provides none; its forces then
  // enter implicit steps explicitly. Effects whose forces do not depend on x
  // or v (gravity) return true and add nothing.
  virtual bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets& dfdv) { return false; }

  // Potential energy (J) of the effect's conservative forces; 0 if it has none.
  virtual double energy(const Eval& e) const { return 0.0; }

  // Adds, per particle, bounds on the row sums of |df/dx| (N/m) and |df/dv|
  // (N·s/m) over the motions the simulation will see (at least at the rest
  // shape). The explicit integrators' stability limit comes from these
  // (Gershgorin: the largest eigenvalue of M⁻¹K is at most max_i k_i / m_i).
  virtual void add_stiffness_bound(const Model& m, VecX& k_rows, VecX& c_rows) const {}

  // Particles whose motion this effect prescribes (pins); default none.
  virtual void prescribed_particles(std::vector<int>& out) const {}
  // Writes the prescribed particles' positions (m) and velocities (m/s) at time t.
  virtual void prescribe(double t, VecX& x, VecX& v) const {}

  // Constraint effects (contacts) may change the total force after every
  // effect has added its share: seed 002 cancels the normal component of a
  // colliding particle's force. Called in effect order, only for effects whose
  // constrains_forces() is true, after all add_forces.
  virtual bool constrains_forces() const { return false; }
  virtual void constrain_forces(const Eval& e, VecX& f) {}

  // Runs after every accepted step; may change positions and velocities
  // (deformation limiting, later collision projection and seam merges).
  virtual void after_step(const Model& m, State& s) {}
  // True when after_step must see every step, not every frame (contacts: cloth
  // moving centimetres between frames passes through a body unseen). BDF runs
  // the hooks once per frame and refuses a system with such an effect.
  virtual bool needs_every_step() const { return false; }
  // Seams (docs/seams.md). Merges happen between integrator advances (frame
  // boundaries of sim::run), in System::apply_merges, never inside a step.
  // Adds pairs of particles (indices of the Model) that should become one
  // particle now; `full` holds every particle of the Model (merged particles'
  // copies share position and velocity).
  virtual void merge_requests(const Model& m, const State& full, std::vector<std::array<int, 2>>& out) {}
  // Drops the requests this effect cannot allow now (offset contact: a merge
  // whose jump could carry cloth through cloth or the body); the seam keeps
  // pulling and asks again. Called after every effect's merge_requests.
  virtual void review_merges(const Model& m, const State& full, std::vector<std::array<int, 2>>& requests) {}
  // Particles were merged. Effects keep their original indexing and are
  // evaluated on full vectors, so nothing is required; representative[i] is
  // the reduced particle of original particle i (equal values: one particle),
  // for effects that drop elements made degenerate or duplicate by the merge
  // (a spring with both ends on one particle, two springs on one edge).
  // Called on every effect, active or not.
  virtual void particles_merged(const Model& m, const std::vector<int>& representative) {}

  // True when the effect has done all its work and may leave the step.
  virtual bool finished() const { return false; }
  // True while the effect has work the system must not be called "at rest"
  // before (seams still open): sim::run's rest detection waits for it.
  virtual bool blocks_rest() const { return false; }
};

}  // namespace vgd::sim
