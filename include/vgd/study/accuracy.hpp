#pragma once
// The accuracy study (`vgd bench accuracy`, docs/accuracy-vs-time.md): what
// accuracy costs in time. Problems with a known answer, every integrator at
// several steps (fixed-step methods) or tolerances (BDF), both cloth models,
// one or two resolutions:
//
//   flag        the seed's flag in its gusty wind (data/scenes/flag.json) for 0.5 s
//               (over 2 s the flapping flag forgets its start: every method ends
//               hundreds of mm from any other); reference: RK4 at 1/32 of its
//               stability limit
//   hanging     a square hanging from two corners (data/scenes/hanging-cloth.json)
//               settling towards its static equilibrium for 4 s; reference: BDF
//               of order 5 at rtol 1e-8 (a converged fine-tolerance solve)
//   cantilever  the lab's tip-loaded strip (vgd lab tip-cantilever): 50 × 10 mm
//               of denim with ν = 0, clamped, a dead tip load k = P L²/B = 2,
//               released straight and damped to rest in 0.5 s; reference: the
//               elastica (lab::tip_load_elastica); strain rosette only (the
//               mass-spring strip has no linear bending stiffness: no elastica
//               to compare with)
//   drape       data/scenes/drape-sphere.json on a coarse grid, the first 0.32 s
//               (falls 0.3 m, lands, its sides still falling); reference: RK4 at
//               1/512 of its stability limit (quick run: 1/128; BDF refuses
//               contact), its own error estimated from RK4 at twice its step
//               (contact makes it first order) and reported as the reference
//               row's error; a row whose error is below twice that estimate is
//               marked unresolved (resolved = 0)
//
// Error: the largest distance (mm) of any particle from the reference at the
// final time; for the cantilever, the distance (mm) of the strip's tip (mean
// of its end column, as the lab measures it) from the elastica's tip.
// CPU time: std::clock of the run (1 thread). Counts: IntegratorStats.
// A run the engine refuses before it starts (an explicit step above the
// stability limit, BDF with contact) is marked refused; one stopped by a
// blow-up, failed.
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace vgd::study {

struct AccuracyRow {
  std::string problem, model, integrator;  // integrator: a method, "reference-<method>" or "preset-<quality>"
  double step_or_tol = 0;  // s for fixed-step methods, rtol for BDF
  int resolution = 0;      // particles along the cloth's first grid direction
  double error_mm = std::numeric_limits<double>::quiet_NaN();
  double cpu_s = 0;
  long rhs = 0, jac = 0;
  bool refused = false;
  std::string status = "ok", message;  // ok, refused, failed, unavailable
  // Whether the error exceeds twice the reference's own estimated error
  // (drape): 1 resolved, 0 not, -1 not judged (no estimate, run not finished,
  // the reference itself).
  int resolved = -1;
};

struct AccuracyOptions {
  bool quick = false;                 // coarse grids, short runs, fewer steps (well under a minute)
  std::vector<std::string> problems;  // flag, hanging, cantilever, drape; empty = all
};

struct AccuracyStudy {
  std::vector<AccuracyRow> rows;
  // "<problem>-<model>-<resolution>" -> the reference's estimated error (mm), where estimated (drape).
  std::map<std::string, double> reference_errors;
};

// The problem names run_accuracy knows.
std::vector<std::string> accuracy_problems();

// Runs the study on 1 thread (the OpenMP thread count is restored after).
// `on_row` sees each row as it is finished (to print progress).
AccuracyStudy run_accuracy(const AccuracyOptions& options,
                           const std::function<void(const AccuracyRow&)>& on_row = {});

// accuracy.csv: one row per run; the last column, resolved, is 1 or 0 where
// the reference's error is estimated (drape), empty elsewhere.
std::string accuracy_csv(const AccuracyStudy& study);

// Writes accuracy.csv and one work-precision diagram (error against CPU time,
// log–log, one curve per method, the Pareto front ringed; unresolved rows
// hollow below a dashed line at twice the reference's estimated error) per
// problem × model × resolution, work-precision-<problem>-<model>-<resolution>.png,
// into `out_dir` (created). Returns the diagrams written.
std::vector<std::filesystem::path> write_accuracy(const AccuracyStudy& study, const std::filesystem::path& out_dir);

}  // namespace vgd::study
