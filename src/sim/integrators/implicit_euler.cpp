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
// - Preconditioner: the inverse of each particle's 3×3 diagonal block of the
//   matrix (block Jacobi; B&W use the scalar diagonal); a block that is not
//   positive definite falls back to the particle's mass.
// - Single-threaded and deterministic (effects may use OpenMP internally).
#include <Eigen/Cholesky>
#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fixed_step.hpp"
#include "implicit.hpp"

namespace vgd::sim::detail {

namespace {

constexpr int kMaxHalvings = 8;         // the smallest retried step is h / 256
constexpr double kResidualFloor = 1e-9;  // m/s: Newton residuals below this are accepted anyway
constexpr double kVelocityFraction = 0.5;  // ... and so are those below this fraction of |v0| + |Δv|

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

// ---- preconditioned conjugate gradients -------------------------------------

enum class CgStatus { converged, max_iterations, negative_curvature, non_finite };

struct CgResult {
  CgStatus status = CgStatus::converged;
  int iterations = 0;
};

// Block-Jacobi preconditioner: inverses of A's 3×3 diagonal blocks.
void block_jacobi(const SparseMatrix& a, const VecX& mass_dof, std::vector<Mat3>& inv) {
  const int n = static_cast<int>(a.rows() / 3);
  std::vector<Mat3> blocks(n, Mat3::Zero());
  for (int c = 0; c < a.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(a, c); it; ++it)
      if (it.row() / 3 == c / 3) blocks[c / 3](it.row() % 3, c % 3) = it.value();
  inv.resize(n);
  for (int i = 0; i < n; ++i) {
    Eigen::LLT<Mat3> llt(blocks[i]);
    if (llt.info() == Eigen::Success && blocks[i].allFinite())
      inv[i] = llt.solve(Mat3::Identity());
    else
      inv[i] = Mat3::Identity() / mass_dof[3 * i];
  }
}

// Solves A x = b for symmetric A by PCG from x = 0, with the filter S (1 for
// free dofs, 0 for prescribed ones) applied to residuals and directions
// (Baraff & Witkin §5.3). Stops when |r| ≤ tol |b|, at max_it (x then holds
// the last iterate), or at a direction of non-positive curvature (x is then
// meaningless: the step is retried).
class Pcg {
 public:
  CgResult solve(const SparseMatrix& a, const VecX& b, const std::vector<Mat3>& pinv, const VecX& filter, double tol,
                 int max_it, VecX& x) {
    const auto n = b.size();
    x.setZero(n);
    r_ = b.cwiseProduct(filter);
    const double bnorm = r_.norm();
    CgResult out;
    if (!std::isfinite(bnorm)) return {CgStatus::non_finite, 0};
    if (bnorm == 0.0) return out;
    // Solve for x / |b| so that nothing underflows on a system at rest.
    r_ /= bnorm;
    precondition(pinv, r_, z_);
    p_ = z_.cwiseProduct(filter);
    double rz = r_.dot(p_);
    for (int k = 0; k < max_it; ++k) {
      q_.noalias() = a * p_;
      q_ = q_.cwiseProduct(filter);
      const double pq = p_.dot(q_);
      out.iterations = k + 1;
      if (!std::isfinite(pq)) return {CgStatus::non_finite, out.iterations};
      if (pq <= 0.0) return {CgStatus::negative_curvature, out.iterations};
      const double alpha = rz / pq;
      x += alpha * p_;
      r_ -= alpha * q_;
      if (r_.norm() <= tol) break;
      precondition(pinv, r_, z_);
      z_ = z_.cwiseProduct(filter);
      const double rz_new = r_.dot(z_);
      p_ = z_ + (rz_new / rz) * p_;
      rz = rz_new;
    }
    if (r_.norm() > tol) out.status = CgStatus::max_iterations;
    x *= bnorm;
    return out;
  }

 private:
  static void precondition(const std::vector<Mat3>& pinv, const VecX& r, VecX& z) {
    z.resize(r.size());
    for (std::size_t i = 0; i < pinv.size(); ++i) at(z, static_cast<int>(i)) = pinv[i] * at(r, static_cast<int>(i));
  }
  VecX r_, z_, p_, q_;
};

// ---- the integrator ----------------------------------------------------------

class ImplicitEuler final : public FixedStepIntegrator {
 public:
  using FixedStepIntegrator::FixedStepIntegrator;

