// Yarn strain limiting on triangles: the bound it promises after every step
// (measured as the certificate measures strain), on a mesh whose edges do not
// lie along the yarns, where Provot's spring limit does not hold it; one
// correction's invariants (momentum, pins, shear left free); refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "helpers.hpp"
#include "vgd/mesh/strain.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/strain_limit.hpp"
#include "vgd/sim/integrator.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

// Largest warp and weft strain over the model's triangles (certificate's measure).
double worst_yarn_strain(const Model& m, const VecX& x) {
  double worst = -1.0;
  for (const auto& t : m.triangles) {
    const auto e = vgd::mesh::triangle_strain(m.uv[t[0]], m.uv[t[1]], m.uv[t[2]], at(x, t[0]), at(x, t[1]), at(x, t[2]));
    if (e.valid) worst = std::max({worst, e.warp, e.weft});
  }
  return worst;
}

// A 12 × 12 cloth of 1 m hanging from two corners, its grain turned 30° from
// the mesh's rows, so that no edge lies along the warp or the weft.
Model turned_flag(int n) {
  Model m = make_grid(n, n, 1.0 / (n - 1), 1.0 / (n - 1), Vec3::Zero(), Vec3::UnitX(), -Vec3::UnitY(), 0.1);
  const double a = std::numbers::pi / 6;
  for (auto& uv : m.uv) uv = Vec2(std::cos(a) * uv.x() - std::sin(a) * uv.y(), std::sin(a) * uv.x() + std::cos(a) * uv.y());
  m.triangle_piece.assign(m.triangles.size(), 0);
  m.pieces = {"flag"};
  return m;
}

}  // namespace

TEST(StrainLimit, HoldsTheYarnsWithinTheLimitAfterEveryStepWhereProvotsSpringsDoNot) {
  // The seed's springs and 0.1 kg particles: hanging from two corners, the
  // cloth's triangles stretch by more than 30 % along a yarn. Provot's limit
  // at 10 % on the warp and weft springs leaves them above 10 % (its springs
  // are the mesh's edges, none along a yarn, so it limits almost none); the
  // triangle limit at 10 % keeps every triangle within 1.1 (1 + tolerance)
  // after every step, its passes converging each time.
  const int n = 12;
  const StrainLimitDef defaults;
  struct Outcome {
    double worst = 0.0;
    StrainLimitStats stats;
  };
  auto run = [&](double provot, double triangles) -> Outcome {
    Model m = turned_flag(n);
    MassSpringMaterial mat;
    mat.max_strain = provot;
    MassSpringOptions opt;
    opt.fixed = {0, n - 1};
    auto list = effects(make_mass_spring(m, {mat}, opt), make_gravity({}), make_viscosity({0.2, 0.0}),
                        make_pins(m, {opt.fixed}));
    if (triangles > 0.0) {
      StrainLimitDef d;
      d.limit = {triangles};
      d.fixed = opt.fixed;
      list.insert(list.begin() + 1, make_strain_limit(m, d));
    }
    System sys(m, std::move(list));
    Outcome out;
    step_through(sys, 0.002, 500, [&](int k, const State& s) {  // 1 s, checked after every step
      if (!s.x.allFinite()) {
        ADD_FAILURE() << "non-finite positions at step " << k;
        return false;
      }
      out.worst = std::max(out.worst, worst_yarn_strain(m, s.x));
      EXPECT_EQ(at(s.x, 0), at(m.x0, 0));  // the pinned corner stays put
      return true;
    });
    if (triangles > 0.0) out.stats = *strain_limit_stats(*sys.effects()[1]);
    return out;
  };
  const Outcome free = run(0.0, 0.0), provot = run(0.1, 0.0), limited = run(0.0, 0.1);
  RecordProperty("free_worst", sci(free.worst));
  RecordProperty("provot_worst", sci(provot.worst));
  RecordProperty("limited_worst", sci(limited.worst));
  EXPECT_GT(free.worst, 0.3);
  EXPECT_GT(provot.worst, 0.2);
  EXPECT_LE(limited.worst, 1.1 * (1.0 + defaults.tolerance) - 1.0 + 1e-12);
  EXPECT_GT(limited.worst, 0.1);  // the limit was reached: the check above is not idle
  EXPECT_GT(limited.stats.corrections, 0);
  EXPECT_EQ(limited.stats.unresolved_steps, 0);
  EXPECT_EQ(limited.stats.triangles, 2 * (n - 1) * (n - 1));
  EXPECT_EQ(strain_limit_stats(*make_gravity({})), nullptr);
}

