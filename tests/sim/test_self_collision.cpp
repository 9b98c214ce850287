// Self-collision: a cloth that folds onto itself on the floor ends with no
// triangle through another (exact count, CGAL) and no two particles closer
// than half the thickness.
#include <gtest/gtest.h>

#include "helpers.hpp"
#include "surfaces.hpp"
#include "vgd/mesh/surface_checks.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/body_collision.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/self_collision.hpp"
#include "vgd/sim/integrator.hpp"

namespace vgd::sim {
namespace {

using test::sci;

// One triangle in z = 0 (particles 0, 1, 2, 1 g each) and particle 3 at p.
Model triangle_and_particle(const Vec3& p) {
  Model m = test::particles(4, 0.001);
  at(m.x0, 0) = Vec3(0, 0, 0);
  at(m.x0, 1) = Vec3(0.1, 0, 0);
  at(m.x0, 2) = Vec3(0, 0.1, 0);
  at(m.x0, 3) = p;
  m.triangles = {{0, 1, 2}};
  m.triangle_piece = {0};
  m.pieces = {"p"};
  m.uv = {Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1), Vec2(p.x(), p.y())};
  return m;
}

std::vector<mesh::Vec3> positions(const VecX& x) {
  std::vector<mesh::Vec3> out;
  for (int i = 0; i < x.size() / 3; ++i) out.push_back(at(x, i));
  return out;
}

// Smallest distance between two particles that share no triangle.
double min_pair_distance(const Model& m, const VecX& x) {
  const int n = m.num_particles();
  std::vector<std::vector<int>> near(n);
  for (const auto& t : m.triangles)
    for (int a : t)
      for (int b : t) near[a].push_back(b);
  double best = 1e300;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (std::find(near[i].begin(), near[i].end(), j) != near[i].end()) continue;
      best = std::min(best, (at(x, i) - at(x, j)).norm());
    }
  return best;
}

struct Fold {
  int intersections;
  double min_distance;
  SelfCollisionStats stats;
};

// A 0.4 m square cloth (21 × 21, 2 cm spacing, 1 g particles) held upright and
// slightly tilted over the floor, dropped: it buckles and folds onto itself.
Fold fold(bool self, double thickness = 0.004) {
  constexpr int n = 21;
  constexpr double d = 0.02;
  const Vec3 axis_v = Vec3(0.25, 1.0, 0.0).normalized();  // leaning: it falls to +x
  Model m = make_grid(n, n, d, d, Vec3(0, 0.005, -0.2), Vec3::UnitZ(), axis_v, 0.001);
  MassSpringMaterial mat;
  mat.warp = mat.weft = 40.0;
  mat.shear = 10.0;
  mat.bend_warp = mat.bend_weft = 0.5;  // limp: it folds
  mat.damping = 0.01;
  BodyCollisionDef floor;
  floor.body = test::box(Vec3(1.0, 0.05, 1.0), Mat3::Identity(), Vec3(0, -0.05, 0));
  floor.query = BodyQuery::exact;
  floor.clearance = 0.002;
  std::vector<std::unique_ptr<Effect>> fx;
  fx.push_back(make_mass_spring(m, {mat}));
  fx.push_back(make_gravity({}));
  fx.push_back(make_viscosity({0.0, 0.5}));
  Effect* sc = nullptr;
  if (self) {
    SelfCollisionDef def;
    def.thickness = thickness;
    auto e = make_self_collision(m, def);
    sc = e.get();
    fx.push_back(std::move(e));
  }
  fx.push_back(make_body_collision(m, floor));
  System sys(m, std::move(fx));
  IntegratorSettings st;
  st.step = 0.001;
  st.auto_substep = true;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  integ->advance(sys, s, 1.5);
  Fold out{mesh::count_triangle_intersections(positions(s.x), m.triangles), min_pair_distance(m, s.x), {}};
  if (sc) out.stats = self_collision_stats(*sc);
  return out;
}

TEST(SelfCollision, FoldedClothDoesNotPassThroughItself) {
  const Fold with = fold(true);
  RecordProperty("intersections", with.intersections);
  RecordProperty("min_pair_distance_m", sci(with.min_distance));
  RecordProperty("pairs_in_contact", with.stats.pairs);
  RecordProperty("pairs_total", static_cast<int>(with.stats.pairs_total));
  EXPECT_EQ(with.intersections, 0);
  EXPECT_GE(with.min_distance, 0.004 / 2);
  EXPECT_GT(with.stats.pairs_total, 0);  // it did fold onto itself
}

