// Body collisions: a cloth draped on a sphere stays outside it (measured
// exactly), Coulomb friction on a slope, seed 002's slide, seam and belt points.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "surfaces.hpp"
#include "vgd/mesh/surface_checks.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/body_collision.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/integrator.hpp"

namespace vgd::sim {
namespace {

using test::effects;
using test::sci;

constexpr double kG = 9.81;  // m/s²

std::vector<mesh::Vec3> positions(const VecX& x) {
  std::vector<mesh::Vec3> out;
  for (int i = 0; i < x.size() / 3; ++i) out.push_back(at(x, i));
  return out;
}

double max_speed(const VecX& v) {
  double s = 0;
  for (int i = 0; i < v.size() / 3; ++i) s = std::max(s, at(v, i).norm());
  return s;
}

// A light fabric on 2 g particles (seed-like springs, N/m), gravity and air
// drag, with the collision given.
std::vector<std::unique_ptr<Effect>> light_cloth(const Model& m, std::unique_ptr<Effect> collision) {
  MassSpringMaterial mat;
  mat.warp = mat.weft = 60.0;
  mat.shear = mat.bend_warp = mat.bend_weft = 10.0;
  mat.damping = 0.02;
  return effects(make_mass_spring(m, {mat}), make_gravity({}), make_viscosity({0.0, 2.0}), std::move(collision));
}

struct Drape {
  double max_depth, top_height, speed, centre_speed, max_pen_seen;
  int in_contact;
};

// A 31 × 31 cloth (0.9 m square, 3 cm spacing, 2 g particles) dropped from
// 5 cm above a 0.3 m sphere (4 992 triangles), seed-like springs, 2 s.
Drape drape(ContactResponse response, BodyQuery query, Method method) {
  constexpr int n = 31;
  constexpr double d = 0.03, r = 0.3;
  const Vec3 origin(-0.5 * d * (n - 1), r + 0.05, -0.5 * d * (n - 1));
  Model m = make_grid(n, n, d, d, origin, Vec3::UnitX(), Vec3::UnitZ(), 0.002);
  BodyCollisionDef def;
  def.body = test::uv_sphere(r);
  def.response = response;
  def.query = query;
  auto coll = make_body_collision(m, def);
  Effect* c = coll.get();
  System sys(m, light_cloth(m, std::move(coll)));
  IntegratorSettings st;
  st.method = method;
  st.step = method == Method::implicit_euler ? 0.005 : 0.002;
  st.auto_substep = true;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  double worst = 0.0;
  for (int frame = 1; frame <= 40; ++frame) {
    integ->advance(sys, s, frame * 0.05);
    const auto depth = mesh::penetration_depths(def.body, positions(s.x));
    worst = std::max(worst, *std::max_element(depth.begin(), depth.end()));
  }
  const int centre = (n / 2) * n + n / 2;
  const auto& stats = body_collision_stats(*c);
  return {worst, s.x[3 * centre + 1], max_speed(s.v), at(s.v, centre).norm(), stats.max_penetration, stats.in_contact};
}

void check_drape(const Drape& res, const std::string& tag, bool rests = true) {
  ::testing::Test::RecordProperty(tag + "_max_depth_m", sci(res.max_depth));
  ::testing::Test::RecordProperty(tag + "_max_speed_end_m_per_s", sci(res.speed));
  ::testing::Test::RecordProperty(tag + "_max_penetration_seen_m", sci(res.max_pen_seen));
  EXPECT_LE(res.max_depth, 0.001);  // the drape's 1 mm bound, exact (CGAL) at every frame
  if (!rests) return;
  EXPECT_GT(res.in_contact, 50);
  // Resting on top: the centre particle at the clearance over the pole.
  EXPECT_NEAR(res.top_height, 0.3 + 0.003, 0.002);
  // On top and nearly still (2 s is short of full rest: 0.04–0.06 m/s seen).
  EXPECT_LT(res.centre_speed, 0.1);
  EXPECT_LT(res.speed, 0.5);          // the hanging skirt still sways, nothing flies off
}

TEST(BodyCollision, ClothDrapedOnSphereStaysOutsideProvot) {
  check_drape(drape(ContactResponse::provot, BodyQuery::grid, Method::symplectic_euler), "provot");
}
// Frictionless (seed 002 without seams): the cloth slides off the sphere; it
// must still never be inside it.
TEST(BodyCollision, ClothOnSphereSlidesOffWithoutEnteringIt) {
  check_drape(drape(ContactResponse::slide, BodyQuery::grid, Method::symplectic_euler), "slide", false);
}
TEST(BodyCollision, ClothDrapedOnSphereStaysOutsideExactImplicit) {
  check_drape(drape(ContactResponse::provot, BodyQuery::exact, Method::implicit_euler), "exact_implicit");
}

// ---- one particle on a plane ------------------------------------------------

struct Slope {
  Model model;
  BodyCollisionDef def;
  Vec3 down;    // unit, downhill along the surface
  Vec3 normal;  // unit, out of the surface
};

// A 2 m slab tilted by theta about z; the particle starts on it at the clearance.
Slope slope(double theta, const Vec3& v0_along_down, double mu, ContactResponse response) {
  Slope s{test::particles(1, 0.01), {}, Vec3::Zero(), Vec3::Zero()};
  const Mat3 rot = Eigen::AngleAxisd(-theta, Vec3::UnitZ()).toRotationMatrix();  // +x side goes down
  s.def.body = test::box(Vec3(1.0, 0.1, 1.0), rot);
  s.def.query = BodyQuery::exact;
  s.def.friction = mu;
  s.def.response = response;
  s.normal = rot * Vec3::UnitY();
  s.down = rot * Vec3::UnitX();
  at(s.model.x0, 0) = (0.1 + s.def.clearance) * s.normal - 0.5 * s.down;
  at(s.model.v0, 0) = v0_along_down;
  return s;
}

State run(Slope& sl, double t_end, std::unique_ptr<Effect>* keep = nullptr, bool gravity = true, double h = 0.001) {
  auto coll = make_body_collision(sl.model, sl.def);
  std::vector<std::unique_ptr<Effect>> fx;
  if (gravity) fx.push_back(make_gravity({}));
  fx.push_back(std::move(coll));
  System sys(sl.model, std::move(fx));
  IntegratorSettings st;
  st.step = h;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  integ->advance(sys, s, t_end);
  return s;
}

// The body between particles: a 10 × 10 cloth at a 3 cm spacing dropped
// across a rod of 6 mm radius that lies midway between two rows of particles,
// where no particle ever touches it. Particles alone let it pass between them
// (the cloth falls on); with the body's points and the cloth's edge midpoints
// and centres the cloth hangs on it like a towel on a rail, and no point of
// the cloth between particles (edge midpoints, triangle centres, measured
// exactly with CGAL) is ever more than 1 mm inside it.
struct Towel {
  double deepest;       // m: deepest cloth midpoint or centre inside the rod over the frames
  double rows_end;      // m: mean height of the two rows beside the rod at the end
  long pushes;
};
Towel drop_on_rod(double vertex_clearance) {
  constexpr int n = 10;
  constexpr double d = 0.03, r = 0.006;
  const Vec3 origin(-0.5 * d * (n - 1), r + 0.02, -0.5 * d * (n - 1));
  Model m = make_grid(n, n, d, d, origin, Vec3::UnitX(), Vec3::UnitZ(), 0.002);
  BodyCollisionDef def;
  def.body = test::rod(r, 0.5);
  def.vertex_clearance = vertex_clearance;
  auto coll = make_body_collision(m, def);
  Effect* c = coll.get();
  System sys(m, light_cloth(m, std::move(coll)));
  IntegratorSettings st;
  st.method = Method::implicit_euler;
  st.step = 0.005;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  Towel t{0.0, 0.0, 0};
  for (int frame = 1; frame <= 40; ++frame) {
    integ->advance(sys, s, frame * 0.025);
    std::vector<mesh::Vec3> between;
    for (const auto& tri : m.triangles) {
      const Vec3 a = at(s.x, tri[0]), b = at(s.x, tri[1]), cc = at(s.x, tri[2]);
      between.insert(between.end(), {(a + b + cc) / 3.0, 0.5 * (a + b), 0.5 * (b + cc), 0.5 * (cc + a)});
    }
    const auto depth = mesh::penetration_depths(def.body, between);
    t.deepest = std::max(t.deepest, *std::max_element(depth.begin(), depth.end()));
  }
  for (int i = 0; i < n; ++i) t.rows_end += (s.x[3 * (4 * n + i) + 1] + s.x[3 * (5 * n + i) + 1]) / (2.0 * n);
  t.pushes = body_collision_stats(*c).vertex_contacts + body_collision_stats(*c).sample_contacts;
  return t;
}

TEST(BodyCollision, ASharpBodyDoesNotPassBetweenParticles) {
  const Towel on = drop_on_rod(0.001);
  ::testing::Test::RecordProperty("deepest_between_particles_m", sci(on.deepest));
  ::testing::Test::RecordProperty("rows_beside_the_rod_m", sci(on.rows_end));
  EXPECT_GT(on.pushes, 0);
  EXPECT_LE(on.deepest, 0.001);  // the drape's 1 mm bound, between particles too
  // Hanging on the rod: the rows beside it a little under its centre (the
  // cloth falls away on both sides), not fallen.
  EXPECT_GT(on.rows_end, -0.03);
  // Particles alone: the rod passes between them and the cloth falls on.
  const Towel off = drop_on_rod(0.0);
  EXPECT_EQ(off.pushes, 0);
  EXPECT_LT(off.rows_end, -0.5);
  EXPECT_GT(off.deepest, 0.003);  // it went through the rod
}

TEST(BodyCollision, ProvotFrictionDeceleratesPerCoulomb) {
  const double theta = 20.0 * M_PI / 180.0, mu = 0.5, v0 = 2.0, t = 0.5;
  Slope sl = slope(theta, Vec3::Zero(), mu, ContactResponse::provot);
  at(sl.model.v0, 0) = v0 * sl.down;
  const State s = run(sl, t);
  const double a = kG * (std::sin(theta) - mu * std::cos(theta));  // < 0: slows down
  const double expected = v0 + a * t;
  const double got = at(s.v, 0).dot(sl.down);
  RecordProperty("coulomb_expected_m_per_s", sci(expected));
  RecordProperty("coulomb_got_m_per_s", sci(got));
  EXPECT_NEAR(got, expected, 0.03 * expected);
  EXPECT_NEAR(at(s.v, 0).dot(sl.normal), 0.0, 0.02);  // stays on the surface
  EXPECT_NEAR((at(s.x, 0)).dot(sl.normal), 0.1 + sl.def.clearance, 1e-3);
}

TEST(BodyCollision, ProvotFrictionAcceleratesOnASteepSlopePerCoulomb) {
  const double theta = 40.0 * M_PI / 180.0, mu = 0.3, t = 0.3;
  Slope sl = slope(theta, Vec3::Zero(), mu, ContactResponse::provot);
  const State s = run(sl, t);
  const double expected = kG * (std::sin(theta) - mu * std::cos(theta)) * t;
  EXPECT_NEAR(at(s.v, 0).dot(sl.down), expected, 0.03 * expected);
}

TEST(BodyCollision, ProvotFrictionHoldsBelowTheAngleOfRepose) {
  const double theta = 20.0 * M_PI / 180.0;  // tan θ = 0.36 < μ = 1
  Slope sl = slope(theta, Vec3::Zero(), 1.0, ContactResponse::provot);
  const Vec3 start = at(sl.model.x0, 0);
  const State s = run(sl, 0.5);
  EXPECT_LT(at(s.v, 0).norm(), 1e-9);
  EXPECT_LT((at(s.x, 0) - start).dot(sl.down), 1e-4);
}

// A body that moves (BodyCollisionDef::velocity): a particle resting on a
// slab lifted at 0.5 m/s and pushed sideways at 0.2 m/s rides on it — the
// response acts on the velocity relative to the body, friction (μ = 1)
// carries it along — and ends where the slab took it, moving with it. The
// slab at rest keeps it where it was.
TEST(BodyCollision, AMovingBodyCarriesAParticleRestingOnIt) {
  const Vec3 vb(0.2, 0.5, 0.0);
  for (const bool moving : {false, true}) {
    Slope sl = slope(0.0, Vec3::Zero(), 1.0, ContactResponse::provot);
    sl.def.min_bounce_speed = 1.0;  // no bounce off the rising slab
    if (moving) sl.def.velocity = vb;
    const Vec3 start = at(sl.model.x0, 0);
    const double t = 0.5;
    const State s = run(sl, t);
    const Vec3 moved = moving ? Vec3(vb * t) : Vec3::Zero();
    const Vec3 want_v = moving ? vb : Vec3::Zero();
    RecordProperty(moving ? "moving_offset_m" : "static_offset_m", sci((at(s.x, 0) - start - moved).norm()));
    EXPECT_NEAR(at(s.x, 0).y(), start.y() + moved.y(), 1e-3);  // on the slab, at the clearance
    EXPECT_NEAR(at(s.x, 0).x(), start.x() + moved.x(), 5e-3);  // carried by friction (lags its first steps)
    EXPECT_LT((at(s.v, 0) - want_v).norm(), 0.02);
  }
}

TEST(BodyCollision, ProvotBouncesFastImpactsWithRestitution) {
  Slope sl = slope(0.0, Vec3::Zero(), 0.5, ContactResponse::provot);
  at(sl.model.x0, 0) = Vec3(0, 0.1 + 0.02, 0);
  at(sl.model.v0, 0) = Vec3(0, -2.0, 0);
  const State s = run(sl, 0.012, nullptr, false);  // no gravity: one impact
  EXPECT_NEAR(at(s.v, 0).y(), 0.3 * 2.0, 1e-9);
}

TEST(BodyCollision, SlideKeepsTangentialSpeed) {
  Slope sl = slope(0.0, Vec3::Zero(), 0.5, ContactResponse::slide);
  at(sl.model.v0, 0) = Vec3(0, 0, 1.0);  // along the flat surface
  const State s = run(sl, 0.5);
  EXPECT_NEAR(at(s.v, 0).z(), 1.0, 1e-9);  // frictionless
  EXPECT_NEAR(at(s.x, 0).y(), 0.1 + sl.def.clearance, 1e-4);
}

TEST(BodyCollision, SlideCancelsTheInwardNormalForce) {
  Slope sl = slope(0.0, Vec3::Zero(), 0.5, ContactResponse::slide);
  auto e = make_body_collision(sl.model, sl.def);
  ASSERT_TRUE(e->constrains_forces());
  State s = initial_state(sl.model);
  at(s.x, 0).y() -= 0.001;  // inside the clearance
  e->after_step(sl.model, s);
  EXPECT_EQ(body_collision_stats(*e).in_contact, 1);
  VecX f(3);
  f << 1.0, -2.0, 0.5;
  e->constrain_forces({sl.model, 0.0, s.x, s.v}, f);
  EXPECT_NEAR(f[0], 1.0, 1e-12);
  EXPECT_NEAR(f[1], 0.0, 1e-12);
  EXPECT_NEAR(f[2], 0.5, 1e-12);
  f << 1.0, 2.0, 0.0;  // pulling away: untouched
  e->constrain_forces({sl.model, 0.0, s.x, s.v}, f);
  EXPECT_NEAR(f[1], 2.0, 1e-12);
}

TEST(BodyCollision, SeamParticleKeepsItsSpeedAndForceMagnitude) {
  Slope sl = slope(0.0, Vec3::Zero(), 0.5, ContactResponse::slide);
  sl.def.seam_particles = {0};
  at(sl.model.x0, 0) = Vec3(0, 0.1 + 0.004, 0);
  at(sl.model.v0, 0) = Vec3(1.0, -1.0, 0.0);
  const State s = run(sl, 0.01, nullptr, false);
  EXPECT_NEAR(at(s.v, 0).norm(), std::sqrt(2.0), 1e-9);  // |v| kept
  EXPECT_NEAR(at(s.v, 0).y(), 0.0, 1e-9);                // now tangential
  EXPECT_NEAR(at(s.v, 0).x(), std::sqrt(2.0), 1e-9);
  // The force: tangential, with its magnitude.
  auto e = make_body_collision(sl.model, sl.def);
  State s2 = initial_state(sl.model);
  at(s2.x, 0).y() = 0.1 + 0.001;
  e->after_step(sl.model, s2);
  VecX f(3);
  f << 3.0, -4.0, 0.0;
  e->constrain_forces({sl.model, 0.0, s2.x, s2.v}, f);
  EXPECT_NEAR(f.norm(), 5.0, 1e-12);
  EXPECT_NEAR(f[1], 0.0, 1e-12);
}

TEST(BodyCollision, StickyParticleStopsWhereItTouches) {
  // A belt point falling on a sphere with a sideways velocity.
  Model m = test::particles(1, 0.01);
  at(m.x0, 0) = Vec3(0.05, 0.36, 0.0);
  at(m.v0, 0) = Vec3(0.5, 0.0, 0.0);
  BodyCollisionDef def;
  def.body = test::uv_sphere(0.3);
  def.sticky_particles = {0};
  auto coll = make_body_collision(m, def);
  Effect* c = coll.get();
  System sys(m, effects(make_gravity({}), std::move(coll)));
  IntegratorSettings st;
  st.step = 0.001;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  integ->advance(sys, s, 0.5);
  ASSERT_EQ(body_collision_stats(*c).stuck, 1);
  const Vec3 stuck_at = at(s.x, 0);
  EXPECT_EQ(at(s.v, 0).norm(), 0.0);
  EXPECT_NEAR(stuck_at.norm(), 0.3 + def.clearance, 5e-4);  // on the surface (polyhedral sphere)
  integ->advance(sys, s, 1.0);
  EXPECT_EQ(at(s.v, 0).norm(), 0.0);
  EXPECT_LT((at(s.x, 0) - stuck_at).norm(), 1e-12);
}

}  // namespace
}  // namespace vgd::sim
