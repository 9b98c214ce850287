// Implicit Euler after Baraff & Witkin 1998, "Large steps in cloth simulation"
// (SIGGRAPH '98, §4–§5): one linearised backward Euler step per fixed step h,
// solved by filtered, preconditioned conjugate gradients.
//
// Backward Euler on M x'' = f(x, v):   v1 = v0 + h M⁻¹ f(x1, v1),  x1 = x0 + h v1.
// Linearising f about the start of the step, f(x0 + Δx, v0 + Δv) ≈ f0 + K Δx + D Δv
// with K = ∂f/∂x, D = ∂f/∂v and Δx = h (v0 + Δv), gives one linear system for
// the velocity change (B&W eq. 16):
//     (M − h D − h² K) Δv = h (f0 + h K v0).
// With newton_iterations > 1 the step continues as Newton's method on the
// implicit equations r(Δv) = h f(x0 + h (v0 + Δv), v0 + Δv) − M Δv = 0,
// relinearised at each iterate k (forces at t + h):
//     (M − h D_k − h² K_k) δ = h f_k − M Δv_k,   Δv_{k+1} = Δv_k + δ,
// stopping early once |r(Δv_k)| ≤ cg_tolerance · |r(0)|.
// Stats: rhs_evaluations = force evaluations (newton_iterations + 1 per step,
// the last one for the acceptance test below), jacobian_evaluations = Newton
// iterations, linear_iterations = PCG iterations.
//
// Decisions:
// - Prescribed degrees of freedom: System::jacobian drops their rows and
//   columns and System::force zeroes their forces, so their rows of the matrix
//   are M_ii and of the right-hand side 0; PCG also applies B&W's filter S (the
//   free-dof mask) to every residual and direction. Their Δv is 0; the frame
//   (FixedStepIntegrator) then writes their prescribed positions and velocities.
// - Symmetry: CG needs a symmetric matrix. Conservative forces and dampers give
//   one; an effect whose blocks are not symmetric is replaced by its symmetric
//   part ½(A + Aᵀ) (the antisymmetric rest then acts through Newton iterations).
// - Missing Jacobians: an effect whose add_jacobian returns false still
//   contributes the blocks it added; the rest of its dependence on x and v
//   enters explicitly through f.
// - Indefiniteness (compressed springs' geometric stiffness can make
//   M − h²K indefinite) and bad linearisations: PCG stops at the first
//   direction of non-positive curvature pᵀAp ≤ 0; and every step is checked
//   after the fact: it is accepted only if the Newton residual at the new
//   state, max |M⁻¹(h f(x1, v1) − M Δv)|, is no larger than the linearised one
//   at Δv = 0, max |M⁻¹ h (f0 + h K v0)|, or than half of max |v0| + max |Δv|
//   (one more force evaluation per step). A near-singular matrix (an
//   eigenvalue of M − h²K close to 0) passes the curvature test but gives a
//   huge Δv that fails this one; left in, it
//   injects energy. A rejected step is retried as two half steps (h²K shrinks
//   fourfold per halving while M stays), up to kMaxHalvings times; beyond that
//   the run stops with a SimulationError saying why. Each retry counts in
//   stats.convergence_failures. Effects that can should offer a definite
//   (clamped) Jacobian, e.g. drop the compressive geometric term of springs
//   (Choi & Ko 2002); the retry is the safety net.
// - A linear solve that reaches cg_max_iterations is accepted as it stands
//   (B&W use a fixed iteration budget too) and counted in
//   stats.convergence_failures.
// - Assembly: System::jacobian fills K and D as 3×3 blocks on a pattern kept
//   between steps (rebuilt after seam merges or when an effect adds a new
//   block); the step matrix is built on the same pattern, symmetrised block
//   by block with the pattern's transpose map, and PCG multiplies in block
//   CSR. Nothing is sorted per step (setFromTriplets, a transpose and a sum
//   were half of the step time on the drapes).
// - Preconditioner: the inverse of each particle's 3×3 diagonal block of the
//   matrix (block Jacobi; B&W use the scalar diagonal); a block that is not
//   positive definite falls back to the particle's mass. Optionally
//   (IntegratorSettings::preconditioner = cholesky) a lagged CHOLMOD factor
//   of an earlier step's matrix: 7–13 PCG iterations instead of 30–60, but
//   with the reference BLAS one triangular solve pair costs ~70 block SpMVs
//   and a factorisation ~65 ms on 5 000 particles, so block Jacobi is the
//   default (docs/performance.md, "Implicit Euler: where the time goes").
// - Warm start: the first Newton iteration's PCG starts from the previous
//   accepted step's Δv scaled by the step ratio (Δv ≈ h a varies slowly);
//   the stopping test stays |b − A x| ≤ cg_tolerance |b|, so the accuracy
//   asked for is unchanged; it halves the iterations of the drapes.
// - Threads: the block products and the step matrix share block rows
//   statically among OpenMP threads when omp_get_max_threads() > 1 (each
//   row summed by one thread in a fixed order: results do not depend on the
//   thread count); the rest is serial and deterministic.
#include <omp.h>

