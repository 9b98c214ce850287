// Offset contact (sim/effects/contact.hpp): its distances against sampled
// minima, and its promise checked exactly (CGAL) after every step: a cloth
// folding onto itself on the floor, a cloth dropped across a rod thinner than
// its mesh, two sheets pressed together on a sphere; with the energy after
// every step at 5 and 10 ms.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "helpers.hpp"
#include "surfaces.hpp"
#include "vgd/mesh/surface_checks.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/contact.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/seam.hpp"
#include "vgd/sim/integrator.hpp"

namespace vgd::sim {
namespace {

using test::effects;
using test::sci;

// ---- distances --------------------------------------------------------------------

TEST(ContactDistance, PointTriangleAndSegmentsMatchDenseSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto rnd = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  constexpr int kSamples = 200;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p = rnd(), a = rnd(), b = rnd(), c = rnd();
    Vec3 w;
    const double d = point_triangle_distance(p, a, b, c, w);
    double sampled = 1e300;
    for (int i = 0; i <= kSamples; ++i)
      for (int j = 0; i + j <= kSamples; ++j) {
        const double s = double(i) / kSamples, t = double(j) / kSamples;
        sampled = std::min(sampled, (p - (a + s * (b - a) + t * (c - a))).norm());
      }
    ASSERT_LE(d, sampled + 1e-12) << trial;
    // Exactly: the projection onto the plane when it falls inside, else the
    // nearest edge (each by a ternary search: the distance is convex along it).
    const auto to_segment = [](const Vec3& x, const Vec3& s0, const Vec3& s1) {
      const double len2 = (s1 - s0).squaredNorm();
      const double t = len2 > 0 ? std::clamp((x - s0).dot(s1 - s0) / len2, 0.0, 1.0) : 0.0;
      return (x - (s0 + t * (s1 - s0))).norm();
    };
    double exact = std::min({to_segment(p, a, b), to_segment(p, b, c), to_segment(p, c, a)});
    const Vec3 nrm = (b - a).cross(c - a).normalized();
    const Vec3 foot = p - (p - a).dot(nrm) * nrm;
    const bool inside = ((b - a).cross(foot - a)).dot(nrm) >= 0 && ((c - b).cross(foot - b)).dot(nrm) >= 0 &&
                        ((a - c).cross(foot - c)).dot(nrm) >= 0;
    if (inside) exact = std::min(exact, std::abs((p - a).dot(nrm)));
    ASSERT_NEAR(d, exact, 1e-12) << trial;
    EXPECT_NEAR((p - (w[0] * a + w[1] * b + w[2] * c)).norm(), d, 1e-12);
    EXPECT_NEAR(w.sum(), 1.0, 1e-12);
    EXPECT_GE(w.minCoeff(), -1e-12);

    const Vec3 q0 = rnd(), q1 = rnd();
    // One in four pairs parallel, one in eight with a point for a segment.
    const Vec3 q1p = trial % 4 == 0 ? q0 + 0.7 * (b - a) : trial % 8 == 1 ? q0 : q1;
    double s, t;
    const double e = segment_distance(a, b, q0, q1p, s, t);
    double sampled_e = 1e300;
    for (int i = 0; i <= 2000; ++i)
      for (int j = 0; j <= 20; ++j) {
        const Vec3 x = a + (i / 2000.0) * (b - a), y = q0 + (j / 20.0) * (q1p - q0);
        sampled_e = std::min(sampled_e, (x - y).norm());
      }
    ASSERT_LE(e, sampled_e + 1e-12) << trial;
    {
      // Exactly: along the first segment the distance to the second is convex.
      const auto to_second = [&](double x) {
        const Vec3 px = a + x * (b - a);
        const double len2 = (q1p - q0).squaredNorm();
        const double y = len2 > 0 ? std::clamp((px - q0).dot(q1p - q0) / len2, 0.0, 1.0) : 0.0;
        return (px - (q0 + y * (q1p - q0))).norm();
      };
      double lo = 0.0, hi = 1.0;
      for (int it = 0; it < 200; ++it) {
        const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        (to_second(m1) < to_second(m2) ? hi : lo) = (to_second(m1) < to_second(m2) ? m2 : m1);
      }
      ASSERT_NEAR(e, to_second(0.5 * (lo + hi)), 1e-9) << trial;
    }
    EXPECT_NEAR((a + s * (b - a) - (q0 + t * (q1p - q0))).norm(), e, 1e-12);
  }
}

// ---- the promise, step by step ---------------------------------------------------

std::vector<mesh::Vec3> positions(const VecX& x) {
  std::vector<mesh::Vec3> out;
  for (int i = 0; i < x.size() / 3; ++i) out.push_back(at(x, i));
  return out;
}

// Crossing triangle pairs of the cloth with itself and with the body (one
// mesh: the body's triangles after the cloth's).
int crossings(const VecX& x, const Model& m, const mesh::SurfaceMesh& body) {
  std::vector<mesh::Vec3> v = positions(x);
  std::vector<std::array<int, 3>> t = m.triangles;
  const int n = static_cast<int>(v.size());
  v.insert(v.end(), body.vertices.begin(), body.vertices.end());
  for (const auto& b : body.triangles) t.push_back({b[0] + n, b[1] + n, b[2] + n});
  return mesh::count_triangle_intersections(v, t);
}

struct Trace {
  int steps = 0;
  int worst_crossings = 0;     // the most crossing pairs after any step
  double deepest = 0.0;        // m: the deepest any particle was inside the body after any step
  double largest_gain = 0.0;   // J: the largest rise of the total energy over one step
  double largest_mechanical_gain = 0.0;  // J: the same without the contact's stored energy
  double start_energy = 0.0, end_energy = 0.0;
  ContactStats stats;
  VecX end_x;                  // m: positions after the last step
};

// Steps `sys` by implicit Euler at h for `seconds`, checking after each step.
Trace run(System& sys, const Effect& contact, const mesh::SurfaceMesh& body, double h, double seconds) {
  IntegratorSettings st;
  st.method = Method::implicit_euler;
  st.step = h;
  auto integ = make_integrator(st);
  State s = initial_state(sys.model());
  integ->prepare(sys, s);
  auto energy = [&] { return sys.kinetic_energy(s.v) + sys.potential_energy(s.t, s.x, s.v); };
  auto stored = [&] { return contact.energy({sys.model(), s.t, s.x, s.v}); };
  Trace tr;
  double mech_prev = 0.0;
  tr.start_energy = tr.end_energy = energy();
  mech_prev = tr.start_energy - stored();
  for (int k = 1; k * h <= seconds + 1e-12; ++k) {
    integ->advance(sys, s, k * h);
    ++tr.steps;
    tr.worst_crossings = std::max(tr.worst_crossings, crossings(s.x, sys.model(), body));
    const auto depth = mesh::penetration_depths(body, positions(s.x));
    for (double d : depth) tr.deepest = std::max(tr.deepest, d);
    const double e = energy();
    tr.largest_gain = std::max(tr.largest_gain, e - tr.end_energy);
    const double mech = e - stored();
    tr.largest_mechanical_gain = std::max(tr.largest_mechanical_gain, mech - mech_prev);
    mech_prev = mech;
    tr.end_energy = e;
  }
  tr.stats = contact_stats(contact);
  tr.end_x = s.x;
  return tr;
}

void report(const Trace& t) {
  ::testing::Test::RecordProperty("steps", t.steps);
  ::testing::Test::RecordProperty("worst_crossings", t.worst_crossings);
  ::testing::Test::RecordProperty("deepest_m", sci(t.deepest));
  ::testing::Test::RecordProperty("min_cloth_m", sci(t.stats.min_cloth));
  ::testing::Test::RecordProperty("min_body_m", sci(t.stats.min_body));
  ::testing::Test::RecordProperty("cut", static_cast<int>(t.stats.cut));
  ::testing::Test::RecordProperty("largest_gain_J", sci(t.largest_gain));
}

// The self-collision test's cloth (0.4 m, 21 × 21, limp) held upright and
// leaning over the floor, dropped: it buckles and folds onto itself.
TEST(Contact, AClothFoldingOntoItselfNeverCrossesAtAnyStep) {
  constexpr int n = 21;
  constexpr double d = 0.02;
  const Vec3 axis_v = Vec3(0.25, 1.0, 0.0).normalized();
  Model m = make_grid(n, n, d, d, Vec3(0, 0.005, -0.2), Vec3::UnitZ(), axis_v, 0.001);
  MassSpringMaterial mat;
  mat.warp = mat.weft = 40.0;
  mat.shear = 10.0;
  mat.bend_warp = mat.bend_weft = 0.5;
  mat.damping = 0.01;
  ContactDef cd;
  cd.body = test::box(Vec3(1.0, 0.05, 1.0), Mat3::Identity(), Vec3(0, -0.05, 0));
  auto c = make_contact(m, cd);
  const Effect* ce = c.get();
  System sys(m, effects(make_mass_spring(m, {mat}), make_gravity({}), make_viscosity({0.0, 0.5}), std::move(c)));
  const Trace t = run(sys, *ce, cd.body, 0.005, 1.5);
  report(t);
  EXPECT_EQ(t.worst_crossings, 0);
  EXPECT_EQ(t.deepest, 0.0);
  EXPECT_GE(t.stats.min_cloth, cd.floor);
  EXPECT_LT(t.stats.min_cloth, cd.radius);  // it did fold onto itself
  EXPECT_LT(t.stats.min_body, cd.radius);   // and lay on the floor
}

// A 10 × 10 cloth at 3 cm dropped across a rod of 6 mm radius lying midway between two
// rows of particles: the rod is thinner than the mesh, so only the body's
// edges and vertices against the cloth's triangles hold it.
TEST(Contact, ARodThinnerThanTheMeshNeverPassesBetweenParticles) {
  constexpr int n = 10;
  constexpr double d = 0.03;
  constexpr double r = 0.006;
  const double x0 = -0.5 * d * (n - 1);
  Model m = make_grid(n, n, d, d, Vec3(x0, r + 0.02, x0), Vec3::UnitX(), Vec3::UnitZ(), 0.002);
  MassSpringMaterial mat;
  mat.warp = mat.weft = 60.0;
  mat.shear = 10.0;
  mat.bend_warp = mat.bend_weft = 1.0;
  mat.damping = 0.02;
  ContactDef cd;
  cd.body = test::rod(r, 0.5);
  auto c = make_contact(m, cd);
  const Effect* ce = c.get();
  System sys(m, effects(make_mass_spring(m, {mat}), make_gravity({}), std::move(c)));
  const Trace t = run(sys, *ce, cd.body, 0.005, 1.0);
  report(t);
  EXPECT_EQ(t.worst_crossings, 0);
  EXPECT_EQ(t.deepest, 0.0);
  EXPECT_LT(t.stats.min_body, cd.radius);  // it hangs on the rod
}

// Two 21 × 21 sheets at 3 cm, 1 cm apart, dropped from 5 cm onto a 0.3 m
// sphere (the contact-energy test's scene): the upper lands on the lower, both
// hang round the sphere.
Trace sheets_on_sphere(double h, double seconds) {
  constexpr double r = 0.3;
  Model m = test::sheets(21, r + 0.05, 2);
  MassSpringMaterial mat;
  mat.warp = mat.weft = 60.0;
  mat.shear = mat.bend_warp = mat.bend_weft = 10.0;
  mat.damping = 0.02;
  ContactDef cd;
  cd.body = test::uv_sphere(r, 32, 20);
  auto c = make_contact(m, cd);
  const Effect* ce = c.get();
  System sys(m, effects(make_mass_spring(m, {mat}), make_gravity({}), std::move(c)));
  return run(sys, *ce, cd.body, h, seconds);
}

// The contact's own stored energy (½ k (r − d)² of the pairs within the
// radius) is counted apart: pairs that come within the radius during a step
// store it at once, and the cuts and the impulses at the step's end take it
// out again before it can turn into motion; what must never rise is the
// cloth's kinetic, gravitational and elastic energy.
TEST(Contact, TwoSheetsOnASphereNeverCrossAndGainNoEnergyAt5And10ms) {
  for (const double h : {0.005, 0.01}) {
    const Trace t = sheets_on_sphere(h, 0.6);
    ::testing::Test::RecordProperty("h_" + std::to_string(static_cast<int>(h * 1000)) + "ms_largest_total_gain_J",
                                    sci(t.largest_gain));
    ::testing::Test::RecordProperty("h_" + std::to_string(static_cast<int>(h * 1000)) + "ms_largest_gain_J",
                                    sci(t.largest_mechanical_gain));
    EXPECT_EQ(t.worst_crossings, 0) << h;
    EXPECT_EQ(t.deepest, 0.0) << h;
    EXPECT_LT(t.stats.min_cloth, ContactDef{}.radius) << h;  // the upper sheet lies on the lower
    EXPECT_LT(t.stats.min_body, ContactDef{}.radius) << h;
    EXPECT_LE(t.largest_mechanical_gain, 1e-12) << h;
    EXPECT_LT(t.end_energy, 0.7 * t.start_energy) << h;  // the landing took energy out
  }
}

// Two sheets 1 cm apart, sewn along one edge (each particle of the lower
// sheet's edge to the one above it), no gravity: the seam pulls the upper
// edge down onto the lower. The two sides of a seam do not repel each other,
// so the seam closes far inside the contact radius (pushed apart by
// k (r − d) the pull of 0.05 N per pair would stall at r − F/k = 2.5 mm);
// the bound still keeps them from passing through each other.
TEST(Contact, ASeamClosesInsideTheContactRadiusWithoutCrossing) {
  constexpr int n = 11;
  Model m = test::sheets(n, 0.2, 2);
  MassSpringMaterial mat;
  mat.warp = mat.weft = 60.0;
  mat.shear = mat.bend_warp = mat.bend_weft = 10.0;
  mat.damping = 0.02;
  SeamDef sd;
  sd.merge = false;
  SeamPairs edge{"edge", {}};
  for (int i = 0; i < n; ++i) edge.pairs.push_back({i * n + n - 1, n * n + i * n + n - 1});
  sd.seams = {edge};
  ContactDef cd;
  cd.body = test::box(Vec3(1.0, 0.05, 1.0), Mat3::Identity(), Vec3(0, -1.0, 0));  // out of reach
  cd.sewn = edge.pairs;
  auto c = make_contact(m, cd);
  const Effect* ce = c.get();
  System sys(m, effects(make_mass_spring(m, {mat}), make_seam(m, sd), make_viscosity({0.0, 0.5}), std::move(c)));
  const Trace t = run(sys, *ce, cd.body, 0.005, 1.0);
  report(t);
  EXPECT_EQ(t.worst_crossings, 0);
  EXPECT_GE(t.stats.min_cloth, cd.floor * (1 - 1e-9));  // the sides close down to the floor (to rounding)
  double widest = 0.0;
  for (const auto& p : edge.pairs) widest = std::max(widest, (at(t.end_x, p[0]) - at(t.end_x, p[1])).norm());
  ::testing::Test::RecordProperty("widest_gap_m", sci(widest));
  EXPECT_LT(widest, cd.radius / 3);
}

}  // namespace
}  // namespace vgd::sim
