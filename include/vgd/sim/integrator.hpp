#pragma once
// Integrators advance a System's State to a given time. They are
// interchangeable: all drive the same effects and emit the same frames; the
// method is a scene setting (IntegratorSettings), dispatched in make_integrator.
//
// Explicit methods know their stability limit (from System::stiffness) and
// refuse a step above it with a message naming the limit, the stiffest particle
// and effect, and what would work — or sub-step when auto_substep is set.
#include <limits>
#include <memory>
#include <string>

#include "vgd/sim/system.hpp"

namespace vgd::sim {

enum class Method {
  symplectic_euler,  // seed 000's Euler: v += h a(x, v); x += h v      (order 1)
  midpoint,          // explicit midpoint on y = (x, v)                    (order 2)
  rk4,               // classical fourth-order Runge–Kutta on y = (x, v)   (order 4)
  implicit_euler,    // Baraff–Witkin: one Newton step, conjugate gradients
  bdf,               // SUNDIALS CVODE, variable order BDF, Newton, KLU or GMRES
};

const char* to_string(Method m);
// "euler"/"symplectic-euler", "midpoint", "rk4", "implicit-euler", "bdf"/"cvode"; nullopt-like: throws std::invalid_argument.
Method parse_method(const std::string& s);
bool is_explicit(Method m);

struct IntegratorSettings {
  Method method = Method::symplectic_euler;
  double step = 0.004;         // s: the fixed step of explicit and implicit Euler methods
  bool auto_substep = false;   // explicit methods: shrink the step to the limit instead of refusing
  double safety = 0.9;         // explicit methods: use at most this fraction of the stability limit
  // implicit Euler
  int newton_iterations = 1;   // Baraff–Witkin take one
  double cg_tolerance = 1e-8;  // relative residual of the linear solve (CG), and the Newton stop
  int cg_max_iterations = 1000;
  // The linear solve of each step: preconditioned conjugate gradients
  // (Baraff & Witkin), or a sparse Cholesky factorisation (LDLᵀ, ordering
  // computed once per sparsity pattern) — exact whatever the condition
  // number, which stiff fabrics on light particles make large.
  enum class LinearSolver { cg, cholesky } linear_solver = LinearSolver::cg;
  // CG's preconditioner: the inverse 3×3 diagonal blocks (block Jacobi), or
  // a lagged sparse Cholesky factor of an earlier step's matrix, refactorised
  // when a solve needed more than refactor_iterations PCG iterations (and
  // after resets and pattern changes).
  enum class Preconditioner { block_jacobi, cholesky } preconditioner = Preconditioner::block_jacobi;
  int refactor_iterations = 8;
  // Start each step's first CG solve from the last step's Δv (scaled by the
  // step ratio). Off by default: with a residual test relative to |b|, the
  // stiff modes dominate the residual, so an error the guess carries in the
  // soft ones — a rigid drift of the whole garment, or an inward velocity the
  // collision projection has since removed — can pass the test uncorrected.
  // It flung the shipped skirt off the mannequin within 0.2 s.
  bool warm_start = false;
  // Hold the particles touching a body inside the step (Baraff & Witkin
  // §5.3 contact constraints) instead of leaving them to the body
  // collision's corrections after it. Without it, the solve lets touching
  // particles sink into the body and relaxes their neighbours towards them,
  // the corrections push only the touching ones back out, and friction then
  // holds the re-stretched cloth: at 5–10 ms a square on the shoulder gained
  // 5x its energy and stayed stretched 59 % (docs/accuracy-vs-time.md, Hard
  // cases). With it, energy stays near its start, but sewing takes longer
  // (bench dress: rest at 3.1 s instead of 2.0 s simulated, twice the wall
  // time), so drapes keep it off. Off: bit-identical to the code without it.
  bool hold_contacts = false;
  // Hold them (as hold_contacts) from the first step at which no effect has
  // work left (System::may_rest: every seam sewn): sewing keeps its pace,
  // and settling keeps touching cloth on the body's surface instead of
  // letting each step sink it there. Left to the corrections, a polo's
  // armpit seam junction, pulled up by its armhole's tension, sank 22-28 mm
  // into the crease between arm and torso at every 10 ms step and was pushed
  // back out along the crease's normal (docs/collisions.md). vgd drape and
  // vgd dress set it with --hold-contacts.
  bool hold_contacts_once_sewn = false;
  // BDF (CVODE)
  double rtol = 1e-4;          // relative tolerance
  double atol = 1e-6;          // absolute tolerance (m for positions, m/s for velocities)
  // BDF orders 3-5 are not stable near the imaginary axis, where cloth's
  // lightly damped stiff modes sit: at order 5 a 5 mm strain-rosette mesh
  // gained 86 % energy in 0.2 s (72 708 steps, 102 s); at 2 (A-stable) it
  // completes in 2 410 steps, 4 s (tests/stability). Order 2 damps the
  // swinging of a hanging cloth, though (5.6 mm off at rtol 1e-5 where order
  // 5 is within 0.05 mm): 5 stays the default, 2 is the choice for fine meshes.
  int max_order = 5;
  bool krylov = false;         // GMRES (matrix-free) instead of KLU sparse direct
  double max_step = 0.0;       // s, 0 = no limit
  // every method: a particle faster than this (m/s) means the run blew up
  double max_speed = 340.0;
};

struct IntegratorStats {
  long steps = 0;
  long rhs_evaluations = 0;       // System::force calls made by the integrator
  long jacobian_evaluations = 0;
  long newton_iterations = 0;
  long linear_iterations = 0;
  long error_test_failures = 0;
  long convergence_failures = 0;
  double last_step = 0.0;         // s
  int order = 0;                  // last BDF order (0 for fixed methods)
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual Method method() const = 0;
  // Checks the settings against the system before any step; throws
  // SimulationError explaining why a run would fail (an explicit step above
  // the stability limit) and what would work.
  virtual void prepare(System& sys, const State& s) {}
  // The system changed between two advances (seam merges: fewer particles,
  // new masses and stiffness bounds): drops what was sized or factored for the
  // old system (buffers, CVODE's history) and checks the settings again, as
  // prepare does. Statistics keep counting.
  virtual void reset(System& sys, const State& s) { prepare(sys, s); }
  // Advances s to t_end (s). Throws SimulationError on a blow-up or solver failure.
  virtual void advance(System& sys, State& s, double t_end) = 0;
  virtual IntegratorStats stats() const = 0;
  // The step actually used by fixed-step methods (after any sub-stepping), s.
  virtual double step() const { return 0.0; }
};

std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings);

// Largest stable step (s) of an explicit method for a system with these
// stiffness bounds (before the safety factor); +inf for implicit methods.
// Symplectic Euler: h < 2/ω on undamped oscillations and h < 2/c for the
// damping rate c; RK4: h·ω < 2√2 and h·c < 2.78; midpoint: its stability region
// touches the imaginary axis only at 0, so oscillations grow by (hω)⁴/8 per
// step: h·ω ≤ 0.5 and h³ω⁴/8 − c/2 ≤ 0.01/s (at most 1 % amplitude growth per
// simulated second, net of damping).
double stability_limit(Method m, const Stiffness& k);

}  // namespace vgd::sim