#include <Eigen/Cholesky>
#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cmath>

#include "fixed_step.hpp"
#include "implicit.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/sim/effects/body_collision.hpp"

namespace vgd::sim::detail {

namespace {

constexpr int kMaxHalvings = 8;         // the smallest retried step is h / 256
constexpr double kResidualFloor = 1e-9;  // m/s: Newton residuals below this are accepted anyway
constexpr double kVelocityFraction = 0.5;  // ... and so are those below this fraction of |v0| + |Δv|
// Held contacts reviewed after a solve (let go, or eased to the normal) are
// solved for once more, not until nothing changes: a second re-solve let
// go more contacts every step and the drapes crept on (T-shirt: rest after
// 3.96 s simulated instead of 1.76 s; the skirt with the T-shirt over it
// never came to rest within 8 s). What a re-solve would still change waits
// for the next step.
constexpr int kMaxResolves = 1;

// ---- preconditioned conjugate gradients -------------------------------------

enum class CgStatus { converged, max_iterations, negative_curvature, non_finite };

struct CgResult {
  CgStatus status = CgStatus::converged;
  int iterations = 0;
};

// Block-Jacobi preconditioner: inverses of A's 3×3 diagonal blocks (A on the
// Jacobian's block pattern, row-major blocks).
void block_jacobi(const BlockPattern& p, const std::vector<double>& a, const VecX& mass_dof, std::vector<Mat3>& inv) {
  inv.resize(p.n);
  for (int i = 0; i < p.n; ++i) {
    const Mat3 b = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(a.data() + 9 * p.diag[i]);
    Eigen::LLT<Mat3> llt(b);
    if (llt.info() == Eigen::Success && b.allFinite())
      inv[i] = llt.solve(Mat3::Identity());
    else
      inv[i] = Mat3::Identity() / mass_dof[3 * i];
  }
}

// Solves A x = b for symmetric A by PCG from x = 0, with the filter S applied
// to residuals and directions (Baraff & Witkin §5.3): mask(y) sets y = S y
// (0 on prescribed dofs, the body normal's component removed at held
// contacts; a no-op when all are free). apply_a(p, q): q = A p;
// apply_p(r, z): z = P⁻¹ r. Stops when |r| ≤ tol |b|, at max_it (x then
// holds the last iterate), or at a direction of non-positive curvature (x is
// then meaningless: the step is retried).
class Pcg {
 public:
  template <class ApplyA, class ApplyP, class Mask>
  CgResult solve(ApplyA&& apply_a, ApplyP&& apply_p, const VecX& b, Mask&& mask, double tol, int max_it,
                 const VecX* guess, VecX& x) {
    const auto n = b.size();
    r_ = b;
    mask(r_);
    const double bnorm = r_.norm();
    CgResult out;
    if (!std::isfinite(bnorm)) return {CgStatus::non_finite, 0};
    if (bnorm == 0.0 || guess == nullptr || guess->size() != n) {
      x.setZero(n);
    } else {
      // A warm start: r = b − A x0. The stopping test stays |r| ≤ tol |b|.
      x = *guess;
      mask(x);
      apply_a(x, q_);
      mask(q_);
      r_ -= q_;
      if (!r_.allFinite()) x.setZero(n), r_ = b, mask(r_);
    }
    if (bnorm == 0.0) return out;
    // Solve for x / |b| so that nothing underflows on a system at rest.
    r_ /= bnorm;
    x /= bnorm;
    if (r_.norm() <= tol) {
      x *= bnorm;
      return out;
    }
    apply_p(r_, z_);
    mask(z_);
    p_ = z_;
    double rz = r_.dot(p_);
    for (int k = 0; k < max_it; ++k) {
      apply_a(p_, q_);
      mask(q_);
      const double pq = p_.dot(q_);
      out.iterations = k + 1;
      if (!std::isfinite(pq)) return {CgStatus::non_finite, out.iterations};
      if (pq <= 0.0) return {CgStatus::negative_curvature, out.iterations};
      const double alpha = rz / pq;
      x += alpha * p_;
      r_ -= alpha * q_;
      if (r_.norm() <= tol) break;
      apply_p(r_, z_);
      mask(z_);
      const double rz_new = r_.dot(z_);
      p_ = z_ + (rz_new / rz) * p_;
      rz = rz_new;
    }
    if (out.iterations == max_it && r_.norm() > tol) out.status = CgStatus::max_iterations;
    x *= bnorm;
    return out;
  }

