// vgd bench drape-sphere: the benchmark scene runs and its checks
// hold (speed is measured by the benchmark itself, docs/performance.md, not
// asserted here).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"

namespace vgd::test {
namespace {

using json = nlohmann::json;

// With self-collision the dropped cloth folds round the sphere without passing
// through itself or the sphere (exact checks: every frame against the
// sphere's triangles, the last frame for crossing triangle pairs), on one
// thread and on every core. (That the crossing count catches crossings is
// tested where a fold is made to cross: tests/sim/test_self_collision.cpp.)
TEST(CliBench, DrapeSphereWithSelfCollisionHasNoCrossingsAndNoPenetration) {
  const auto r = run_vgd({"bench", "drape-sphere", "--self-collision", "--duration", "1.6", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json list = json::parse(r.out);
  ASSERT_FALSE(list.empty());
  for (const auto& rec : list) {
    SCOPED_TRACE(rec.dump());
    EXPECT_EQ(rec["status"], "ok");
    EXPECT_TRUE(rec["self_collision"].get<bool>());
    EXPECT_EQ(rec["crossing_triangle_pairs"].get<int>(), 0);
    EXPECT_LE(rec["max_penetration_m"].get<double>(), 1e-3);
    EXPECT_NEAR(rec["simulated_s"].get<double>(), 1.6, 1e-9);
    EXPECT_DOUBLE_EQ(rec["blender_wall_per_simulated_s"].get<double>(), rec["threads"].get<int>() > 1 ? 9.4 : 13.9);
  }
}

}  // namespace
}  // namespace vgd::test