TEST(SelfCollision, WithoutItTheSameClothPassesThroughItself) {
  // The scene above is a real test: without self-collision it crosses.
  const Fold without = fold(false);
  RecordProperty("intersections_without", without.intersections);
  EXPECT_GT(without.intersections, 0);
}

TEST(SelfCollision, ImpulseStopsAnApproachingParticle) {
  // One triangle in z = 0 and a particle 1 mm above it moving down at 1 m/s.
  Model m = triangle_and_particle(Vec3(0.02, 0.02, 0.001));
  SelfCollisionDef def;
  def.thickness = 0.003;
  auto e = make_self_collision(m, def);
  State s = initial_state(m);
  s.x = m.x0;
  at(s.v, 3) = Vec3(0, 0, -1.0);
  e->after_step(m, s);
  // Equal masses: the particle and the triangle meet at the common normal velocity.
  const Vec3 w(1.0 - 0.2 - 0.2, 0.2, 0.2);
  const double vt = w[0] * at(s.v, 0).z() + w[1] * at(s.v, 1).z() + w[2] * at(s.v, 2).z();
  // (Within the triangle's tilt from the position correction: ~1e-4 m/s.)
  EXPECT_NEAR(at(s.v, 3).z() - vt, 0.0, 2e-4);
  // Momentum conserved along the normal.
  double p = 0;
  for (int i = 0; i < 4; ++i) p += at(s.v, i).z();
  EXPECT_NEAR(p, -1.0, 1e-12);
  // And pushed back to the thickness, on the side it came from.
  const double wp = w[0] * at(s.x, 0).z() + w[1] * at(s.x, 1).z() + w[2] * at(s.x, 2).z();
  EXPECT_NEAR(at(s.x, 3).z() - wp, 0.003, 1e-6);
}

// The repulsion's damping (SelfCollisionDef::damping, a fraction ζ of
// critical): a particle 1 mm over a triangle (within the 3 mm thickness),
// approaching it at 0.5 m/s, is pushed back by the spring and, damped, by
// 2 ζ √(k m) × 0.5 m/s more; the triangle takes the opposite share by
// barycentric weight (no net force), and the velocity Jacobian holds the
// damping for the implicit step.
TEST(SelfCollision, DampedRepulsionTakesOffTheApproach) {
  Model m = triangle_and_particle(Vec3(0.02, 0.02, 0.001));
  State s = initial_state(m);
  s.x = m.x0;
  at(s.v, 3) = Vec3(0, 0, -0.5);
  const auto force = [&](double zeta, Triplets* dfdv) {
    SelfCollisionDef def;
    def.thickness = 0.003;
    def.stiffness = 1.0;
    def.damping = zeta;
    auto e = make_self_collision(m, def);
    VecX f = VecX::Zero(3 * m.num_particles());
    const Eval ev{m, 0.0, s.x, s.v};
    e->add_forces(ev, f);
    Triplets dfdx;
    if (dfdv) e->add_jacobian(ev, dfdx, *dfdv);
    return f;
  };
  const VecX undamped = force(0.0, nullptr);
  EXPECT_NEAR(at(undamped, 3).z(), 1.0 * (0.003 - 0.001), 1e-12) << "k (th - d)";
  Triplets dfdv;
  const VecX damped = force(1.0, &dfdv);
  const double c = 2.0 * std::sqrt(1.0 * 0.001);  // N·s/m: critical for 1 N/m on 1 g
  EXPECT_NEAR(at(damped, 3).z() - at(undamped, 3).z(), c * 0.5, 1e-12);
  Vec3 total = Vec3::Zero();
  for (int i = 0; i < 4; ++i) total += at(damped, i);
  EXPECT_NEAR(total.norm(), 0.0, 1e-12);
  double zz = 0.0;  // the pressed particle's own zz entry of df/dv
  for (const auto& t : dfdv)
    if (t.row() == 3 * 3 + 2 && t.col() == 3 * 3 + 2) zz += t.value();
  EXPECT_NEAR(zz, -c, 1e-12);
  Triplets none;
  force(0.0, &none);
  EXPECT_TRUE(none.empty()) << "no damping, no velocity Jacobian";
}