 private:
  VecX r_, z_, p_, q_;
};

// ---- the integrator ----------------------------------------------------------

class ImplicitEuler final : public FixedStepIntegrator {
 public:
  using FixedStepIntegrator::FixedStepIntegrator;

  void prepare(System& sys, const State& s) override {
    FixedStepIntegrator::prepare(sys, s);
    // An indefinite matrix is an outcome the step handles (Outcome::indefinite),
    // not news for the terminal: CHOLMOD would print it on stdout, into a
    // command's JSON (vgd lab drape --json).
    ldlt_.cholmod().print = 0;
    factor_.cholmod().print = 0;
    mass_dof_.resize(0);  // rebuilt from the system's (possibly merged) masses on the next step
    factor_valid_ = false;  // a lagged factor belongs to the old system
    prev_h_ = 0.0;          // ... and so does the warm start
    if (settings_.newton_iterations < 1)
      throw SimulationError("implicit Euler needs at least 1 Newton iteration (got " +
                            std::to_string(settings_.newton_iterations) + ")");
    if (!(settings_.cg_tolerance > 0.0) || settings_.cg_max_iterations < 1)
      throw SimulationError("implicit Euler needs a conjugate-gradient tolerance > 0 (got " +
                            format_significant(settings_.cg_tolerance, 3) +
                            ") and at least 1 iteration (got " + std::to_string(settings_.cg_max_iterations) +
                            ")");
  }

 private:
  void do_step(System& sys, State& s, double h) override { step_or_halve(sys, s, h, 0); }

  // Why a step was not taken.
  enum class Outcome { accepted, indefinite, diverged, non_finite };

  // Takes the step; where it is rejected, takes two half steps instead.
  void step_or_halve(System& sys, State& s, double h, int depth) {
    const Outcome o = try_step(sys, s, h);
    if (o == Outcome::accepted) return;
    ++stats_.convergence_failures;
    if (depth == kMaxHalvings) refuse(o, s.t, h);
    const double t0 = s.t;
    step_or_halve(sys, s, 0.5 * h, depth + 1);
    s.t = t0 + 0.5 * h;
    sys.apply_prescribed(s);
    step_or_halve(sys, s, 0.5 * h, depth + 1);
    s.t = t0;
  }

  [[noreturn]] void refuse(Outcome o, double t, double h) const {
    const std::string when = " at t = " + format_significant(t, 3) + " s even with a step of " +
                             format_significant(h, 3) + " s (" + std::to_string(1 << kMaxHalvings) +
                             " times smaller than asked)";
    if (o == Outcome::non_finite)
      throw SimulationError("implicit Euler: non-finite " + nonfinite_ +
                            "; the step is not taken (check material values, or try a smaller step)");
    if (o == Outcome::indefinite)
      throw SimulationError("implicit Euler: the step matrix M - h df/dv - h^2 df/dx is not positive definite" + when +
                            ": some effect's stiffness is strongly indefinite, typically springs under compression. "
                            "What would help: a smaller step, an effect that clamps its compressive stiffness, "
                            "softer material values, or BDF");
    throw SimulationError("implicit Euler: the linearised step makes the implicit equations worse, not better" + when +
                          ": the forces are too nonlinear over one step. What would help: a smaller step, more Newton "
                          "iterations, softer material values, or BDF");
  }

