// Seams that sew and merge (seed 002 §3.3): the seam force law and its
// Jacobian, merges in the System's coordinates (mass, Σ m x and momentum kept,
// the same accelerations as a model built merged), frames in the original
// particle set, every integrator re-prepared after merges, corners, pins,
// progress.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/seam.hpp"
#include "vgd/sim/run.hpp"
#include "vgd/sim/topology.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

// Two nu × nv grids (cells of 0.1 m) in the z = 0 plane, B to the right of A
// with `gap` (m) between A's right column and B's left column. B's material
// coordinates continue A's (u from (nu − 1) · 0.1 m). Particles: A's first.

// A's right column with B's left column.
SeamPairs side_seam(int nu, int nv) {
  SeamPairs s{"side", {}};
  for (int j = 0; j < nv; ++j) s.pairs.push_back({j * nu + nu - 1, nu * nv + j * nu});
  return s;
}

Vec3 momentum(const VecX& mass, const VecX& v) {
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < mass.size(); ++i) p += mass[i] * at(v, i);
  return p;
}
Vec3 first_moment(const VecX& mass, const VecX& x) { return momentum(mass, x); }

}  // namespace

// ---- the force law ----------------------------------------------------------------

TEST(Seam, ForceFollowsTheLinearAndTheSaturatingLaw) {
  Model m = particles(2, 0.01, 0.3);
  for (SeamLaw law : {SeamLaw::linear, SeamLaw::saturating}) {
    SeamDef def;
    def.law = law;
    def.stiffness = 2.0;
    def.max_force = 0.1;
    def.damping = 0.0;
    def.seams = {{"s", {{0, 1}}}};
    auto e = make_seam(m, def);
    const VecX f = forces(*e, m, m.x0);
    const double expect = law == SeamLaw::linear ? 2.0 * 0.3 : 0.1 * std::tanh(2.0 * 0.3 / 0.1);
    EXPECT_NEAR(seam_force(def, 0.3), expect, 1e-15);
    EXPECT_NEAR(f[0], expect, 1e-15);   // particle 0 at x = 0 is pulled towards particle 1 at x = 0.3
    EXPECT_NEAR(f[3], -expect, 1e-15);
    EXPECT_NEAR(f.sum(), 0.0, 1e-15);   // momentum kept
  }
  // Near closing the saturating law is the linear spring.
  SeamDef def;
  EXPECT_NEAR(seam_force(def, 1e-4) / (def.stiffness * 1e-4), 1.0, 1e-5);  // tanh x / x = 1 − x²/3, x = 0.002
  EXPECT_LE(seam_force(def, 10.0), def.max_force);
}

TEST(Seam, JacobianMatchesFiniteDifferences) {
  Model m = particles(4, 0.01, 0.05);
  std::srand(3);
  m.x0 += 0.02 * VecX::Random(m.num_dofs());
  const VecX v = VecX::Random(m.num_dofs());
  for (SeamLaw law : {SeamLaw::linear, SeamLaw::saturating}) {
    SeamDef def;
    def.law = law;
    def.stiffness = 3.0;
    def.max_force = 0.05;
    def.damping = 0.2;
    def.seams = {{"a", {{0, 1}, {2, 3}}}, {"b", {{1, 2}}}};
    auto e = make_seam(m, def);
    Triplets tx, tv;
    ASSERT_TRUE(e->add_jacobian({m, 0.0, m.x0, v}, tx, tv));
    SparseMatrix K(m.num_dofs(), m.num_dofs()), D(m.num_dofs(), m.num_dofs());
    K.setFromTriplets(tx.begin(), tx.end());
    D.setFromTriplets(tv.begin(), tv.end());
    const double h = 1e-6;
    double worst = 0.0;
    for (int c = 0; c < m.num_dofs(); ++c) {
      VecX xp = m.x0, xm = m.x0, vp = v, vm = v;
      xp[c] += h, xm[c] -= h, vp[c] += h, vm[c] -= h;
      const VecX dfx = (forces(*e, m, xp, v) - forces(*e, m, xm, v)) / (2 * h);
      const VecX dfv = (forces(*e, m, m.x0, vp) - forces(*e, m, m.x0, vm)) / (2 * h);
      worst = std::max(worst, (dfx - VecX(K.col(c))).lpNorm<Eigen::Infinity>() / def.stiffness);
      worst = std::max(worst, (dfv - VecX(D.col(c))).lpNorm<Eigen::Infinity>() / def.damping);
    }
    EXPECT_LT(worst, 1e-7) << "law " << static_cast<int>(law);
  }
}