TEST(SelfCollision, CrossedParticleIsBroughtBack) {
  Model m = test::particles(4, 0.001);
  at(m.x0, 0) = Vec3(0, 0, 0);
  at(m.x0, 1) = Vec3(0.1, 0, 0);
  at(m.x0, 2) = Vec3(0, 0.1, 0);
  at(m.x0, 3) = Vec3(0.02, 0.02, 0.002);  // above, before the step
  m.triangles = {{0, 1, 2}};
  m.uv = {Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1), Vec2(0.02, 0.02)};
  auto e = make_self_collision(m, {});
  State s = initial_state(m);
  e->after_step(m, s);  // remembers the side
  at(s.x, 3).z() = -0.001;  // went through in one step
  e->after_step(m, s);
  EXPECT_EQ(self_collision_stats(*e).crossings, 1);
  const Vec3 w(0.6, 0.2, 0.2);
  const double wp = w[0] * at(s.x, 0).z() + w[1] * at(s.x, 1).z() + w[2] * at(s.x, 2).z();
  EXPECT_NEAR(at(s.x, 3).z() - wp, 0.003, 1e-6);
}

// Layers: a triangle of an outer garment (layer 1) 10 mm over a flat body
// (a box whose top is z = 0) and a particle of the inner garment (layer 0)
// 4 mm outside it — a crossing an earlier step left. With layers the particle
// goes back under the triangle (the body's order); without, the side it came
// from is kept and the crossing stays.
TEST(SelfCollision, LayersPutTheInnerGarmentBackUnderTheOuterOne) {
  const auto body = test::box(Vec3(0.2, 0.2, 0.05), Mat3::Identity(), Vec3(0.05, 0.05, -0.05));
  const SignedDistanceGrid grid(body);
  for (const bool layered : {false, true}) {
    Model m = triangle_and_particle(Vec3(0.02, 0.02, 0.014));
    for (int i = 0; i < 3; ++i) at(m.x0, i).z() = 0.010;
    SelfCollisionDef def;
    def.body = &grid;
    if (layered) def.layer = {1, 1, 1, 0};
    auto e = make_self_collision(m, def);
    State s = initial_state(m);
    e->after_step(m, s);
    const double height = at(s.x, 3).z() - (0.6 * at(s.x, 0).z() + 0.2 * at(s.x, 1).z() + 0.2 * at(s.x, 2).z());
    if (layered) {
      // Within 10 µm: the contact's edge–edge pairs move it by micrometres more.
      EXPECT_NEAR(height, -def.thickness, 1e-5) << "the inner particle belongs under the outer triangle";
      EXPECT_GT(at(s.x, 0).z(), 0.010) << "not held by the body: the outer layer gives way too";
    } else {
      EXPECT_NEAR(height, 0.004, 1e-12) << "without layers the crossing is not seen";
    }
  }
}

// An inner particle the body holds (within held_distance) does not move: the
// outer triangle, pressed through it, is lifted over it instead.
TEST(SelfCollision, TheBodyHoldsTheInnerLayerAndTheOuterGivesWay) {
  const auto body = test::box(Vec3(0.2, 0.2, 0.05), Mat3::Identity(), Vec3(0.05, 0.05, -0.05));
  const SignedDistanceGrid grid(body);
  Model m = triangle_and_particle(Vec3(0.02, 0.02, 0.004));
  for (int i = 0; i < 3; ++i) at(m.x0, i).z() = 0.0035;  // outer layer, 0.5 mm under the inner particle
  SelfCollisionDef def;
  def.body = &grid;
  def.layer = {1, 1, 1, 0};
  auto e = make_self_collision(m, def);
  State s = initial_state(m);
  e->after_step(m, s);
  EXPECT_EQ(at(s.x, 3).z(), 0.004);
  const double tri = 0.6 * at(s.x, 0).z() + 0.2 * at(s.x, 1).z() + 0.2 * at(s.x, 2).z();
  EXPECT_NEAR(tri - 0.004, def.thickness, 1e-5);
}