  // One (Newton-)linearised backward Euler step; s is changed only when accepted:
  // when the Newton residual at the new state, max |M⁻¹(h f(x1, v1) − M Δv)|
  // (m/s), is no larger than the linearised one at Δv = 0, max |M⁻¹ h (f0 + h K v0)|,
  // or than half the velocities involved, max |v0| + max |Δv| (or below
  // kResidualFloor). A step whose linearisation is off by more than that (a
  // near-singular matrix giving a huge Δv, forces far more nonlinear than the
  // step) would inject energy, so it is retried as two half steps. The
  // velocity clause keeps steps whose residual is the explicit part of
  // effects without a Jacobian (O(h² |∂f/∂x| |v| / m)).
  Outcome try_step(System& sys, State& s, double h) {
    const int n = sys.num_dofs();
    const VecX& filter = sys.free_dofs();
    mask_ = sys.has_prescribed() ? &filter : nullptr;
    if (mass_dof_.size() != n) {
      mass_dof_.resize(n);
      for (int i = 0; i < n / 3; ++i) at(mass_dof_, i).setConstant(sys.mass()[i]);
      inv_mass_dof_ = mass_dof_.cwiseInverse();
    }
    // Largest |M⁻¹ r| over all dofs (m/s).
    auto velocity_max = [&](const VecX& r) { return r.cwiseProduct(inv_mass_dof_).lpNorm<Eigen::Infinity>(); };
    if (settings_.hold_contacts || (settings_.hold_contacts_once_sewn && sys.may_rest()))
      gather_contacts(sys);  // off: nothing is held, the step is the plain one
    else contacts_.clear();
    held_.clear();
    dv_.setZero(n);
    double r0 = 0.0;
    const int iterations = std::max(1, settings_.newton_iterations);
    for (int k = 0;; ++k) {
      // The linearisation point: the start (B&W), then the latest iterate at t + h.
      if (k == 0) {
        it_ = s;
      } else {
        it_.t = s.t + h;
        it_.v = s.v + dv_;
        it_.x = s.x + h * it_.v;
        sys.apply_prescribed(it_);
      }
      sys.force(it_.t, it_.x, it_.v, f_);
      ++stats_.rhs_evaluations;
      if (const int i = first_non_finite(f_); i >= 0) {
        nonfinite_ =
            "force on particle " + std::to_string(i / 3) + " at t = " + format_significant(it_.t, 3) + " s";
        if (k == 0) refuse(Outcome::non_finite, s.t, h);  // at the start of the step: no smaller step helps
        return Outcome::non_finite;
      }
      if (k > 0) {
        // Newton residual r(Δv_k) = h f_k − M Δv_k (less the held contacts'
        // normal components: the body's reaction).
        rhs_ = (h * f_ - mass_dof_.cwiseProduct(dv_)).cwiseProduct(filter);
        apply_held(rhs_);
        const double r = velocity_max(rhs_);
        const double scale = kVelocityFraction * (s.v.lpNorm<Eigen::Infinity>() + dv_.lpNorm<Eigen::Infinity>());
        if (r > std::max({r0, scale, kResidualFloor})) return Outcome::diverged;
        if (k == iterations || r <= settings_.cg_tolerance * r0) break;
        if (!held_.empty()) rhs_ = (h * f_ - mass_dof_.cwiseProduct(dv_)).cwiseProduct(filter);  // unreduced again
      }
      sys.jacobian(it_.t, it_.x, it_.v, jac_);
      ++stats_.jacobian_evaluations;
      if (k == 0) {
        jac_.multiply(jac_.dfdx, s.v, tmp_);  // K v0 (N/s)
        // The Jacobian holds no block in a prescribed particle's row or
        // column, so K v0 misses what the prescribed particles' own motion
        // does to their free neighbours over the step: K_fp v_p, added here
        // as a directional difference of the forces (one more evaluation,
        // only while some prescribed particle moves). Without it a free
        // particle next to a moving pin felt the pin's move one step late:
        // on a 5 mm mesh pulled in its plane the residual grew as h², larger
        // than the step's own, and the step was refused at every size.
        if (mask_) add_prescribed_coupling(sys, s, filter, tmp_);
        rhs_ = h * f_ + (h * h) * tmp_;
        if (mask_) rhs_.array() *= filter.array();
        choose_held(s, filter);
        if (held_.empty()) {
          r0 = velocity_max(rhs_);
        } else {
          rhs0_ = rhs_;
          apply_held(rhs0_);
          r0 = velocity_max(rhs0_);
        }
      }
      step_matrix(h);
      ++stats_.newton_iterations;
      if (!held_.empty()) {
        b_full_ = rhs_;
        a_full_ = a_;
      }
      // Held contacts (Baraff & Witkin §5.3): the step solves for Δv = z + y,
      // z the prescribed velocity change of the held particles (along the
      // normal, or all of it for those static friction holds) and y in the
      // filter's range: S A S y = S (b − A z), with A's held rows and columns
      // replaced by the mass so that the matrix stays definite and a direct
      // solve gives y the held components 0 as PCG does. A held particle the
      // body would have to pull is let go, one static friction cannot hold
      // (reaction outside the cone) is held along the normal only, and the
      // step is solved again (once: kMaxResolves).
      for (int pass = 0;; ++pass) {
        if (pass > 0) {
          a_ = a_full_;
          rhs_ = b_full_;
        }
        if (!held_.empty()) {
          if (k == 0) {
            z_.setZero(n);
            for (const Held& c : held_) at(z_, c.p) = c.z;
            multiply_a(z_, tmp_);
            rhs_ -= tmp_;
            if (mask_) rhs_.array() *= filter.array();
          }
          apply_held(rhs_);
          project_step_matrix();
        }
        if (settings_.linear_solver == IntegratorSettings::LinearSolver::cholesky) {
          // Prescribed dofs: their rows and columns hold M_ii only and their
          // right-hand side is 0, so their Δv comes out 0 as with the CG filter.
          const Outcome o = cholesky_solve();
          if (o != Outcome::accepted) return o;
          ++stats_.linear_iterations;
        } else {
          // Warm start of the first Newton iteration: the last accepted step's
          // velocity change, scaled to this step (Δv ∝ h for smooth motion).
          // Newton corrections (k > 0) start from 0.
          const bool warm = settings_.warm_start && k == 0 && prev_h_ > 0.0 && prev_dv_.size() == n;
          if (warm) guess_ = prev_dv_ * (h / prev_h_);
          // A re-solve starts from the last pass's Δv: the system differs
          // only at the contacts let go or eased.
          const bool again = pass > 0;
          if (again) guess_ = delta_;
          const CgResult cg = pcg_solve(warm || again ? &guess_ : nullptr);
          stats_.linear_iterations += cg.iterations;
          if (cg.status == CgStatus::non_finite) {
            nonfinite_ = "force Jacobian at t = " + format_significant(it_.t, 3) + " s";
            refuse(Outcome::non_finite, s.t, h);
          }
          if (cg.status == CgStatus::negative_curvature) return Outcome::indefinite;
          if (cg.status == CgStatus::max_iterations) ++stats_.convergence_failures;
        }
        if (held_.empty()) break;
        apply_held(delta_);
        if (k == 0) delta_ += z_;
        // The body's reaction on each held particle (N·s): A Δ − b, with the
        // unprojected A and b of this linearisation.
        a_.swap(a_full_);
        multiply_a(delta_, tmp_);
        a_.swap(a_full_);
        tmp_ -= b_full_;
        for (Held& c : held_) c.reaction = at(tmp_, c.p);
        if (k > 0 || pass == kMaxResolves || !review_held(s)) break;
      }
      dv_ += delta_;
    }
    s.v += dv_;
    s.x += h * s.v;
    prev_dv_ = dv_, prev_h_ = h;
    // The normal velocity change each held contact took: friction after the
    // step takes up to μ times it off the tangential velocity.
    for (const Held& c : held_)
      if (const double jn = c.reaction.dot(c.n); jn > 0.0)
        for (int q = c.first; q < c.last; ++q)
          body_collision_add_normal_impulse(*contacts_[q].effect, contacts_[q].particle, jn / mass_dof_[3 * c.p]);
    return Outcome::accepted;
  }

