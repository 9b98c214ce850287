// vgd bench accuracy --quick: the claims docs/accuracy-vs-time.md makes about
// the methods' orders and their ordering hold on the quick run, so the
// document cannot silently go stale. One run (about 13 s) checks them all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"

namespace vgd::test {
namespace {

using json = nlohmann::json;

// The quick run's output folder, made once.
const std::filesystem::path& out_dir() {
  static const std::filesystem::path dir = scratch_dir("bench-accuracy");
  return dir;
}

// The quick run's records, run once for every test below.
const json& records() {
  static const json list = [] {
    const auto& dir = out_dir();
    const auto r = run_vgd({"bench", "accuracy", "--quick", "--json", "-o", dir.string()});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "accuracy.csv"));
    EXPECT_TRUE(std::filesystem::exists(dir / "work-precision-hanging-strain-rosette-7.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "work-precision-cantilever-strain-rosette-7.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "work-precision-drape-mass-spring-9.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "work-precision-drape-strain-rosette-9.png"));
    return r.code == 0 ? json::parse(r.out) : json::array();
  }();
  return list;
}

// Error (mm) of `integrator` on `problem`/`model` at its k-th step or
// tolerance in the order the bench runs them (largest first).
std::vector<double> errors(const std::string& problem, const std::string& model, const std::string& integrator) {
  std::vector<double> out;
  for (const auto& r : records())
    if (r["problem"] == problem && r["model"] == model && r["integrator"] == integrator && r["status"] == "ok")
      out.push_back(r["error_mm"].get<double>());
  return out;
}

// (problem, model) pairs whose quick-run trajectories converge (the 10 × 10
// mass-spring flag in its 100 m/s wind does not: docs/accuracy-vs-time.md).
const std::vector<std::pair<std::string, std::string>> kConvergent = {
    {"flag", "strain-rosette"}, {"hanging", "mass-spring"}, {"hanging", "strain-rosette"}};


void writes_one_row_per_run_with_the_stated_columns() {
  EXPECT_FALSE(records().empty());
  std::ifstream in(out_dir() / "accuracy.csv");
  const std::string csv((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "problem,model,integrator,step_or_tol,resolution,error_mm,cpu_s,rhs_evals,jac_evals,refused,status,resolved");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), static_cast<long>(records().size()) + 1);
}

// Every explicit method refuses a step of twice its stability limit before
// it starts, with a message naming the limit; BDF refuses the drape's body
// collision (its hooks run once a frame), naming it. Nothing else is refused.
void explicit_steps_above_the_limit_are_refused() {
  std::map<std::string, int> refused;  // problem -> refusals
  for (const auto& r : records())
    if (r["refused"].get<bool>()) {
      const std::string problem = r["problem"], message = r["message"];
      ++refused[problem];
      if (r["integrator"] == "bdf") {
        EXPECT_EQ(problem, "drape") << r.dump();
        EXPECT_NE(message.find("body-collision"), std::string::npos) << r.dump();
      } else {
        EXPECT_NE(message.find("stability limit"), std::string::npos) << r.dump();
      }
    }
  EXPECT_EQ(refused["flag"], 3 * 2);     // 3 explicit methods × 2 models
  EXPECT_EQ(refused["hanging"], 3 * 2);
  EXPECT_EQ(refused["cantilever"], 3);   // strain rosette only
  EXPECT_EQ(refused["drape"], 3 * 2 + 2 * 2);  // and BDF at its 2 tolerances × 2 models
}

// Symplectic and implicit Euler are first order: a 4× smaller step divides
// the error by about 4 (at least 1.5 measured); midpoint is second order (÷16,
// at least 10); RK4 at least second order on the flag (÷15 measured) and
// close to fourth on the hanging cloth (÷80 to ÷180, at least 50).
void errors_fall_with_the_methods_orders() {
  for (const auto& [problem, model] : kConvergent) {
    SCOPED_TRACE(problem + " " + model);
    auto ratio = [&](const std::string& integrator) {
      const auto e = errors(problem, model, integrator);
      EXPECT_EQ(e.size(), 2u) << integrator;
      return e.size() == 2 ? e[0] / e[1] : 0.0;
    };
    EXPECT_GT(ratio("symplectic-euler"), 2.5);
    EXPECT_LT(ratio("symplectic-euler"), 16.0);  // not second order
    EXPECT_GT(ratio("implicit-euler"), 1.5);
    EXPECT_GT(ratio("midpoint"), 10.0);
    EXPECT_GT(ratio("rk4"), problem == "hanging" ? 50.0 : 10.0);
  }
}

// BDF's error follows its tolerance: rtol 1e-5 is at least 4× more accurate than 1e-3.
void bdf_error_follows_its_tolerance() {
  for (const auto& [problem, model] : kConvergent) {
    SCOPED_TRACE(problem + " " + model);
    const auto e = errors(problem, model, "bdf");
    EXPECT_EQ(e.size(), 2u);
    if (e.size() == 2) {
      EXPECT_GT(e[0] / e[1], 4.0);
    }
  }
}

// On the hanging cloth RK4 is the cheapest way to an error below 1 mm (the
// doc's "which method wins"). Among the explicit methods work is counted in
// force evaluations (each costs the same, and the count does not depend on
// the machine's load): no other explicit run reaching 1 mm needs fewer. The
// implicit runs that reach 1 mm (BDF) cost 8-14x RK4's CPU in the same run;
// the test asks for more than 2x.
void rk4_is_the_cheapest_way_below_one_millimetre_on_the_hanging_cloth() {
  for (const std::string model : {"mass-spring", "strain-rosette"}) {
    SCOPED_TRACE(model);
    double fewest = 1e300, rk4_cpu = 1e300, implicit_cpu = 1e300;
    std::string winner;
    for (const auto& r : records()) {
      if (r["problem"] != "hanging" || r["model"] != model || r["status"] != "ok") continue;
      const auto method = r["integrator"].get<std::string>();
      if (method.rfind("reference", 0) == 0 || method.rfind("preset", 0) == 0) continue;
      if (r["error_mm"].get<double>() >= 1.0) continue;
      const double cpu = r["cpu_s"].get<double>();
      if (r["jac_evals"].get<int>() > 0) {
        implicit_cpu = std::min(implicit_cpu, cpu);
        continue;
      }
      if (method == "rk4") rk4_cpu = std::min(rk4_cpu, cpu);
      const double rhs = r["rhs_evals"].get<double>();
      if (rhs < fewest) fewest = rhs, winner = method;
    }
    EXPECT_EQ(winner, "rk4");
    EXPECT_LT(2.0 * rk4_cpu, implicit_cpu);
  }
}

// The cantilever ends at rest against the elastica: every run that finished,
// whatever its method, step or tolerance (presets included), sits on the same
// discrete equilibrium (within 0.002 mm of each other), and that is the 5-cell
// strip's own error, 0.25 mm: more than nothing, less than 1 % of L = 50 mm.
void cantilever_runs_rest_on_one_equilibrium_near_the_elastica() {
  double lo = 1e300, hi = -1e300;
  int finished = 0;
  for (const auto& r : records())
    if (r["problem"] == "cantilever" && r["status"] == "ok" &&
        r["integrator"].get<std::string>().rfind("reference", 0) != 0) {
      const double e = r["error_mm"].get<double>();
      lo = std::min(lo, e), hi = std::max(hi, e), ++finished;
    }
  EXPECT_EQ(finished, 3 + 2 + 2 + 3);  // explicit at their limits, implicit Euler, BDF, presets
  EXPECT_LT(hi - lo, 0.002);
  EXPECT_GT(lo, 0.1);
  EXPECT_LT(hi, 0.5);
}

// The drape (contact): every explicit and implicit Euler run finishes with
// finite errors, and each method's error falls with its step — but contact
// (a projection after every step) leaves RK4 far from fourth order: a 4×
// smaller step divides its error by 3.3 on the mass-spring cloth (15 on the
// strain rosette), where the flag shows ÷11–20 per halving.
void drape_errors_fall_with_the_step_at_low_order() {
  for (const std::string model : {"mass-spring", "strain-rosette"}) {
    SCOPED_TRACE(model);
    int finished = 0;
    for (const auto& r : records())
      if (r["problem"] == "drape" && r["model"] == model && r["integrator"] != "bdf" && !r["refused"].get<bool>()) {
        EXPECT_EQ(r["status"], "ok") << r.dump();
        EXPECT_TRUE(r["error_mm"].is_number() && std::isfinite(r["error_mm"].get<double>())) << r.dump();
        ++finished;
      }
    EXPECT_EQ(finished, 1 + 3 * 2 + 2 + 3);  // reference, 3 explicit × 2 steps, implicit Euler, presets
    auto ratio = [&](const std::string& integrator) {
      const auto e = errors("drape", model, integrator);
      EXPECT_EQ(e.size(), 2u) << integrator;
      return e.size() == 2 ? e[0] / e[1] : 0.0;
    };
    EXPECT_GT(ratio("symplectic-euler"), 2.5);
    EXPECT_GT(ratio("midpoint"), 1.5);
    EXPECT_GT(ratio("rk4"), 2.5);
    EXPECT_GT(ratio("implicit-euler"), 1.4);
    if (model == "mass-spring") {
      EXPECT_LT(ratio("rk4"), 8.0);
    }
    // Implicit Euler at 2.5 ms is still centimetres off while the cloth lands.
    const auto implicit = errors("drape", model, "implicit-euler");
    if (!implicit.empty()) {
      EXPECT_GT(implicit.back(), 5.0);
    }
  }
}

// The drape's reference (RK4 at 1/128 of its limit in the quick run) reports
// its own error, estimated from RK4 at twice its step: positive and, at 9 × 9,
// below 0.05 mm. Every other finished drape row is judged against it —
// resolved exactly when its error is at least twice that estimate, so no
// error below the reference's own goes unflagged — and no row of the other
// problems is judged.
void drape_rows_below_the_references_own_error_are_unresolved() {
  std::map<std::string, double> ref_error;  // model -> mm
  for (const auto& r : records())
    if (r["problem"] == "drape" && r["integrator"] == "reference-rk4") {
      ASSERT_TRUE(r["error_mm"].is_number()) << r.dump();
      ref_error[r["model"]] = r["error_mm"].get<double>();
      EXPECT_GT(r["error_mm"].get<double>(), 0.0) << r.dump();
      EXPECT_LT(r["error_mm"].get<double>(), 0.05) << r.dump();
      EXPECT_TRUE(r["resolved"].is_null()) << r.dump();
    }
  EXPECT_EQ(ref_error.size(), 2u);
  int judged = 0;
  for (const auto& r : records()) {
    const std::string integrator = r["integrator"];
    if (r["problem"] != "drape" || r["status"] != "ok" || integrator.rfind("reference", 0) == 0) {
      EXPECT_TRUE(r["resolved"].is_null()) << r.dump();
      continue;
    }
    ASSERT_TRUE(r["resolved"].is_boolean()) << r.dump();
    EXPECT_EQ(r["resolved"].get<bool>(), r["error_mm"].get<double>() >= 2 * ref_error[r["model"]]) << r.dump();
    ++judged;
  }
  EXPECT_EQ(judged, 2 * (3 * 2 + 2 + 3));  // 2 models × (3 explicit × 2 steps, implicit Euler, presets)
}

}  // namespace

// One quick run (about 13 s) checks every claim: ctest runs each TEST in a
// process of its own, so separate TESTs would run the bench once each.
TEST(CliBenchAccuracy, QuickRunBearsOutTheDocumentsClaims) {
  writes_one_row_per_run_with_the_stated_columns();
  explicit_steps_above_the_limit_are_refused();
  errors_fall_with_the_methods_orders();
  bdf_error_follows_its_tolerance();
  rk4_is_the_cheapest_way_below_one_millimetre_on_the_hanging_cloth();
  cantilever_runs_rest_on_one_equilibrium_near_the_elastica();
  drape_errors_fall_with_the_step_at_low_order();
  drape_rows_below_the_references_own_error_are_unresolved();
}

}  // namespace vgd::test