// Two layers of one garment on a flat body (a box whose top is z = 0): a
// particle 0.5 mm over the body, a triangle 1.5 mm over the particle. The
// correction shares the 1.5 mm missing from the thickness by inverse mass and
// would push the particle 1 mm into the body; with the body given it stays
// out, and the triangle is lifted to the thickness over it instead.
TEST(SelfCollision, CorrectionsDoNotPushClothIntoTheBody) {
  const auto body = test::box(Vec3(0.2, 0.2, 0.05), Mat3::Identity(), Vec3(0.05, 0.05, -0.05));
  const SignedDistanceGrid grid(body);
  for (const bool with_body : {false, true}) {
    Model m = triangle_and_particle(Vec3(0.02, 0.02, 0.0005));
    for (int i = 0; i < 3; ++i) at(m.x0, i).z() = 0.002;
    SelfCollisionDef def;
    if (with_body) def.body = &grid;
    auto e = make_self_collision(m, def);
    State s = initial_state(m);
    e->after_step(m, s);
    const double tri = 0.6 * at(s.x, 0).z() + 0.2 * at(s.x, 1).z() + 0.2 * at(s.x, 2).z();
    if (with_body) {
      EXPECT_GE(at(s.x, 3).z(), -1e-6) << "pushed into the body";
      // The four Gauss–Seidel passes close the gap geometrically, each
      // giving back what the body took: 2.82 of the 3 mm.
      EXPECT_GT(tri - at(s.x, 3).z(), 0.9 * def.thickness) << "the triangle gives way";
    } else {
      EXPECT_LT(at(s.x, 3).z(), -0.0005) << "without the body the particle is pushed into it";
    }
  }
}

// Layers need the body to tell inside from outside.
TEST(SelfCollision, LayersWithoutABodyAreRefused) {
  Model m = triangle_and_particle(Vec3(0.02, 0.02, 0.014));
  SelfCollisionDef def;
  def.layer = {1, 1, 1, 0};
  EXPECT_THROW(make_self_collision(m, def), SimulationError);
  def.layer = {1, 0};
  EXPECT_THROW(make_self_collision(m, def), SimulationError);
}

}  // namespace
}  // namespace vgd::sim