  // ---- held contacts -----------------------------------------------------------

  // A particle touching the body after the last step, from a body collision.
  struct Contact {
    int p;             // reduced particle
    Effect* effect;    // the body collision that found it
    int particle;      // ... and its index there (Model indexing)
    Vec3 n;            // the body's outward normal
    Vec3 vb;           // the body's velocity
    bool stuck;        // static friction stopped it at the last after-step
    double mu;         // Coulomb coefficient (0: no friction)
  };
  // A contact the step holds: along the normal (the body does not let it
  // move further in, its tangential motion is free) or, while static
  // friction holds it, in all three directions (it moves with the body).
  struct Held {
    int p;
    Vec3 n;
    bool all;                     // held in all three directions
    Vec3 z;                       // m/s: the velocity change prescribed (its held part)
    Vec3 reaction = Vec3::Zero();  // N·s: the body's reaction (last solve)
    int first, last;              // contacts_[first, last): its copies
    double mu;
    Vec3 w0;                      // m/s: velocity relative to the body at the start
  };

  // Contacts of every body collision, in reduced particles, grouped by particle.
  void gather_contacts(System& sys) {
    contacts_.clear();
    const std::vector<int>& rep = sys.representative();
    for (const auto& e : sys.effects())
      if (const BodyContacts* bc = body_collision_contacts(*e))
        for (std::size_t k = 0; k < bc->particle.size(); ++k) {
          const int i = bc->particle[k];
          if (i < 0 || i >= static_cast<int>(rep.size())) continue;
          contacts_.push_back({rep[i], e.get(), i, bc->normal[k], bc->body_velocity,
                               k < bc->stuck.size() && bc->stuck[k] != 0, bc->friction});
        }
    std::stable_sort(contacts_.begin(), contacts_.end(), [](const Contact& a, const Contact& b) { return a.p < b.p; });
  }