  void prepare(System& sys, const State& s) override {
    FixedStepIntegrator::prepare(sys, s);
    mass_dof_.resize(0);  // rebuilt from the system's (possibly merged) masses on the next step
    if (settings_.newton_iterations < 1)
      throw SimulationError("implicit Euler needs at least 1 Newton iteration (got " +
                            std::to_string(settings_.newton_iterations) + ")");
    if (!(settings_.cg_tolerance > 0.0) || settings_.cg_max_iterations < 1)
      throw SimulationError("implicit Euler needs a conjugate-gradient tolerance > 0 (got " +
                            fmt(settings_.cg_tolerance) + ") and at least 1 iteration (got " +
                            std::to_string(settings_.cg_max_iterations) + ")");
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
    const std::string when = " at t = " + fmt(t) + " s even with a step of " + fmt(h) + " s (" +
                             std::to_string(1 << kMaxHalvings) + " times smaller than asked)";
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
    if (mass_dof_.size() != n) {
      mass_dof_.resize(n);
      for (int i = 0; i < n / 3; ++i) at(mass_dof_, i).setConstant(sys.mass()[i]);
      inv_mass_dof_ = mass_dof_.cwiseInverse();
      mass_matrix_.resize(n, n);
      mass_matrix_.setIdentity();
      mass_matrix_.diagonal() = mass_dof_;
    }
    // Largest |M⁻¹ r| over all dofs (m/s).
    auto velocity_max = [&](const VecX& r) { return r.cwiseProduct(inv_mass_dof_).lpNorm<Eigen::Infinity>(); };
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
        nonfinite_ = "force on particle " + std::to_string(i / 3) + " at t = " + fmt(it_.t) + " s";
        if (k == 0) refuse(Outcome::non_finite, s.t, h);  // at the start of the step: no smaller step helps
        return Outcome::non_finite;
      }
      if (k > 0) {
        // Newton residual r(Δv_k) = h f_k − M Δv_k.
        rhs_ = (h * f_ - mass_dof_.cwiseProduct(dv_)).cwiseProduct(filter);
        const double r = velocity_max(rhs_);
        const double scale = kVelocityFraction * (s.v.lpNorm<Eigen::Infinity>() + dv_.lpNorm<Eigen::Infinity>());
        if (r > std::max({r0, scale, kResidualFloor})) return Outcome::diverged;
        if (k == iterations || r <= settings_.cg_tolerance * r0) break;
      }
      sys.jacobian(it_.t, it_.x, it_.v, dfdx_, dfdv_);
      ++stats_.jacobian_evaluations;
      if (k == 0) {
        rhs_ = h * f_;
        rhs_.noalias() += (h * h) * (dfdx_ * s.v);
        rhs_ = rhs_.cwiseProduct(filter);
        r0 = velocity_max(rhs_);
      }
      // A = M − h D − h² K, symmetrised.
      a_ = mass_matrix_ - h * dfdv_ - (h * h) * dfdx_;
      at_ = a_.transpose();
      a_ = 0.5 * (a_ + at_);
      ++stats_.newton_iterations;
      if (settings_.linear_solver == IntegratorSettings::LinearSolver::cholesky) {
        // Prescribed dofs: their rows and columns hold M_ii only and their
        // right-hand side is 0, so their Δv comes out 0 as with the CG filter.
        const Outcome o = cholesky_solve();
        if (o != Outcome::accepted) return o;
        ++stats_.linear_iterations;
        dv_ += delta_;
        continue;
      }
      block_jacobi(a_, mass_dof_, pinv_);
      const CgResult cg = pcg_.solve(a_, rhs_, pinv_, filter, settings_.cg_tolerance, settings_.cg_max_iterations, delta_);
      stats_.linear_iterations += cg.iterations;
      if (cg.status == CgStatus::non_finite) {
        nonfinite_ = "force Jacobian at t = " + fmt(it_.t) + " s";
        refuse(Outcome::non_finite, s.t, h);
      }
      if (cg.status == CgStatus::negative_curvature) return Outcome::indefinite;
      if (cg.status == CgStatus::max_iterations) ++stats_.convergence_failures;
      dv_ += delta_;
    }
    s.v += dv_;
    s.x += h * s.v;
    return Outcome::accepted;
  }

  // delta_ = A⁻¹ rhs_ by LDLᵀ; the fill-reducing ordering is recomputed only
  // when A's sparsity pattern changes. A pivot ≤ 0 means A is not positive
  // definite: the step is retried smaller, as for CG's negative curvature.
  Outcome cholesky_solve() {
    const bool same = analysed_ && a_.nonZeros() == static_cast<Eigen::Index>(pattern_inner_.size()) &&
                      std::equal(a_.outerIndexPtr(), a_.outerIndexPtr() + a_.outerSize() + 1, pattern_outer_.begin(),
                                 pattern_outer_.end()) &&
                      std::equal(a_.innerIndexPtr(), a_.innerIndexPtr() + a_.nonZeros(), pattern_inner_.begin());
    if (!same) {
      ldlt_.analyzePattern(a_);
      pattern_outer_.assign(a_.outerIndexPtr(), a_.outerIndexPtr() + a_.outerSize() + 1);
      pattern_inner_.assign(a_.innerIndexPtr(), a_.innerIndexPtr() + a_.nonZeros());
      analysed_ = true;
    }
    ldlt_.factorize(a_);
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

  VecX mass_dof_, inv_mass_dof_, dv_, delta_, f_, rhs_;
  std::string nonfinite_;
  SparseMatrix mass_matrix_, dfdx_, dfdv_, a_, at_;
  std::vector<Mat3> pinv_;
  State it_;
  Pcg pcg_;
  Eigen::CholmodSupernodalLLT<SparseMatrix> ldlt_;
  bool analysed_ = false;
  std::vector<int> pattern_outer_, pattern_inner_;
};

}  // namespace

std::unique_ptr<Integrator> make_implicit_euler(const IntegratorSettings& s) { return std::make_unique<ImplicitEuler>(s); }

}  // namespace vgd::sim::detail
