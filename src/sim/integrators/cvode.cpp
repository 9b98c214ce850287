// The adaptive stiff integrator: SUNDIALS CVODE (Hindmarsh et al., "SUNDIALS:
// Suite of nonlinear and differential/algebraic equation solvers", ACM TOMS
// 31(3), 2005), variable-order BDF (order ≤ max_order) with Newton iteration.
// The only file of vgd that includes SUNDIALS headers.
//
// The ODE, on the free degrees of freedom only (nf of them):
//     y = (x_f, v_f),   y' = (v_f, M⁻¹ f(t, x, v)_f),
// where x and v hold y's values on free dofs and the prescribed positions and
// velocities at time t on the others (System::apply_prescribed). Prescribed
// dofs are thus removed from the system, not frozen in it: they follow their
// path exactly and their motion enters the forces on their neighbours at every
// stage time. The Newton matrix is I − γ J with
//     J = [[0, I], [M⁻¹ ∂f/∂x, M⁻¹ ∂f/∂v]]   (free rows and columns),
// from System::jacobian.
//
// Linear solvers:
// - direct (default): J in a compressed-sparse-column SUNSparseMatrix, KLU.
//   CVODE zeroes the matrix before every Jacobian call and KLU refactors in the
//   sparsity pattern it analysed, so J is written in a fixed pattern that only
//   grows (the union of every pattern seen, plus the diagonal that I − γJ
//   needs); when it grows, KLU is told to analyse the new pattern
//   (SUNLinSol_KLUReInit).
// - krylov = true: matrix-free GMRES (SPGMR, left preconditioned). J·v comes
//   from the sparse ∂f/∂x, ∂f/∂v evaluated when CVODE sets the preconditioner
//   up (the same lagged Jacobian a direct solve would use: a modified Newton);
//   the preconditioner is block Jacobi: per free particle the 6×6 block of
//   I − γJ built from its 3×3 diagonal blocks of M⁻¹∂f/∂x and M⁻¹∂f/∂v, solved
//   by its Schur complement (I − γ M⁻¹D_ii − γ² M⁻¹K_ii) z_v = r_v + γ M⁻¹K_ii r_x,
//   z_x = r_x + γ z_v.
// - Effects without a Jacobian (add_jacobian returns false): the direct solver
//   uses the partial Jacobian (a modified Newton that still converges while
//   γ times the missing stiffness is small, so CVODE takes more iterations or
//   smaller steps); with krylov = true, J·v is then a difference quotient of
//   the right-hand side (one evaluation per product, counted in
//   rhs_evaluations) and so includes every effect.
//
// Seam merges (System::apply_merges, between advances) change the number of
// unknowns: sim::run then calls reset(), and the next advance builds a new
// CVODE of the new size (order 1, a fresh initial step).
//
// After-step hooks (deformation limits, later collisions) change the state,
// which invalidates CVODE's history. They run once per advance() call, i.e.
// once per frame under sim::run, on the state CVODE returns at t_end. When a
// hook (or anyone else) changed x, v or t between two calls, the next call
// restarts CVODE there (CVodeReInit: order 1, a fresh initial step); otherwise
// CVODE continues with its history. CVODE runs in CV_NORMAL mode without a
// stop time: it steps past t_end as far as its step size goes and
// interpolates back, so its steps do not depend on the frame rate (a stop
// time at every frame cost 10–15 % more steps, and more refactorisations, on
// the flag benchmark); forces are therefore evaluated up to one step beyond
// the frame (prescribed motion and time-dependent effects must be defined
// there). System::check_state runs after every advance(), i.e. per frame.
//
// Order: BDF3–5 are not A-stable; their stability regions miss a sliver along
// the imaginary axis. Stiff, lightly damped modes sit right there, so once a
// scene has settled, max_order > 2 can hold CVODE's step to hω ≲ 0.5 by
// repeated error-test failures, whatever the tolerance (a stiff chain:
// tests/sim/test_implicit.cpp, about 9x the steps of BDF2). While the cloth
// moves a lot, accuracy limits the step and higher orders pay (the falling
// flag: bench_implicit.cpp, less than half the steps of BDF2). BDF2 is A-stable.
//
// Errors: a non-finite force is a recoverable RHS failure (CVODE retries with
// a smaller step) up to kMaxRhsFailuresPerCall times per advance(), then an
// unrecoverable one (CVODE would otherwise creep towards the failure in ever
// smaller steps until it runs out of steps); when CVODE gives up (flag < 0)
// the run stops with a SimulationError naming CVODE's flag, its message and
// what would help.
// Exceptions thrown inside callbacks are carried across the C code and
// rethrown. CVODE's own messages go to the error, never to stderr.
//
// Stats: CVODE's counters (summed over restarts); rhs_evaluations adds the
// right-hand sides of difference-quotient J·v; jacobian_evaluations counts
// System::jacobian calls (CVodeGetNumJacEvals for the direct solver,
// preconditioner setups with a fresh Jacobian for GMRES).
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>