TEST(Seam, StiffnessBoundIsTwiceKAndC) {
  Model m = particles(2);
  SeamDef def;
  def.stiffness = 5.0;
  def.damping = 0.5;
  def.seams = {{"s", {{0, 1}}}};
  System sys(m, effects(make_seam(m, def)));
  EXPECT_DOUBLE_EQ(sys.stiffness().omega2, 10.0);       // 2k/m, m = 1 kg
  EXPECT_DOUBLE_EQ(sys.stiffness().damping_rate, 1.0);  // 2c/m
  EXPECT_EQ(sys.stiffness().effect, "seam");
}

TEST(Seam, BadDefinitionsAreRefusedNamingTheSeamAndPair) {
  Model m = particles(3);
  SeamDef def;
  def.seams = {{"collar", {{0, 1}, {2, 7}}}};
  try {
    make_seam(m, def);
    FAIL();
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("('collar'), pair 1 names particle 7"), std::string::npos) << e.what();
  }
  def.seams = {{"x", {{1, 1}}}};
  EXPECT_THROW(make_seam(m, def), SimulationError);
  def.seams = {};
  def.stiffness = -1;
  EXPECT_THROW(make_seam(m, def), SimulationError);
}

// ---- merging in the System ---------------------------------------------------------

TEST(SeamMerge, MergeKeepsMassFirstMomentAndMomentumExactly) {
  const int nu = 3, nv = 4;
  const Model m = test::two_grids(nu, nv, 0.001, 0.01, 0.03);  // the gap is below merge_distance
  SeamDef def;
  def.seams = {side_seam(nu, nv)};
  System sys(m, effects(make_mass_spring(m, {soft_cloth()}), make_seam(m, def)));
  State s = initial_state(m);
  std::srand(7);
  s.v = VecX::Random(m.num_dofs());
  const double mass0 = m.mass.sum();
  const Vec3 p0 = momentum(m.mass, s.v), x0 = first_moment(m.mass, s.x);
  ASSERT_TRUE(sys.apply_merges(s));
  EXPECT_EQ(sys.num_particles(), m.num_particles() - nv);
  EXPECT_EQ(sys.num_particles_full(), m.num_particles());
  EXPECT_EQ(s.x.size(), sys.num_dofs());
  EXPECT_NEAR(sys.mass().sum(), mass0, 1e-15);
  EXPECT_NEAR((momentum(sys.mass(), s.v) - p0).norm(), 0.0, 1e-14);
  EXPECT_NEAR((first_moment(sys.mass(), s.x) - x0).norm(), 0.0, 1e-14);
  // A merged particle weighs what its copies weighed.
  const int a = nu - 1, b = nu * nv;
  EXPECT_EQ(sys.representative()[a], sys.representative()[b]);
  EXPECT_DOUBLE_EQ(sys.mass()[sys.representative()[a]], 0.04);
  // Nothing more to merge.
  EXPECT_FALSE(sys.apply_merges(s));
  // The expanded state puts both copies at one place.
  const VecX full = sys.expand(s.x);
  EXPECT_EQ(full.size(), m.num_dofs());
  EXPECT_EQ(at(full, a), at(full, b));
  // The mass-spring effect dropped the seam line's duplicate springs: nv − 1
  // weft springs and nv − 2 weft bending springs of B's left column.
  const MassSpringStats* st = mass_spring_stats(*sys.effects()[0]);
  ASSERT_NE(st, nullptr);
  const int springs_one = mass_spring_topology(make_grid(nu, nv, 0.1, 0.1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1),
                                               {soft_cloth()}).size();
  EXPECT_EQ(st->springs, 2 * springs_one - (nv - 1) - (nv - 2));
}