  // The contacts this step holds: those whose particle is free and the
  // step's right-hand side b = h (f0 + h K v0) presses into the body
  // (b·n < 0); one normal per particle (its first copy's). A particle that
  // approaches is stopped along the normal, one that leaves keeps leaving.
  void choose_held(const State& s, const VecX& filter) {
    held_.clear();
    for (std::size_t q = 0; q < contacts_.size();) {
      std::size_t end = q + 1;
      while (end < contacts_.size() && contacts_[end].p == contacts_[q].p) ++end;
      const Contact& c = contacts_[q];
      if (filter[3 * c.p] != 0.0 && at(rhs_, c.p).dot(c.n) < 0.0) {
        Held hc{c.p, c.n, c.stuck && c.mu > 0.0, Vec3::Zero(), Vec3::Zero(), static_cast<int>(q), static_cast<int>(end),
                c.mu, Vec3(at(s.v, c.p) - c.vb)};
        set_z(hc);
        held_.push_back(hc);
      }
      q = end;
    }
  }

  // The velocity change a held particle is given: a particle held along the
  // normal that approaches is stopped there, one that leaves keeps leaving;
  // one held all round moves with the body.
  static void set_z(Held& c) {
    c.z = c.all ? Vec3(-c.w0) : Vec3(std::max(0.0, -c.w0.dot(c.n)) * c.n);
  }

  // After a solve: lets go the held particles the body pulls (reaction into
  // the body) and holds along the normal only those whose reaction leaves
  // the friction cone, |J_t| > μ J_n. Returns true if something changed.
  bool review_held(const State&) {
    bool changed = false;
    std::size_t out = 0;
    for (std::size_t k = 0; k < held_.size(); ++k) {
      Held c = held_[k];
      const double jn = c.reaction.dot(c.n);
      if (jn < 0.0) {
        changed = true;
        continue;
      }
      if (c.all && (c.reaction - jn * c.n).norm() > c.mu * jn) {
        c.all = false;
        set_z(c);
        changed = true;
      }
      held_[out++] = c;
    }
    held_.resize(out);
    return changed;
  }

  // y ← S y: the held components removed.
  void apply_held(VecX& y) const {
    for (const Held& c : held_) {
      auto yi = at(y, c.p);
      if (c.all)
        yi.setZero();
      else
        yi -= yi.dot(c.n) * c.n;
    }
  }

  // The filter S: prescribed dofs and held normals.
  void apply_mask(VecX& y) const {
    if (mask_) y.array() *= mask_->array();
    apply_held(y);
  }

  // a_ ← S a_ S + Σ m n nᵀ over the held particles (S_i = I − n nᵀ).
  void project_step_matrix() {
    const BlockPattern& p = jac_.pattern;
    held_of_.assign(p.n, -1);
    for (std::size_t k = 0; k < held_.size(); ++k) held_of_[held_[k].p] = static_cast<int>(k);
    using RowMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
    for (int i = 0; i < p.n; ++i)
      for (int q = p.row[i]; q < p.row[i + 1]; ++q) {
        const int j = p.col[q];
        const int hi = held_of_[i], hj = held_of_[j];
        if (hi < 0 && hj < 0) continue;
        Eigen::Map<RowMat3> b(a_.data() + 9 * q);
        if (hi >= 0) {
          const Held& c = held_[hi];
          if (c.all)
            b.setZero();
          else
            b -= c.n * (c.n.transpose() * b);
        }
        if (hj >= 0) {
          const Held& c = held_[hj];
          if (c.all)
            b.setZero();
          else
            b -= (b * c.n) * c.n.transpose();
        }
        if (i == j)
          b += held_[hi].all ? Mat3(mass_dof_[3 * i] * Mat3::Identity())
                             : Mat3(mass_dof_[3 * i] * held_[hi].n * held_[hi].n.transpose());
      }
  }