#include "implicit.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::sim::detail {

namespace {

constexpr long kMaxStepsPerCall = 100000;  // internal steps per advance() before CVODE gives up
constexpr int kGmresMaxKrylov = 20;          // GMRES subspace size (CVODE's default is 5)
constexpr int kMaxRhsFailuresPerCall = 20;   // non-finite forces CVODE may retry per advance()

std::string flag_name(int flag) {
  char* s = CVodeGetReturnFlagName(flag);
  std::string out = s ? s : "CV_UNKNOWN";
  std::free(s);
  return out;
}

// What would help, per CVODE failure.
std::string advice(int flag) {
  switch (flag) {
    case CV_TOO_MUCH_WORK:
      return "CVODE needed more than " + std::to_string(kMaxStepsPerCall) +
             " internal steps in one advance (one frame under sim::run): the scene is stiffer or faster than the tolerances allow "
             "(loosen rtol/atol, check material values)";
    case CV_TOO_MUCH_ACC:
      return "the tolerances ask for more than double precision can give (loosen rtol/atol)";
    case CV_ERR_FAILURE:
      return "the error test failed repeatedly (loosen rtol/atol, set a smaller max step, check material values)";
    case CV_CONV_FAILURE:
      return "Newton's iteration failed repeatedly (a missing or wrong force Jacobian, non-smooth or non-finite "
             "forces; set a smaller max step, check material values)";
    case CV_FIRST_RHSFUNC_ERR:
    case CV_REPTD_RHSFUNC_ERR:
    case CV_UNREC_RHSFUNC_ERR:
    case CV_RHSFUNC_FAIL:
      return "the forces stayed non-finite when CVODE retried with smaller steps (a blow-up, material values out "
             "of range, or an effect's bug)";
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL:
      return "the Newton matrix could not be factored or solved (check masses and material values; "
             "try krylov or a smaller max step)";
    default:
      return "check the integrator settings (rtol, atol, max order, max step) and material values";
  }
}

// ---- SUNDIALS objects, freed in reverse order ---------------------------------

struct Cvode {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  SUNMatrix a = nullptr;  // direct solver only
  SUNLinearSolver ls = nullptr;
  void* mem = nullptr;
  Cvode() = default;
  Cvode(const Cvode&) = delete;
  Cvode& operator=(const Cvode&) = delete;
  ~Cvode() {
    if (mem) CVodeFree(&mem);
    if (ls) SUNLinSolFree(ls);
    if (a) SUNMatDestroy(a);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

struct Entry {
  sunindextype row;
  double value;
};

// ---- the integrator ----------------------------------------------------------

class Bdf final : public Integrator {
 public:
  explicit Bdf(const IntegratorSettings& s) : settings_(s) {}
  Method method() const override { return Method::bdf; }
  IntegratorStats stats() const override { return stats_; }

  void prepare(System& sys, const State&) override {
    const auto& st = settings_;
    for (const auto& e : sys.effects())
      if (e->needs_every_step())
        throw SimulationError(std::string("BDF cannot run ") + e->name() +
                              ": it applies after-step corrections once per frame, and contacts must be resolved "
                              "after every step (cloth moving centimetres between frames passes through the body "
                              "unseen). What would work: implicit-euler (what drapes use), or an explicit method "
                              "with auto_substep");
    if (!(st.rtol > 0.0) || !std::isfinite(st.rtol) || !(st.atol > 0.0) || !std::isfinite(st.atol))
      throw SimulationError("BDF needs tolerances > 0 (got rtol " + format_significant(st.rtol, 3) +
                            ", atol " + format_significant(st.atol, 3) + ")");
    if (st.max_order < 1 || st.max_order > 5)
      throw SimulationError("BDF order must be 1 to 5 (got " + std::to_string(st.max_order) + ")");
    if (!(st.max_step >= 0.0))
      throw SimulationError("BDF max step must be >= 0 s, 0 meaning no limit (got " +
                            format_significant(st.max_step, 3) + ")");
  }

  // A merge changed the system: bind() rebuilds the free-dof map and a new
  // CVODE of the new size (statistics are folded, not lost).
  void reset(System& sys, const State& s) override {
    prepare(sys, s);
    sys_ = nullptr;
  }

  void advance(System& sys, State& s, double t_end) override {
    if (!(t_end > s.t)) return;
    bind(sys);
    if (nf_ > 0) {
      integrate(s, t_end);
      for (int j = 0; j < nf_; ++j) {
        s.x[free_[j]] = y_out_[j];
        s.v[free_[j]] = y_out_[nf_ + j];
      }
    }
    s.t = t_end;
    t_out_ = t_end;
    sys.apply_prescribed(s);
    // Hooks run on the returned state; if they change it, the next call restarts CVODE.
    sys.after_step(s);
    sys.check_state(s, settings_.max_speed);
  }

 private:
  // ---- set-up ----

  // Builds the free-dof map (and drops CVODE) for a new system.
  void bind(System& sys) {
    if (sys_ == &sys && static_cast<int>(cidx_.size()) == sys.num_dofs()) return;
    fold_stats();
    cv_.reset();
    sys_ = &sys;
    const int n = sys.num_dofs();
    const VecX& free = sys.free_dofs();
    free_.clear();
    cidx_.assign(n, -1);
    for (int d = 0; d < n; ++d)
      if (free[d] != 0.0) {
        cidx_[d] = static_cast<int>(free_.size());
        free_.push_back(d);
      }
    nf_ = static_cast<int>(free_.size());
    inv_mass_.resize(nf_);
    for (int j = 0; j < nf_; ++j) inv_mass_[j] = 1.0 / sys.mass()[free_[j] / 3];
    // Every entry is written before use: free ones from y, prescribed ones by apply_prescribed.
    eval_.x = VecX::Zero(n);
    eval_.v = VecX::Zero(n);
    pat_ptr_.clear();
    pat_rows_.clear();
    have_jacobian_ = false;
  }

  // Copies s into y and (re)starts CVODE when it is not where CVODE left off.
  void integrate(State& s, double t_end) {
    y_in_.resize(2 * nf_);
    for (int j = 0; j < nf_; ++j) {
      y_in_[j] = s.x[free_[j]];
      y_in_[nf_ + j] = s.v[free_[j]];
    }
    const bool continues = cv_ && !failed_ && s.t == t_out_ && y_out_.size() == y_in_.size() && y_in_ == y_out_;
    if (!continues) start(s.t);
    failed_ = true;  // until CVODE returns successfully
    message_.clear();
    nonfinite_.clear();
    rhs_failures_ = 0;
    pending_ = nullptr;
    sunrealtype tret = s.t;
    const int flag = CVode(cv_->mem, t_end, cv_->y, &tret, CV_NORMAL);
    update_stats();
    if (pending_) std::rethrow_exception(pending_);
    if (flag < 0)
      throw SimulationError("BDF (CVODE) stopped at t = " + format_significant(tret, 3) + " s with " +
                            flag_name(flag) + (message_.empty() ? std::string() : " (\"" + message_ + "\")") +
                            (nonfinite_.empty() ? std::string() : "; " + nonfinite_) + ": " + advice(flag));
    failed_ = false;
    const sunrealtype* y = N_VGetArrayPointer(cv_->y);
    y_out_ = Eigen::Map<const VecX>(y, 2 * nf_);
  }

  // Creates CVODE at (t0, y_in_) the first time, re-initialises it afterwards.
  void start(double t0) {
    if (cv_) {
      fold_stats();
      std::copy(y_in_.data(), y_in_.data() + 2 * nf_, N_VGetArrayPointer(cv_->y));
      check(CVodeReInit(cv_->mem, t0, cv_->y), "CVodeReInit");
      return;
    }
    cv_ = std::make_unique<Cvode>();
    Cvode& c = *cv_;
    if (SUNContext_Create(nullptr, &c.ctx) != 0) throw SimulationError("BDF: cannot create a SUNDIALS context");
    c.y = N_VNew_Serial(2 * nf_, c.ctx);
    c.mem = CVodeCreate(CV_BDF, c.ctx);
    if (!c.y || !c.mem) throw SimulationError("BDF: out of memory creating CVODE");
    check(CVodeSetErrHandlerFn(c.mem, on_error, this), "CVodeSetErrHandlerFn");
    std::copy(y_in_.data(), y_in_.data() + 2 * nf_, N_VGetArrayPointer(c.y));
    check(CVodeInit(c.mem, rhs, t0, c.y), "CVodeInit");
    check(CVodeSetUserData(c.mem, this), "CVodeSetUserData");
    check(CVodeSStolerances(c.mem, settings_.rtol, settings_.atol), "CVodeSStolerances");
    check(CVodeSetMaxOrd(c.mem, settings_.max_order), "CVodeSetMaxOrd");
    check(CVodeSetMaxNumSteps(c.mem, kMaxStepsPerCall), "CVodeSetMaxNumSteps");
    if (settings_.max_step > 0.0) check(CVodeSetMaxStep(c.mem, settings_.max_step), "CVodeSetMaxStep");
    if (settings_.krylov) {
      c.ls = SUNLinSol_SPGMR(c.y, SUN_PREC_LEFT, kGmresMaxKrylov, c.ctx);
      if (!c.ls) throw SimulationError("BDF: cannot create the GMRES solver");
      check(CVodeSetLinearSolver(c.mem, c.ls, nullptr), "CVodeSetLinearSolver");
      check(CVodeSetJacTimes(c.mem, nullptr, jtimes), "CVodeSetJacTimes");
      check(CVodeSetPreconditioner(c.mem, psetup, psolve), "CVodeSetPreconditioner");
    } else {
      c.a = SUNSparseMatrix(2 * nf_, 2 * nf_, 4 * static_cast<sunindextype>(nf_), CSC_MAT, c.ctx);
      if (!c.a) throw SimulationError("BDF: out of memory creating the sparse Jacobian");
      c.ls = SUNLinSol_KLU(c.y, c.a, c.ctx);
      if (!c.ls) throw SimulationError("BDF: cannot create the KLU solver");
      // AMD on A + Aᵀ: the Newton matrix is structurally symmetric (on the 30 × 30
      // flag, 1.7x faster overall than SUNDIALS' default COLAMD).
      if (SUNLinSol_KLUSetOrdering(c.ls, 0) != 0) throw SimulationError("BDF: cannot set KLU's ordering");
      check(CVodeSetLinearSolver(c.mem, c.ls, c.a), "CVodeSetLinearSolver");
      check(CVodeSetJacFn(c.mem, jacobian), "CVodeSetJacFn");
    }
  }

  void check(int flag, const char* call) {
    if (flag < 0)
      throw SimulationError(std::string("BDF: ") + call + " failed with " + flag_name(flag) +
                            (message_.empty() ? std::string() : " (\"" + message_ + "\")") + ": " + advice(flag));
  }

  // ---- statistics ----

  // CVODE's counters restart with CVodeReInit: keep what the finished run counted.
  void fold_stats() { base_ = stats_; base_dq_rhs_ = dq_rhs_; base_jacobians_ = jacobians_; }
  void update_stats() {
    long nst = 0, nfe = 0, nfe_ls = 0, nni = 0, nli = 0, netf = 0, ncfn = 0;
    sunrealtype hlast = 0.0;
    int qlast = 0;
    void* m = cv_->mem;
    CVodeGetNumSteps(m, &nst);
    CVodeGetNumRhsEvals(m, &nfe);
    CVodeGetNumLinRhsEvals(m, &nfe_ls);
    CVodeGetNumNonlinSolvIters(m, &nni);
    CVodeGetNumLinIters(m, &nli);
    CVodeGetNumErrTestFails(m, &netf);
    CVodeGetNumNonlinSolvConvFails(m, &ncfn);
    CVodeGetLastStep(m, &hlast);
    CVodeGetLastOrder(m, &qlast);
    stats_.steps = base_.steps + nst;
    stats_.rhs_evaluations = base_.rhs_evaluations + nfe + nfe_ls + (dq_rhs_ - base_dq_rhs_);
    stats_.jacobian_evaluations = base_.jacobian_evaluations + (jacobians_ - base_jacobians_);
    stats_.newton_iterations = base_.newton_iterations + nni;
    stats_.linear_iterations = base_.linear_iterations + nli;
    stats_.error_test_failures = base_.error_test_failures + netf;
    stats_.convergence_failures = base_.convergence_failures + ncfn;
    if (nst > 0) {
      stats_.last_step = hlast;
      stats_.order = qlast;
    }
  }

  // ---- evaluations ----

  // The full state at time t from the free values in y (prescribed dofs from their path).
  void unpack(double t, const sunrealtype* y) {
    eval_.t = t;
    for (int j = 0; j < nf_; ++j) {
      eval_.x[free_[j]] = y[j];
      eval_.v[free_[j]] = y[nf_ + j];
    }
    sys_->apply_prescribed(eval_);
  }

  // y' = (v, M⁻¹ f); 1 (recoverable: CVODE retries with a smaller step) if f is not finite.
  int eval_rhs(double t, const sunrealtype* y, sunrealtype* ydot) {
    unpack(t, y);
    sys_->force(t, eval_.x, eval_.v, f_);
    for (int j = 0; j < nf_; ++j) {
      const double a = f_[free_[j]] * inv_mass_[j];
      if (!std::isfinite(a)) {
        nonfinite_ = "non-finite force on particle " + std::to_string(free_[j] / 3) +
                     " at t = " + format_significant(t, 3) + " s";
        // Recoverable (CVODE retries with a smaller step) a few times per call, then fatal:
        // otherwise CVODE creeps up to the failure in ever smaller steps.
        return ++rhs_failures_ <= kMaxRhsFailuresPerCall ? 1 : -1;
      }
      ydot[j] = y[nf_ + j];
      ydot[nf_ + j] = a;
    }
    return 0;
  }

  // ∂f/∂x and ∂f/∂v at (t, y) into K_, D_; 1 if they are not finite.
  int eval_jacobian(double t, const sunrealtype* y) {
    unpack(t, y);
    complete_ = sys_->jacobian(t, eval_.x, eval_.v, dfdx_, dfdv_);
    ++jacobians_;
    have_jacobian_ = true;
    for (const SparseMatrix* m : {&dfdx_, &dfdv_})
      for (Eigen::Index k = 0; k < m->nonZeros(); ++k)
        if (!std::isfinite(m->valuePtr()[k])) return 1;
    return 0;
  }

  // Writes J = [[0, I], [M⁻¹K, M⁻¹D]] into the CSC matrix in the stored
  // pattern, growing the pattern (and re-analysing with KLU) when needed.
  void fill_sparse(SUNMatrix jac) {
    const int n2 = 2 * nf_;
    bool grew = pat_ptr_.empty();
    new_ptr_.assign(n2 + 1, 0);
    new_rows_.clear();
    new_vals_.clear();
    for (int c = 0; c < n2; ++c) {
      const bool xcol = c < nf_;
      const int j = xcol ? c : c - nf_;
      col_.clear();
      col_.push_back({c, 0.0});              // the diagonal I − γJ needs
      if (!xcol) col_.push_back({j, 1.0});   // x' = v
      const SparseMatrix& src = xcol ? dfdx_ : dfdv_;
      for (SparseMatrix::InnerIterator it(src, free_[j]); it; ++it) {
        const int r = cidx_[it.row()];
        if (r >= 0) col_.push_back({nf_ + r, it.value() * inv_mass_[r]});
      }
      std::sort(col_.begin(), col_.end(), [](const Entry& a, const Entry& b) { return a.row < b.row; });
      // Merge with the stored column: its rows stay, new rows grow the pattern.
      std::size_t a = pat_ptr_.empty() ? 0 : static_cast<std::size_t>(pat_ptr_[c]);
      const std::size_t ae = pat_ptr_.empty() ? 0 : static_cast<std::size_t>(pat_ptr_[c + 1]);
      std::size_t b = 0;
      while (a < ae || b < col_.size()) {
        sunindextype row;
        double value = 0.0;
        if (b == col_.size() || (a < ae && pat_rows_[a] < col_[b].row)) {
          row = pat_rows_[a++];
        } else {
          row = col_[b].row;
          if (a < ae && pat_rows_[a] == row)
            ++a;
          else
            grew = true;
          while (b < col_.size() && col_[b].row == row) value += col_[b++].value;
        }
        new_rows_.push_back(row);
        new_vals_.push_back(value);
      }
      new_ptr_[c + 1] = static_cast<sunindextype>(new_rows_.size());
    }
    const auto nnz = static_cast<sunindextype>(new_rows_.size());
    if (grew) {
      pat_ptr_ = new_ptr_;
      pat_rows_ = new_rows_;
    }
    if (SUNSparseMatrix_NNZ(jac) < nnz && SUNSparseMatrix_Reallocate(jac, nnz) != 0)
      throw SimulationError("BDF: out of memory for a sparse Jacobian of " + std::to_string(nnz) + " entries");
    std::copy(new_ptr_.begin(), new_ptr_.end(), SUNSparseMatrix_IndexPointers(jac));
    std::copy(new_rows_.begin(), new_rows_.end(), SUNSparseMatrix_IndexValues(jac));
    std::copy(new_vals_.begin(), new_vals_.end(), SUNSparseMatrix_Data(jac));
    if (grew) SUNLinSol_KLUReInit(cv_->ls, jac, nnz, SUNKLU_REINIT_PARTIAL);
  }

  // Block-Jacobi preconditioner of I − γJ for GMRES (see the top of the file).
  int setup_preconditioner(double gamma) {
    const int np = nf_ / 3;
    kblk_.assign(np, Mat3::Zero());
    dblk_.assign(np, Mat3::Zero());
    for (auto [m, blocks] : {std::pair{&dfdx_, &kblk_}, std::pair{&dfdv_, &dblk_}})
      for (int c = 0; c < m->outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(*m, c); it; ++it) {
          const int r = cidx_[it.row()], cc = cidx_[c];
          if (r >= 0 && cc >= 0 && r / 3 == cc / 3) (*blocks)[r / 3](r % 3, cc % 3) = it.value() * inv_mass_[r];
        }
    pinv_.resize(np);
    for (int q = 0; q < np; ++q) {
      const Mat3 p = Mat3::Identity() - gamma * dblk_[q] - gamma * gamma * kblk_[q];
      Eigen::FullPivLU<Mat3> lu(p);
      if (!lu.isInvertible()) return 1;  // recoverable: CVODE retries with a fresh Jacobian or a smaller step
      pinv_[q] = lu.inverse();
      if (!pinv_[q].allFinite()) return 1;
    }
    return 0;
  }

  void solve_preconditioner(double gamma, const sunrealtype* r, sunrealtype* z) const {
    for (int q = 0; q < nf_ / 3; ++q) {
      const Vec3 rx(r + 3 * q), rv(r + nf_ + 3 * q);
      const Vec3 zv = pinv_[q] * (rv + gamma * kblk_[q] * rx);
      const Vec3 zx = rx + gamma * zv;
      for (int k = 0; k < 3; ++k) {
        z[3 * q + k] = zx[k];
        z[nf_ + 3 * q + k] = zv[k];
      }
    }
  }

  // J·v from the stored sparse Jacobian, or a difference quotient when some effect has none.
  int jacobian_times(const sunrealtype* v, sunrealtype* jv, double t, const sunrealtype* y, const sunrealtype* fy) {
    if (complete_) {
      vx_.setZero(sys_->num_dofs());
      vv_.setZero(sys_->num_dofs());
      for (int j = 0; j < nf_; ++j) {
        vx_[free_[j]] = v[j];
        vv_[free_[j]] = v[nf_ + j];
      }
      jfull_.noalias() = dfdx_ * vx_;
      jfull_.noalias() += dfdv_ * vv_;
      for (int j = 0; j < nf_; ++j) {
        jv[j] = v[nf_ + j];
        jv[nf_ + j] = jfull_[free_[j]] * inv_mass_[j];
      }
      return 0;
    }
    // Difference quotient: J v ≈ (f(y + σ v) − f(y)) / σ.
    const auto n2 = 2 * nf_;
    const Eigen::Map<const VecX> vm(v, n2), ym(y, n2), fym(fy, n2);
    const double vnorm = vm.lpNorm<Eigen::Infinity>();
    if (vnorm == 0.0) {
      std::fill(jv, jv + n2, 0.0);
      return 0;
    }
    const double sigma = std::sqrt(std::numeric_limits<double>::epsilon()) *
                         (1.0 + ym.lpNorm<Eigen::Infinity>()) / vnorm;
    ytmp_ = ym + sigma * vm;
    ++dq_rhs_;
    if (const int r = eval_rhs(t, ytmp_.data(), jv); r != 0) return r;
    Eigen::Map<VecX> jvm(jv, n2);
    jvm = (jvm - fym) / sigma;
    return 0;
  }

  // ---- C callbacks: no exception may cross CVODE ----

  template <class F>
  int guarded(F&& f) {
    try {
      return f();
    } catch (...) {
      pending_ = std::current_exception();
      return -1;
    }
  }
  static Bdf& self(void* p) { return *static_cast<Bdf*>(p); }

  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* ud) {
    Bdf& b = self(ud);
    return b.guarded([&] { return b.eval_rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot)); });
  }
  static int jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jac, void* ud, N_Vector, N_Vector, N_Vector) {
    Bdf& b = self(ud);
    return b.guarded([&] {
      if (const int r = b.eval_jacobian(t, N_VGetArrayPointer(y)); r != 0) return r;
      b.fill_sparse(jac);
      return 0;
    });
  }
  static int psetup(sunrealtype t, N_Vector y, N_Vector, sunbooleantype jok, sunbooleantype* jcur,
                    sunrealtype gamma, void* ud) {
    Bdf& b = self(ud);
    return b.guarded([&] {
      *jcur = SUNFALSE;
      if (!jok || !b.have_jacobian_) {
        if (const int r = b.eval_jacobian(t, N_VGetArrayPointer(y)); r != 0) return r;
        *jcur = SUNTRUE;
      }
      return b.setup_preconditioner(gamma);
    });
  }
  static int psolve(sunrealtype, N_Vector, N_Vector, N_Vector r, N_Vector z, sunrealtype gamma, sunrealtype, int,
                    void* ud) {
    Bdf& b = self(ud);
    return b.guarded([&] {
      b.solve_preconditioner(gamma, N_VGetArrayPointer(r), N_VGetArrayPointer(z));
      return 0;
    });
  }
  static int jtimes(N_Vector v, N_Vector jv, sunrealtype t, N_Vector y, N_Vector fy, void* ud, N_Vector) {
    Bdf& b = self(ud);
    return b.guarded([&] {
      return b.jacobian_times(N_VGetArrayPointer(v), N_VGetArrayPointer(jv), t, N_VGetArrayPointer(y),
                              N_VGetArrayPointer(fy));
    });
  }
  static void on_error(int code, const char* module, const char* function, char* msg, void* ud) {
    if (code >= 0) return;  // warnings are not failures
    Bdf& b = self(ud);
    b.message_ = std::string(module ? module : "") + "/" + (function ? function : "") + ": " + (msg ? msg : "");
  }

  // ---- data ----
  IntegratorSettings settings_;
  IntegratorStats stats_, base_;
  long dq_rhs_ = 0, base_dq_rhs_ = 0, jacobians_ = 0, base_jacobians_ = 0;
  int rhs_failures_ = 0;

  System* sys_ = nullptr;
  std::unique_ptr<Cvode> cv_;
  bool failed_ = false;
  double t_out_ = std::numeric_limits<double>::quiet_NaN();  // where CVODE left off
  VecX y_in_, y_out_;

  std::vector<int> free_;  // compact index → dof
  std::vector<int> cidx_;  // dof → compact index, −1 if prescribed
  int nf_ = 0;
  VecX inv_mass_;  // per free dof, 1/kg
  State eval_;
  VecX f_, vx_, vv_, jfull_, ytmp_;

  SparseMatrix dfdx_, dfdv_;
  bool complete_ = true, have_jacobian_ = false;
  std::vector<sunindextype> pat_ptr_, pat_rows_, new_ptr_, new_rows_;
  std::vector<double> new_vals_;
  std::vector<Entry> col_;
  std::vector<Mat3> kblk_, dblk_, pinv_;

  std::string message_, nonfinite_;
  std::exception_ptr pending_;
};

}  // namespace

std::unique_ptr<Integrator> make_bdf(const IntegratorSettings& s) { return std::make_unique<Bdf>(s); }

}  // namespace vgd::sim::detail