TEST(SeamMerge, MergedSystemGivesTheAccelerationsOfAModelBuiltMerged) {
  // Two 2 × 2 grids sewn along one edge = a 3 × 2 grid whose middle column
  // weighs both pieces' particles. Bending springs (none in a 2 × 2 piece)
  // and spring damping are off so that the one-piece lattice of the hand-built
  // model has exactly the merged system's springs.
  MassSpringMaterial mat = soft_cloth();
  mat.bend_warp = mat.bend_weft = 0.0;
  mat.damping = 0.0;
  const Model m = test::two_grids(2, 2, 0.001, 0.01, 0.02);
  SeamDef def;
  def.seams = {side_seam(2, 2)};  // (1, 4), (3, 6)
  System sys(m, effects(make_mass_spring(m, {mat}), make_damping(m, {0.3}), make_gravity({}), make_seam(m, def)));
  State s = initial_state(m);
  ASSERT_TRUE(sys.apply_merges(s));
  ASSERT_EQ(sys.num_particles(), 6);

  // By hand: particles 0, 1+4, 2, 3+6, 5, 7 (the reduced order: lowest copy first).
  Model h;
  h.x0.resize(18);
  h.v0 = VecX::Zero(18);
  h.mass.resize(6);
  h.mass << 0.01, 0.03, 0.01, 0.03, 0.02, 0.02;
  h.uv = {Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1), Vec2(0.1, 0.1), Vec2(0.2, 0), Vec2(0.2, 0.1)};
  for (int i = 0; i < 6; ++i) at(h.x0, i) << h.uv[i].x(), h.uv[i].y(), 0.0;
  h.triangles = {{0, 1, 3}, {0, 3, 2}, {1, 4, 5}, {1, 5, 3}};
  h.triangle_piece = {0, 0, 0, 0};
  h.pieces = {"merged"};
  System hand(h, effects(make_mass_spring(h, {mat}), make_damping(h, {0.3}), make_gravity({})));

  std::srand(11);
  const VecX x = h.x0 + 0.01 * VecX::Random(18), v = VecX::Random(18);
  VecX a1, a2;
  sys.acceleration(0.0, x, v, a1);
  hand.acceleration(0.0, x, v, a2);
  EXPECT_LT((a1 - a2).norm(), 1e-12 * a2.norm()) << (a1 - a2).transpose();
  SparseMatrix k1, d1, k2, d2;
  sys.jacobian(0.0, x, v, k1, d1);
  hand.jacobian(0.0, x, v, k2, d2);
  EXPECT_LT((k1 - k2).norm(), 1e-12 * k2.norm());
  EXPECT_LT((d1 - d2).norm(), 1e-12 * d2.norm());
  EXPECT_NEAR(sys.kinetic_energy(v), hand.kinetic_energy(v), 1e-15);
}

TEST(SeamMerge, ThreePiecesMeetAtACornerAndPinsFollowTheirMergedParticle) {
  // Three triangles around a corner c: A = (cA, a1, a2), B = (cB, b1, b2),
  // C = (cC, c1, c2). Seams: A–B (cA, cB), (a2, b1); B–C (cB, cC), (b2, c1);
  // C–A (cC, cA), (c2, a1): a closed fan of three triangles.
  Model m;
  const double r = 0.1, pi = 3.14159265358979323846;
  std::vector<Vec3> pts;
  for (int k = 0; k < 3; ++k) {
    const double t0 = 2 * pi * k / 3, t1 = 2 * pi * (k + 1) / 3;
    const Vec3 shift = 1e-4 * Vec3(std::cos(t0 + pi / 3), std::sin(t0 + pi / 3), 0);  // within merge_distance
    pts.push_back(shift);
    pts.push_back(shift + r * Vec3(std::cos(t0), std::sin(t0), 0));
    pts.push_back(shift + r * Vec3(std::cos(t1), std::sin(t1), 0));
  }
  m.x0.resize(27);
  for (int i = 0; i < 9; ++i) at(m.x0, i) = pts[i];
  m.v0 = VecX::Zero(27);
  m.mass = VecX::Constant(9, 0.01);
  for (int i = 0; i < 9; ++i) m.uv.push_back(Vec2(pts[i].x(), pts[i].y()));
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  SeamDef def;
  def.seams = {{"AB", {{0, 3}, {2, 4}}}, {"BC", {{3, 6}, {5, 7}}}, {"CA", {{6, 0}, {8, 1}}}};
  PinDef pins;
  pins.particles = {3};  // B's corner
  System sys(m, effects(make_pins(m, pins), make_seam(m, def)));
  State s = initial_state(m);
  ASSERT_TRUE(sys.apply_merges(s));
  EXPECT_EQ(sys.num_particles(), 4);
  const auto& rep = sys.representative();
  EXPECT_EQ(rep[0], rep[3]);
  EXPECT_EQ(rep[3], rep[6]);
  EXPECT_DOUBLE_EQ(sys.mass()[rep[0]], 0.03);
  // The corner is pinned (B's pin) and sits where the pin holds it.
  EXPECT_EQ(sys.free_dofs()[3 * rep[0]], 0.0);
  EXPECT_EQ(at(s.x, rep[0]), pts[3]);
  const MeshCheck c = check_merged_mesh(merged_topology(m, rep));
  EXPECT_TRUE(c.ok());
  EXPECT_EQ(c.interior_edges, 3);
  EXPECT_EQ(c.boundary_edges, 3);
  const SeamReport* rp = seam_report(*sys.effects()[1]);
  ASSERT_NE(rp, nullptr);
  EXPECT_EQ(rp->total.closed, 6);
  EXPECT_TRUE(sys.effects()[1]->finished());
}