namespace vgd::sim {
namespace {

// A seam pair never collides: particle 3, joined to corner 0 of the triangle
// it approaches, is left alone (a seam could not close otherwise); the same
// particle not joined is stopped and pushed back.
TEST(SelfCollision, JoinedParticlesDoNotCollide) {
  Model m = triangle_and_particle(Vec3(0.02, 0.02, 0.001));
  for (const bool joined : {false, true}) {
    SelfCollisionDef def;
    def.thickness = 0.003;
    if (joined) def.joined = {{3, 0}};
    auto e = make_self_collision(m, def);
    State s = initial_state(m);
    at(s.v, 3) = Vec3(0, 0, -1.0);
    VecX f = VecX::Zero(m.num_dofs());
    e->add_forces({m, 0.0, s.x, s.v}, f);
    e->after_step(m, s);
    if (joined) {
      EXPECT_EQ(at(f, 3).norm(), 0.0);
      EXPECT_EQ(at(s.v, 3).z(), -1.0);
      EXPECT_EQ(at(s.x, 3).z(), 0.001);
    } else {
      EXPECT_GT(at(f, 3).z(), 0.0);
      EXPECT_GT(at(s.v, 3).z(), -0.5);
    }
  }
}

// An edge already through a triangle when the step starts: the corrections
// keep the side each pair started on, so only the history-free untangling
// pulls its nearer end (1 mm under) back over the plane, to the thickness;
// with it off the crossing stays.
TEST(SelfCollision, AnEdgeThroughATriangleAtTheStartIsPulledBack) {
  Model m = test::particles(6, 0.001);
  at(m.x0, 0) = Vec3(0, 0, 0);
  at(m.x0, 1) = Vec3(0.1, 0, 0);
  at(m.x0, 2) = Vec3(0, 0.1, 0);
  at(m.x0, 3) = Vec3(0.02, 0.02, -0.001);  // through: 1 mm under
  at(m.x0, 4) = Vec3(0.02, 0.02, 0.02);    // its edge's other end, 20 mm over
  at(m.x0, 5) = Vec3(0.2, 0.2, 0.02);
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  m.triangle_piece = {0, 0};
  m.pieces = {"p"};
  for (int i = 0; i < 6; ++i) m.uv.push_back(Vec2(at(m.x0, i).x(), at(m.x0, i).y()));
  for (const int passes : {4, 0}) {
    SelfCollisionDef def;
    def.thickness = 0.003;
    def.untangle_passes = passes;
    auto e = make_self_collision(m, def);
    State s = initial_state(m);
    at(s.v, 3) = Vec3(0, 0, -0.1);  // still going down
    e->after_step(m, s);
    const Vec3 w(0.6, 0.2, 0.2);
    const double under = at(s.x, 3).z() - (w[0] * at(s.x, 0).z() + w[1] * at(s.x, 1).z() + w[2] * at(s.x, 2).z());
    if (passes > 0) {
      EXPECT_EQ(self_collision_stats(*e).tangled, 2);  // edges 3–4 and 3–5
      EXPECT_GE(self_collision_stats(*e).untangled, 1);
      EXPECT_NEAR(under, 0.003, 1e-5);  // over the plane, at the thickness (the triangle tilts a little)
      // The approach is stopped: no relative velocity into the triangle left.
      const double vt = w[0] * at(s.v, 0).z() + w[1] * at(s.v, 1).z() + w[2] * at(s.v, 2).z();
      EXPECT_GE(at(s.v, 3).z() - vt, -1e-12);
    } else {
      EXPECT_LT(under, 0.0);  // left through
      EXPECT_EQ(self_collision_stats(*e).untangled, 0);
    }
  }
}

// Seam hems are exempt from colliding with each other while seams close;
// once every seam pair is one particle they are ordinary cloth: particle 3
// (a hem, falling through a triangle with a hem corner) passes before the
// merge and is stopped after it.
TEST(SelfCollision, SewnHemsCollideOnceEverySeamIsSewn) {
  Model m = test::particles(6, 0.001);
  at(m.x0, 0) = Vec3(0, 0, 0);
  at(m.x0, 1) = Vec3(0.1, 0, 0);
  at(m.x0, 2) = Vec3(0, 0.1, 0);
  at(m.x0, 3) = Vec3(0.02, 0.02, 0.002);
  at(m.x0, 4) = at(m.x0, 3);  // 3's seam partner
  at(m.x0, 5) = at(m.x0, 0);  // 0's seam partner
  // (4, 5, 1): the partners' triangle, so that both hems are of one garment.
  m.triangles = {{0, 1, 2}, {4, 5, 1}};
  m.triangle_piece = {0, 0};
  m.pieces = {"p"};
  for (int i = 0; i < 6; ++i) m.uv.push_back(Vec2(at(m.x0, i).x(), at(m.x0, i).y()));
  for (const bool sewn : {false, true}) {
    SelfCollisionDef def;
    def.thickness = 0.003;
    def.joined = {{3, 4}, {0, 5}};
    auto e = make_self_collision(m, def);
    if (sewn) e->particles_merged(m, {0, 1, 2, 3, 3, 0});
    State s = initial_state(m);
    e->after_step(m, s);      // remembers the side: over
    at(s.x, 3).z() = -0.001;  // through in one step
    at(s.x, 4) = at(s.x, 3);
    e->after_step(m, s);
    if (sewn)
      EXPECT_GT(at(s.x, 3).z(), 0.0) << "a sewn hem is ordinary cloth";
    else
      EXPECT_EQ(at(s.x, 3).z(), -0.001) << "an open seam's hem passes";
  }
}

// After a merge the copies of one particle are one: no collision between them.
TEST(SelfCollision, MergedCopiesDoNotCollide) {
  Model m = triangle_and_particle(Vec3(0.0, 0.0, 0.0005));
  SelfCollisionDef def;
  def.thickness = 0.003;
  auto e = make_self_collision(m, def);
  e->particles_merged(m, {0, 1, 2, 0});
  State s = initial_state(m);
  VecX f = VecX::Zero(m.num_dofs());
  e->add_forces({m, 0.0, s.x, s.v}, f);
  EXPECT_EQ(f.norm(), 0.0);
}

}  // namespace
}  // namespace vgd::sim