  // out += K_fp v_p: the forces' derivative along the prescribed dofs'
  // velocities (free dofs keep still), by a one-sided difference over a
  // displacement of 1e-7 m at the fastest prescribed dof (relative error of
  // the spring forces ~1e-7 / spacing; rounding ~1e-16 · |f| / 1e-7 m).
  void add_prescribed_coupling(System& sys, const State& s, const VecX& filter, VecX& out) {
    u_ = s.v - s.v.cwiseProduct(filter);  // prescribed dofs' velocities, 0 elsewhere
    const double speed = u_.lpNorm<Eigen::Infinity>();
    if (speed == 0.0) return;
    const double eps = 1e-7 / speed;  // s: the displacement is eps · u
    xe_ = s.x + eps * u_;
    sys.force(s.t, xe_, s.v, fe_);
    ++stats_.rhs_evaluations;
    out += ((fe_ - f_) / eps).cwiseProduct(filter);
  }

  // a_ = ½ (A + Aᵀ) with A = M − h D − h² K, on the Jacobian's block pattern
  // (which holds (j, i) whenever it holds (i, j), and every diagonal block):
  // block (i, j) = ½ (A_ij + A_jiᵀ). Symmetric Jacobians (springs without
  // damping, dampers, gravity) give A itself; for the others CG needs the
  // symmetric part (the antisymmetric rest acts through Newton iterations).
  void step_matrix(double h) {
    const BlockPattern& p = jac_.pattern;
    a_.resize(9 * static_cast<std::size_t>(p.blocks()));
    const double* K = jac_.dfdx.data();
    const double* D = jac_.dfdv.data();
    double* A = a_.data();
    const double ch = 0.5 * h, ch2 = 0.5 * h * h;
    const int n = p.n;
#pragma omp parallel for schedule(static) if (n >= 1024 && omp_get_max_threads() > 1)
    for (int i = 0; i < n; ++i)
      for (int q = p.row[i]; q < p.row[i + 1]; ++q) {
        const int t = p.transpose[q];
        const double *kq = K + 9 * q, *kt = K + 9 * t, *dq = D + 9 * q, *dt = D + 9 * t;
        double* aq = A + 9 * q;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            aq[3 * r + c] = -ch * (dq[3 * r + c] + dt[3 * c + r]) - ch2 * (kq[3 * r + c] + kt[3 * c + r]);
        if (p.col[q] == i) aq[0] += mass_dof_[3 * i], aq[4] += mass_dof_[3 * i], aq[8] += mass_dof_[3 * i];
      }
  }

  // y = a_ x.
  void multiply_a(const VecX& x, VecX& y) const { jac_.multiply(a_, x, y); }

  // a_ as an Eigen sparse matrix (for CHOLMOD, which reads its lower
  // triangle). The scalar pattern is built once per block pattern; a_ is
  // symmetric, so its block-CSR rows read as CSC columns in the same order.
  const SparseMatrix& sparse_a() {
    const BlockPattern& p = jac_.pattern;
    if (sparse_version_ != p.version) {
      const int n = 3 * p.n;
      a_sparse_ = SparseMatrix(n, n);
      a_sparse_.resizeNonZeros(9 * p.blocks());
      int* outer = a_sparse_.outerIndexPtr();
      int* inner = a_sparse_.innerIndexPtr();
      sparse_slot_.resize(9 * static_cast<std::size_t>(p.blocks()));
      int k = 0;
      outer[0] = 0;
      for (int i = 0; i < p.n; ++i)
        for (int r = 0; r < 3; ++r) {
          for (int q = p.row[i]; q < p.row[i + 1]; ++q)
            for (int c = 0; c < 3; ++c) {
              inner[k] = 3 * p.col[q] + c;
              sparse_slot_[k++] = 9 * q + 3 * r + c;
            }
          outer[3 * i + r + 1] = k;
        }
      sparse_version_ = p.version;
    }
    double* v = a_sparse_.valuePtr();
    for (std::size_t k = 0; k < sparse_slot_.size(); ++k) v[k] = a_[sparse_slot_[k]];
    return a_sparse_;
  }

