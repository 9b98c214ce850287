// The accuracy study as a library: the quick cantilever against the elastica
// (a known answer), rows reported as they finish, the CSV, and the caller's
// thread count left as it was.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "vgd/study/accuracy.hpp"

namespace vgd::study {
namespace {

TEST(StudyAccuracy, QuickCantileverAgainstTheElastica) {
  omp_set_num_threads(2);
  std::vector<std::string> seen;
  const AccuracyStudy s = run_accuracy({true, {"cantilever"}}, [&](const AccuracyRow& r) { seen.push_back(r.integrator); });
  EXPECT_EQ(omp_get_max_threads(), 2) << "the study restores the caller's thread count";
  ASSERT_FALSE(s.rows.empty());
  EXPECT_EQ(seen.size(), s.rows.size()) << "every row reported as it finished";
  EXPECT_EQ(s.rows.front().integrator, "reference-elastica");
  int refused = 0, ok = 0;
  for (const auto& r : s.rows) {
    EXPECT_EQ(r.problem, "cantilever");
    EXPECT_EQ(r.model, "strain-rosette");  // the mass-spring strip has no elastica
    if (r.status == "refused") ++refused;
    if (r.status == "ok" && r.integrator.rfind("reference", 0) != 0) {
      ++ok;
      ASSERT_TRUE(std::isfinite(r.error_mm)) << r.integrator;
      // Every stable run ends on the strip's discrete equilibrium, a few
      // tenths of a mm from the elastica's tip at 5 cells (docs/accuracy-vs-time.md).
      EXPECT_LT(r.error_mm, 1.0) << r.integrator << " at " << r.step_or_tol;
    }
  }
  // Each explicit method is first asked for twice its stability limit: refused.
  EXPECT_EQ(refused, 3);
  EXPECT_GE(ok, 6);
  // The CSV: a header and one line per row.
  const std::string csv = accuracy_csv(s);
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), s.rows.size() + 1);
  EXPECT_EQ(csv.rfind("problem,model,integrator,", 0), 0u);
}

}  // namespace
}  // namespace vgd::study