TEST(SeamMerge, TwoPinnedParticlesAreNeverMerged) {
  Model m = particles(3, 0.01, 0.001);  // all within merge_distance of their neighbours
  SeamDef def;
  def.seams = {{"s", {{0, 1}, {1, 2}}}};
  PinDef pins;
  pins.particles = {0, 2};
  System sys(m, effects(make_pins(m, pins), make_seam(m, def)));
  State s = initial_state(m);
  ASSERT_TRUE(sys.apply_merges(s));
  EXPECT_EQ(sys.num_particles(), 2);  // 1 joins 0; 2 cannot join the pinned 0+1
  EXPECT_EQ(sys.representative()[0], sys.representative()[1]);
  EXPECT_NE(sys.representative()[1], sys.representative()[2]);
  EXPECT_EQ(seam_report(*sys.effects()[1])->total.closed, 1);
}

// ---- sewing runs -------------------------------------------------------------------

namespace {
struct Sewn {
  RunSummary summary;
  int particles = 0;
  MemorySink frames;
  SeamReport report;
  MeshCheck mesh;
  VecX mass;
  Vec3 momentum_end;
};

Sewn sew(const IntegratorSettings& st, int nu = 3, int nv = 4, double gap = 0.05) {
  const Model m = test::two_grids(nu, nv, gap);
  SeamDef def;
  def.law = SeamLaw::linear;
  def.stiffness = 1.0;
  def.damping = 0.25;  // about critical for the two pieces' relative motion
  def.seams = {side_seam(nu, nv)};
  System sys(m, effects(make_mass_spring(m, {soft_cloth()}), make_seam(m, def)));
  auto integ = make_integrator(st);
  State s = initial_state(m);
  Sewn out;
  out.summary = run(sys, *integ, s, {30.0, 2.0}, {&out.frames});
  out.particles = sys.num_particles();
  out.report = *seam_report(*sys.effects()[1]);
  out.mesh = check_merged_mesh(merged_topology(m, sys.representative()));
  out.mass = sys.mass();
  out.momentum_end = momentum(sys.mass(), s.v);
  return out;
}
}  // namespace

class SeamRun : public ::testing::TestWithParam<Method> {};

