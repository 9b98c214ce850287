#pragma once
// The system an integrator advances: a model plus the effects a scene called
// for. It sums forces, assembles Jacobians, applies prescribed motion, checks
// states, and counts and times every effect (the per-effect profile).
//
// Seam merges (docs/seams.md) happen in the System's coordinates: the Model
// and the effects keep the original particles ("full" set, Model indexing);
// after merges the integrator's State holds the reduced set
// (num_particles() ≤ num_particles_full()). Every verb below takes and
// returns reduced vectors: the System expands a reduced x, v to the full set
// (a merged particle's copies get its position and velocity), evaluates the
// effects on full vectors and reduces forces and Jacobian rows and columns by
// summing copies. A merged particle's mass is the sum of its copies' masses —
// exactly what deleting a vertex and re-pointing its triangles does to lumped
// masses. Before the first merge reduced = full and nothing is expanded.
#include <array>
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
// A 3N × 3N matrix of 3 × 3 particle blocks in block-CSR form (full storage:
// block (i, j) and (j, i) are both stored when either is), on a pattern that is
// fixed between seam merges. System::jacobian fills ∂f/∂x and ∂f/∂v on one
// shared pattern; the implicit integrators build their step matrix on it
// without sorting, transposing or searching. Blocks are row-major, 9 doubles.
struct BlockPattern {
  int n = 0;                    // block rows and columns (reduced particles)
  std::vector<int> row;         // n + 1: blocks of row i are row[i] .. row[i + 1) − 1
  std::vector<int> col;         // per block, its column; sorted within a row
  std::vector<int> diag;        // per row i, the slot of block (i, i)
  std::vector<int> transpose;   // per block (i, j), the slot of (j, i)
  long version = 0;             // changes whenever the slots are renumbered
  int blocks() const { return static_cast<int>(col.size()); }
  // Slot of block (i, j) (reduced particles) or −1 if not in the pattern.
  int find(int i, int j) const;
};

// ∂f/∂x (N/m) and ∂f/∂v (N·s/m) as blocks on one pattern; rows and columns of
// prescribed particles hold nothing. Value arrays have one extra block at the
// end (slot blocks()): where assembly drops the contributions it cannot place.
struct BlockJacobian {
  BlockPattern pattern;
  std::vector<double> dfdx, dfdv;  // 9 · (blocks() + 1)
  // y = J x for a value array of this pattern (J: dfdx or dfdv); x, y of size 3n.
  void multiply(const std::vector<double>& values, const VecX& x, VecX& y) const;
  // The same matrix as an Eigen sparse matrix (tests, CVODE-style callers).
  SparseMatrix to_sparse(const std::vector<double>& values) const;
};

// What effects with a block Jacobian write into (BlockJacobianEffect). Particle
// indices are the Model's (original) ones: the assembler maps merged copies to
// their reduced particle and drops blocks in prescribed rows or columns.
class JacobianAssembler {
 public:
  // Changes whenever slots are renumbered: effects may cache slots per version.
  long version() const { return version_; }
  // The slot of block (i, j) (original particles), or −1 when the block is
  // dropped (prescribed). A block not yet in the pattern is recorded, gets the
  // scratch slot and the System assembles again on a grown pattern.
  int slot(int i, int j);
  double* dfdx(int slot) { return dfdx_ + 9 * slot; }
  double* dfdv(int slot) { return dfdv_ + 9 * slot; }

 private:
  friend class System;
  long version_ = 0;
  const BlockPattern* pattern_ = nullptr;
  const std::vector<int>* rep_ = nullptr;
  const VecX* free_ = nullptr;
  double* dfdx_ = nullptr;
  double* dfdv_ = nullptr;
  std::vector<std::array<int, 2>>* missing_ = nullptr;
};

// An effect that writes its Jacobian straight into the block pattern (no
// triplets) implements this too; System::jacobian(…, BlockJacobian&) uses it
// instead of Effect::add_jacobian. It must add exactly what add_jacobian adds.
class BlockJacobianEffect {
 public:
  virtual ~BlockJacobianEffect() = default;
  virtual bool add_jacobian_blocks(const Eval& e, JacobianAssembler& out) = 0;
};

struct Stiffness {
  double omega2 = 0.0;         // max_i k_i / m_i (1/s²): squared highest angular frequency bound
  double damping_rate = 0.0;   // max_i c_i / m_i (1/s)
  int particle = -1;           // where omega2 is reached
  std::string effect;          // the effect contributing most there
};

class System {
 public:
  System(Model model, std::vector<std::unique_ptr<Effect>> effects);