TEST(StrainLimit, ACorrectionKeepsMomentumAndShapeAndLeavesShearAndPinsAlone) {
  // One right triangle, legs 10 cm along the warp and the weft.
  Model m = particles(3, 0.01);
  m.uv = {Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1)};
  m.triangles = {{0, 1, 2}};
  m.mass << 0.01, 0.02, 0.03;
  StrainLimitDef d;
  d.limit = {0.1};
  d.tolerance = 0.0;
  auto place = [&](const Eigen::Matrix<double, 3, 2>& F, State& s) {
    for (int i = 0; i < 3; ++i) at(s.x, i) = Vec3(0.3, 1.0, -0.2) + F * m.uv[i];
  };
  // Sheared 30° with both yarns at their rest length: a woven's bias is soft,
  // nothing to correct.
  {
    auto e = make_strain_limit(m, d);
    State s = initial_state(m);
    Eigen::Matrix<double, 3, 2> F;
    F.col(0) = Vec3(1, 0, 0);
    F.col(1) = Vec3(std::sin(std::numbers::pi / 6), std::cos(std::numbers::pi / 6), 0);
    place(F, s);
    const VecX before = s.x;
    e->after_step(m, s);
    EXPECT_EQ(s.x, before);
    EXPECT_EQ(strain_limit_stats(*e)->corrections, 0);
  }
  // Stretched 50 % along the weft and sheared, flying apart along it.
  for (bool pin : {false, true}) {
    if (pin) d.fixed = {2};
    auto e = make_strain_limit(m, d);
    State s = initial_state(m);
    Eigen::Matrix<double, 3, 2> F;
    F.col(0) = Vec3(1.05, 0, 0);
    F.col(1) = 1.5 * Vec3(std::sin(0.2), std::cos(0.2), 0);
    place(F, s);
    Eigen::Matrix<double, 3, 2> L = Eigen::Matrix<double, 3, 2>::Zero();
    L.col(1) = 2.0 * F.col(1);  // the weft stretching at 200 %/s
    for (int i = 0; i < 3; ++i) at(s.v, i) = Vec3(0.1, 0, 0) + L * m.uv[i];
    const VecX x_before = s.x;
    Vec3 p_before = Vec3::Zero(), p_after = Vec3::Zero();
    for (int i = 0; i < 3; ++i) p_before += m.mass[i] * at(s.v, i);
    e->after_step(m, s);
    for (int i = 0; i < 3; ++i) p_after += m.mass[i] * at(s.v, i);
    const auto strain = vgd::mesh::triangle_strain(m.uv[0], m.uv[1], m.uv[2], at(s.x, 0), at(s.x, 1), at(s.x, 2));
    EXPECT_NEAR(strain.weft, 0.1, 1e-12);
    EXPECT_NEAR(strain.warp, 0.05, 1e-12);  // the warp, within its limit, is kept
    EXPECT_NEAR(strain.shear_deg, 0.2 * 180 / std::numbers::pi, 1e-9);  // and the shear
    // The weft no longer stretching; the warp's rate and the drift are kept.
    const Vec3 weft = (at(s.x, 2) - at(s.x, 0)).normalized();
    EXPECT_NEAR(weft.dot(at(s.v, 2) - at(s.v, 0)), 0.0, 1e-12);
    if (pin) {
      EXPECT_EQ(at(s.x, 2), at(x_before, 2));
    } else {
      EXPECT_LT((p_after - p_before).norm(), 1e-15);
      Vec3 c_before = Vec3::Zero(), c_after = Vec3::Zero();
      for (int i = 0; i < 3; ++i) c_before += m.mass[i] * at(x_before, i), c_after += m.mass[i] * at(s.x, i);
      EXPECT_LT((c_after - c_before).norm(), 1e-15);  // the centre of mass stays
    }
    EXPECT_EQ(strain_limit_stats(*e)->corrections, 1);
  }
}

TEST(StrainLimit, RefusesLimitsThatDoNotFitTheModel) {
  Model m = particles(3, 0.01);
  m.uv = {Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1)};
  m.triangles = {{0, 1, 2}};
  auto refused = [&](const StrainLimitDef& d, const char* says) {
    try {
      make_strain_limit(m, d);
      ADD_FAILURE() << "accepted, expected: " << says;
    } catch (const SimulationError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused({{0.1, 0.2}}, "2 limits given for 1 pieces");
  refused({{-0.1}}, "finite strain >= 0");
  refused({{std::nan("")}}, "finite strain >= 0");
  refused({{0.0}}, "no piece has a limit > 0");
  refused({{0.1}, {}, 0}, "passes must be at least 1");
}