TEST_P(SeamRun, AllPairsMergeAndFramesKeepTheOriginalParticles) {
  IntegratorSettings st;
  st.method = GetParam();
  st.step = 0.002;
  const int nu = 3, nv = 4;
  const Sewn r = sew(st, nu, nv);
  ASSERT_TRUE(r.summary.ok) << r.summary.error;
  EXPECT_EQ(r.particles, 2 * nu * nv - nv);
  EXPECT_EQ(r.report.total.closed, nv);
  EXPECT_EQ(r.report.total.total, nv);
  ASSERT_EQ(r.report.seams.size(), 1u);
  EXPECT_EQ(r.report.seams[0].name, "side");
  EXPECT_EQ(r.report.seams[0].closed, nv);
  EXPECT_EQ(r.report.total.max_gap, 0.0);
  EXPECT_NEAR(r.mass.sum(), 2 * nu * nv * 0.01, 1e-15);
  EXPECT_LT(r.momentum_end.norm(), 1e-12);  // internal forces only: momentum stays 0
  // The seam line became interior: 2 (nv − 1) boundary edges gone, nv − 1 interior ones more.
  EXPECT_TRUE(r.mesh.ok());
  EXPECT_EQ(r.mesh.boundary_edges, 2 * (2 * (nu - 1) + 2 * (nv - 1)) - 2 * (nv - 1));
  // Every frame has every original particle; merged copies are at one place.
  ASSERT_EQ(r.frames.frames.size(), 61u);
  for (const VecX& f : r.frames.frames) ASSERT_EQ(f.size(), 3 * 2 * nu * nv);
  const VecX& last = r.frames.frames.back();
  for (int j = 0; j < nv; ++j) EXPECT_EQ(at(last, j * nu + nu - 1), at(last, nu * nv + j * nu));
  // In the first frame the pieces were apart.
  EXPECT_NEAR((at(r.frames.frames[0], nu - 1) - at(r.frames.frames[0], nu * nv)).norm(), 0.05, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Integrators, SeamRun,
                         ::testing::Values(Method::symplectic_euler, Method::rk4, Method::implicit_euler, Method::bdf),
                         [](const auto& p) {
                           std::string s = to_string(p.param);
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

TEST(SeamRun, ProgressCountsOpenPairsAndTheirGapsWhenMergingIsOff) {
  const int nu = 3, nv = 4;
  const Model m = test::two_grids(nu, nv, 0.05);
  SeamDef def;
  def.merge = false;
  def.damping = 0.25;
  def.stiffness = 1.0;
  def.seams = {side_seam(nu, nv)};
  System sys(m, effects(make_mass_spring(m, {soft_cloth()}), make_seam(m, def)));
  const SeamReport* rp = seam_report(*sys.effects()[1]);
  EXPECT_EQ(rp->total.closed, 0);
  EXPECT_NEAR(rp->total.max_gap, 0.05, 1e-12);
  EXPECT_NEAR(rp->total.mean_gap, 0.05, 1e-12);
  auto integ = make_integrator({});
  State s = initial_state(m);
  const auto r = run(sys, *integ, s, {30.0, 0.5}, {});
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(sys.num_particles(), m.num_particles());
  EXPECT_EQ(rp->total.closed, 0);
  EXPECT_GT(rp->total.max_gap, 0.0);
  EXPECT_LT(rp->total.max_gap, 0.05);  // pulled closer
  EXPECT_LE(rp->total.mean_gap, rp->total.max_gap);
  EXPECT_FALSE(sys.effects()[1]->finished());
}

// The last open pair of a seam that has stopped closing merges once it has
// stalled for last_stitch_frames frames within last_stitch_distance; before
// that, beyond that distance, or with the rule off, it is left open.
TEST(SeamMerge, TheLastStalledPairOfASeamMergesAfterItsFrames) {
  Model m = test::particles(4, 0.001);
  at(m.x0, 0) = Vec3(0, 0, 0), at(m.x0, 1) = Vec3(0.001, 0, 0);     // within the merge distance
  at(m.x0, 2) = Vec3(0, 0.1, 0), at(m.x0, 3) = Vec3(0.03, 0.1, 0);  // 3 cm apart, held there
  const State s = initial_state(m);
  // Frames until the stalled pair (2, 3) is asked to merge; -1 for never (30 frames).
  auto frames_until_last = [&](double distance) {
    SeamDef def;
    def.seams = {SeamPairs{"side", {{0, 1}, {2, 3}}}};
    def.last_stitch_distance = distance;
    def.last_stitch_frames = 10;
    auto e = make_seam(m, def);
    for (int frame = 1; frame <= 30; ++frame) {
      std::vector<std::array<int, 2>> out;
      e->merge_requests(m, s, out);
      for (const auto& pair : out)
        if (pair == std::array<int, 2>{2, 3}) return frame;
      if (frame == 1) {
        EXPECT_EQ(out, (std::vector<std::array<int, 2>>{{0, 1}}));
        e->particles_merged(m, {0, 0, 1, 2});  // the close pair merged: (2, 3) is the seam's last
      }
    }
    return -1;
  };
  EXPECT_EQ(frames_until_last(0.05), 10);  // no nearer than at the start from the first frame: ten in a row
  EXPECT_EQ(frames_until_last(0.02), -1);  // farther than the last stitch reaches
  EXPECT_EQ(frames_until_last(0.0), -1);   // off
}

// ---- seams in order ----------------------------------------------------------------

// A seam that waits for others (SeamPairs::after: a sleeve's cap for its
// underarm seam) exerts no force and has no energy until every pair of those
// has merged, then pulls by its law; with a wait limit it pulls from that
// time on whatever the others do. Release happens at frame boundaries.
TEST(SeamOrder, ASeamWaitsUntilTheSeamsItIsAfterHaveClosed) {
  Model m = test::particles(4, 0.001);
  at(m.x0, 0) = Vec3(0, 0, 0), at(m.x0, 1) = Vec3(0.001, 0, 0);     // "underarm": within the merge distance
  at(m.x0, 2) = Vec3(0, 0.1, 0), at(m.x0, 3) = Vec3(0.03, 0.1, 0);  // "armhole": 3 cm apart
  SeamDef def;
  def.damping = 0.0;
  def.seams = {SeamPairs{"underarm", {{0, 1}}, {}}, SeamPairs{"armhole", {{2, 3}}, {0}}};
  auto e = make_seam(m, def);
  const VecX v = VecX::Zero(m.num_dofs());
  const SeamReport* r = seam_report(*e);
  EXPECT_FALSE(r->seams[0].waiting);
  EXPECT_TRUE(r->seams[1].waiting);
  VecX f = forces(*e, m, m.x0, v);
  EXPECT_EQ(at(f, 2), Vec3::Zero());
  EXPECT_EQ(at(f, 3), Vec3::Zero());
  EXPECT_GT(at(f, 0).x(), 0.0);  // the underarm pulls
  const double underarm_energy = e->energy({m, 0.0, m.x0, v});
  EXPECT_GT(underarm_energy, 0.0);
  EXPECT_LT(underarm_energy, seam_force(def, 0.001) * 0.001);  // ∫₀^d φ < φ(d) d: the underarm's alone
  Triplets dx, dv;
  e->add_jacobian({m, 0.0, m.x0, v}, dx, dv);
  for (const auto& t : dx) EXPECT_LT(t.row(), 6);  // blocks of particles 0 and 1 only
  // Frame boundary: the underarm's pair merges; the armhole pulls from then on.
  std::vector<std::array<int, 2>> out;
  e->merge_requests(m, initial_state(m), out);
  EXPECT_EQ(out, (std::vector<std::array<int, 2>>{{0, 1}}));
  EXPECT_TRUE(r->seams[1].waiting);
  e->particles_merged(m, {0, 0, 1, 2});
  EXPECT_FALSE(r->seams[1].waiting);
  f = forces(*e, m, m.x0, v);
  EXPECT_NEAR(at(f, 2).x(), seam_force(def, 0.03), 1e-15);
  EXPECT_NEAR(at(f, 3).x(), -seam_force(def, 0.03), 1e-15);

  // The underarm never closes (5 cm apart, no merge): with a wait limit of
  // 0.5 s the armhole pulls from the first frame boundary at or after 0.5 s.
  at(m.x0, 1) = Vec3(0.05, 0, 0);
  def.wait_limit = 0.5;
  auto late = make_seam(m, def);
  const SeamReport* rl = seam_report(*late);
  for (const double t : {0.0, 0.25, 0.49}) {
    out.clear();
    late->merge_requests(m, State{t, m.x0, v}, out);
    EXPECT_TRUE(out.empty());
    EXPECT_TRUE(rl->seams[1].waiting) << t;
    EXPECT_EQ(at(forces(*late, m, m.x0, v, t + 0.01), 2), Vec3::Zero()) << t;
  }
  late->merge_requests(m, State{0.5, m.x0, v}, out);
  EXPECT_FALSE(rl->seams[1].waiting);
  EXPECT_NEAR(at(forces(*late, m, m.x0, v, 0.5), 2).x(), seam_force(def, 0.03), 1e-15);
}

TEST(SeamOrder, WaitingForAMissingSeamOrForItselfIsRefused) {
  Model m = test::particles(6);
  SeamDef def;
  auto refused = [&](const std::string& expect) {
    try {
      make_seam(m, def);
      ADD_FAILURE() << "accepted; expected: " << expect;
    } catch (const SimulationError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  };
  def.seams = {SeamPairs{"cap", {{0, 1}}, {3}}};
  refused("seam 0 ('cap') waits for seam 3, but the seams are 0 to 0");
  def.seams = {SeamPairs{"cap", {{0, 1}}, {0}}};
  refused("seam 0 ('cap') waits for itself");
  def.seams = {SeamPairs{"a", {{0, 1}}, {}}, SeamPairs{"b", {{2, 3}}, {2}}, SeamPairs{"c", {{4, 5}}, {1}}};
  refused("waits for it in turn");
  def.seams = {SeamPairs{"a", {{0, 1}}, {}}, SeamPairs{"b", {{2, 3}}, {0}}, SeamPairs{"c", {{4, 5}}, {1}}};
  EXPECT_NO_THROW(make_seam(m, def));  // c after b after a
  def.seams = {SeamPairs{"a", {{0, 1}}, {}}, SeamPairs{"b", {{2, 3}}, {0}}};
  def.wait_limit = -1.0;
  refused("wait_limit = -1 s");
  def.wait_limit = 0.0;
  EXPECT_NO_THROW(make_seam(m, def));
}