  // The original model (full particle set; never changes).
  const Model& model() const { return model_; }
  // Particles and degrees of freedom the integrator advances (reduced set).
  int num_particles() const { return static_cast<int>(mass_.size()); }
  int num_dofs() const { return 3 * num_particles(); }
  int num_particles_full() const { return model_.num_particles(); }
  // Masses (kg) of the reduced particles.
  const VecX& mass() const { return mass_; }
  // True once some particles were merged.
  bool merged() const { return merged_; }
  // Original particle → reduced particle (identity before any merge).
  const std::vector<int>& representative() const { return rep_; }
  // A reduced 3N vector (positions, velocities) as the full set: merged
  // particles' copies get the same values. Returns the input unchanged before any merge.
  VecX expand(const VecX& reduced) const;
  // A full state in the current reduced coordinates: each merged particle at
  // the mass-weighted mean of its copies' positions and velocities.
  State reduce(const State& full) const;
  const std::vector<std::unique_ptr<Effect>>& effects() const { return effects_; }

  // Sum of all effects' forces (N); rows of prescribed particles are zero.
  void force(double t, const VecX& x, const VecX& v, VecX& f);
  // a = M⁻¹ f (m/s²); zero for prescribed particles.
  void acceleration(double t, const VecX& x, const VecX& v, VecX& a);
  // df/dx (N/m) and df/dv (N·s/m), 3N x 3N, with prescribed rows and columns
  // removed (zero). Returns false if some force effect has no Jacobian.
  bool jacobian(double t, const VecX& x, const VecX& v, SparseMatrix& dfdx, SparseMatrix& dfdv);
  // The same Jacobians as blocks on a pattern kept between calls: the union of
  // every block effects have added since the last merge (blocks whose value
  // became 0 stay, as explicit zeros). No sorting: triplets from effects are
  // placed by a search in their block row, BlockJacobianEffects write their
  // blocks into cached slots. J.pattern.version tells callers when the
  // pattern changed (after a merge or a new block): the values are the sum
  // of the same contributions as the SparseMatrix overload's, in the same
  // order per entry.
  bool jacobian(double t, const VecX& x, const VecX& v, BlockJacobian& J);

  // 1 for free degrees of freedom, 0 for prescribed ones (3N).
  const VecX& free_dofs() const { return free_; }
  bool has_prescribed() const { return !prescribed_.empty(); }
  // Overwrites prescribed particles' positions and velocities with their values at s.t.
  void apply_prescribed(State& s) const;
  // False while an active effect has work left that rest must wait for (Effect::blocks_rest).
  bool may_rest() const;
  // After-step hooks of all active effects; drops effects that report finished().
  void after_step(State& s);

  // ½ Σ m v² (J) and Σ effect potential energies (J).
  double kinetic_energy(const VecX& v) const;
  double potential_energy(double t, const VecX& x, const VecX& v) const;

  // Seams: gathers the active effects' merge requests at s (reduced), unites
  // them with the merges so far (a particle may merge with several: seam
  // crossings, corners), and when the particle count falls maps s to the new
  // reduced set conserving mass, Σ m x and momentum Σ m v exactly (to rounding),
  // tells every effect (Effect::particles_merged) and recomputes the stiffness
  // bounds. A request that would make one particle of two prescribed ones is
  // ignored (they follow their own paths). Returns true when particles were
  // merged: integrators must then be reset (Integrator::reset). Call only
  // between integrator advances (sim::run does, at frame boundaries).
  bool apply_merges(State& s);

  // Gershgorin bounds at the rest shape (computed at construction and after every merge).
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

  void compute_stiffness();
  // Full-set scratch state from a reduced one (t, x, v).
  void expand_into(const VecX& reduced, VecX& full) const;
  // Reduced forces (or any per-dof sum) from full ones: copies summed.
  void reduce_sum(const VecX& full, VecX& reduced) const;

  Model model_;
  // ---- merges (identity, merged_ false, until the first merge) ----
  bool merged_ = false;
  std::vector<int> rep_;               // original particle → reduced particle
  std::vector<int> first_;             // reduced particle → its lowest original particle
  VecX mass_;                          // reduced masses (kg)
  std::vector<int> prescribed_full_;   // prescribed original particles, sorted
  VecX xf_, vf_, ff_;                  // full-set scratch vectors (forces, Jacobians)
  mutable VecX px_, pv_;               // full-set scratch of apply_prescribed
  State sf_;                           // full-set scratch state (after-step hooks, merge requests)
  std::vector<std::unique_ptr<Effect>> effects_;
  std::vector<EffectProfile> profile_;  // parallel to effects_
  std::vector<bool> active_;
  std::vector<int> prescribed_;  // prescribed reduced particles
  VecX free_;
  VecX inv_mass_dof_;  // 3N: 1/m for free dofs, 0 for prescribed ones
  Stiffness stiffness_;
  long force_evals_ = 0, jacobian_evals_ = 0;
  Triplets dfdx_t_, dfdv_t_;
  // Block assembly: the pattern (reduced particles), effects with a block
  // Jacobian (nullptr for the others), and blocks found missing in a pass.
  BlockPattern pattern_;
  long pattern_versions_ = 0;
  std::vector<BlockJacobianEffect*> block_effects_;
  std::vector<std::array<int, 2>> missing_;
  void grow_pattern(const std::vector<std::array<int, 2>>& blocks);
  bool assemble_blocks(const Eval& e, BlockJacobian& J);
};

}  // namespace vgd::sim