  // delta_ = A⁻¹ rhs_ by PCG with the preconditioner of the settings.
  CgResult pcg_solve(const VecX* guess) {
    auto apply_a = [&](const VecX& x, VecX& y) { multiply_a(x, y); };
    auto mask = [&](VecX& y) { apply_mask(y); };
    if (settings_.preconditioner == IntegratorSettings::Preconditioner::cholesky) {
      // Lagged Cholesky: the factor of an earlier step's A. A changes slowly
      // from step to step (the same springs, slightly rotated), so PCG with
      // it needs a few iterations; it is refactorised when PCG needed more than
      // refactor_iterations, after a reset, or when the pattern changed. A
      // factorisation that fails (A not positive definite) leaves block Jacobi
      // for this step. Either way PCG stops at the same tolerance, so the step
      // is that of the exact solve to within cg_tolerance.
      if (!factor_valid_ || refactor_ || factor_version_ != jac_.pattern.version) refactorise();
      if (factor_valid_) {
        const CgResult cg = pcg_.solve(
            apply_a, [&](const VecX& r, VecX& z) { z = factor_.solve(r); }, rhs_, mask, settings_.cg_tolerance,
            settings_.cg_max_iterations, guess, delta_);
        refactor_ = cg.iterations > settings_.refactor_iterations;
        return cg;
      }
    }
    block_jacobi(jac_.pattern, a_, mass_dof_, pinv_);
    auto apply_p = [&](const VecX& r, VecX& z) {
      z.resize(r.size());
      for (std::size_t i = 0; i < pinv_.size(); ++i) at(z, static_cast<int>(i)) = pinv_[i] * at(r, static_cast<int>(i));
    };
    return pcg_.solve(apply_a, apply_p, rhs_, mask, settings_.cg_tolerance, settings_.cg_max_iterations, guess, delta_);
  }

  void refactorise() {
    const SparseMatrix& a = sparse_a();
    if (factor_version_ != jac_.pattern.version) {
      factor_.analyzePattern(a);
      factor_version_ = jac_.pattern.version;
    }
    factor_.factorize(a);
    factor_valid_ = factor_.info() == Eigen::Success;
    refactor_ = false;
    ++factorisations_;
  }

  // delta_ = A⁻¹ rhs_ by LDLᵀ; the fill-reducing ordering is recomputed only
  // when A's sparsity pattern changes. A pivot ≤ 0 means A is not positive
  // definite: the step is retried smaller, as for CG's negative curvature.
  Outcome cholesky_solve() {
    const SparseMatrix& a = sparse_a();
    if (analysed_version_ != jac_.pattern.version) {
      ldlt_.analyzePattern(a);
      analysed_version_ = jac_.pattern.version;
    }
    ldlt_.factorize(a);
    if (ldlt_.info() != Eigen::Success) return Outcome::indefinite;
    delta_ = ldlt_.solve(rhs_);
    if (!delta_.allFinite()) {
      nonfinite_ = "velocity change from the Cholesky solve";
      return Outcome::non_finite;
    }
    return Outcome::accepted;
  }

  static int first_non_finite(const VecX& f) {
    for (Eigen::Index i = 0; i < f.size(); ++i)
      if (!std::isfinite(f[i])) return static_cast<int>(i);
    return -1;
  }

  VecX mass_dof_, inv_mass_dof_, dv_, delta_, f_, rhs_, tmp_;
  const VecX* mask_ = nullptr;     // the free-dof filter, nullptr when every dof is free
  std::vector<Contact> contacts_;  // touching the body after the last step, by particle
  std::vector<Held> held_;         // ... those this step holds
  std::vector<int> held_of_;       // per particle: its index in held_, −1 if none
  VecX z_, rhs0_, b_full_;         // held normals' Δv; right-hand sides
  std::vector<double> a_full_;     // the step matrix before the held rows and columns were replaced
  VecX u_, xe_, fe_;  // add_prescribed_coupling's scratch
  VecX prev_dv_, guess_;  // the last accepted step's Δv (m/s), for the warm start
  double prev_h_ = 0.0;   // ... and its step (s); 0: none
  std::string nonfinite_;
  BlockJacobian jac_;
  std::vector<double> a_;          // the step matrix on jac_.pattern (row-major 3×3 blocks)
  SparseMatrix a_sparse_;          // ... as a scalar matrix, for CHOLMOD
  std::vector<int> sparse_slot_;   // a_sparse_ value k = a_[sparse_slot_[k]]
  long sparse_version_ = -1;       // the block pattern a_sparse_'s pattern was built for
  std::vector<Mat3> pinv_;
  State it_;
  Pcg pcg_;
  Eigen::CholmodSupernodalLLT<SparseMatrix> ldlt_;  // linear_solver = cholesky
  long analysed_version_ = -1;
  Eigen::CholmodSupernodalLLT<SparseMatrix> factor_;  // preconditioner = cholesky (lagged)
  long factor_version_ = -1;
  bool factor_valid_ = false, refactor_ = false;
  long factorisations_ = 0;
};

}  // namespace

std::unique_ptr<Integrator> make_implicit_euler(const IntegratorSettings& s) { return std::make_unique<ImplicitEuler>(s); }

}  // namespace vgd::sim::detail
