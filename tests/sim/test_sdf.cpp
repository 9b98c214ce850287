// The distance queries of body collisions against a sphere whose distance is
// known: the grid against the exact BVH, the BVH against the analytic sphere.
#include <gtest/gtest.h>

#include <random>

#include <omp.h>

#include "helpers.hpp"
#include "surfaces.hpp"
#include "vgd/sim/sdf.hpp"

namespace vgd::sim {
namespace {

using test::sci;

constexpr double kR = 0.3;  // m

// Points at distances in [-band, band] from the sphere, in random directions.
std::vector<Vec3> shell_points(int n, double band, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-band, band);
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    const Vec3 dir = Vec3(g(rng), g(rng), g(rng)).normalized();
    out.push_back((kR + u(rng)) * dir);
  }
  return out;
}

// The polyhedral sphere lies within r (1 − cos(Δ/2)) of the true one, Δ the
// larger angular step (64 × 40: 4.5° → 0.23 mm, plus the facet sag ~0.36 mm).
constexpr double kFacetError = 0.0006;  // m

TEST(Bvh, SignedDistanceMatchesTheSphere) {
  const auto sphere = test::uv_sphere(kR);
  const TriangleBvh bvh(sphere);
  double worst = 0.0;
  for (const Vec3& p : shell_points(2000, 0.05)) {
    const auto c = bvh.closest(p);
    const double exact = p.norm() - kR;
    worst = std::max(worst, std::abs(c.distance - exact));
    if (std::abs(exact) > kFacetError) {
      EXPECT_EQ(c.distance < 0, exact < 0);
    }
    EXPECT_GT(c.normal.dot(p.normalized()), 0.99);
  }
  RecordProperty("bvh_max_error_vs_sphere_m", sci(worst));
  EXPECT_LT(worst, kFacetError);
}

TEST(Sdf, GridMatchesTheExactMeshDistanceNearTheSurface) {
  const auto sphere = test::uv_sphere(kR);
  const SignedDistanceGrid grid(sphere, {0.005, 0.02});
  const TriangleBvh bvh(sphere);
  double worst = 0.0, worst_analytic = 0.0, worst_angle = 0.0;
  for (const Vec3& p : shell_points(5000, 0.01)) {
    Vec3 g;
    const double d = grid.sample(p, g);
    const auto c = bvh.closest(p);
    worst = std::max(worst, std::abs(d - c.distance));
    worst_analytic = std::max(worst_analytic, std::abs(d - (p.norm() - kR)));
    worst_angle = std::max(worst_angle, std::acos(std::min(1.0, g.normalized().dot(p.normalized()))));
    EXPECT_NEAR(g.norm(), 1.0, 0.1);  // a distance field's gradient is unit (creases: a little less)
  }
  RecordProperty("grid_max_error_vs_exact_m", sci(worst));
  RecordProperty("grid_max_error_vs_sphere_m", sci(worst_analytic));
  RecordProperty("grid_max_normal_angle_rad", sci(worst_angle));
  // 5 mm spacing: the trilinear interpolant rounds the polyhedron's creases
  // (facets 4.5° apart) by ~0.16 mm; well under the 3 mm clearance.
  EXPECT_LT(worst, 0.00025);
  // Against the true sphere: the facets' own error (kFacetError) plus the grid's.
  EXPECT_LT(worst_analytic, kFacetError + 0.00025);
  // Gradient ≈ radial: the facets themselves are up to ~3° off radial.
  EXPECT_LT(worst_angle, 4.0 * M_PI / 180.0);
}

// The narrow band is built in z slabs on the threads: every node sees the
// triangles in the same order, so the grid is the same bit for bit.
TEST(Sdf, GridDoesNotDependOnTheThreadCount) {
  const auto sphere = test::uv_sphere(kR);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const SignedDistanceGrid one(sphere, {0.005, 0.02});
  omp_set_num_threads(3);  // more slabs than this machine's cores, uneven ones
  const SignedDistanceGrid three(sphere, {0.005, 0.02});
  omp_set_num_threads(threads);
  EXPECT_EQ(one.band_nodes(), three.band_nodes());
  for (const Vec3& p : shell_points(2000, 0.02)) EXPECT_EQ(one.distance(p), three.distance(p)) << p.transpose();
}

TEST(Sdf, FarFieldHasTheRightSign) {
  const auto sphere = test::uv_sphere(kR);
  const SignedDistanceGrid grid(sphere, {0.005, 0.02});
  EXPECT_FLOAT_EQ(grid.distance(Vec3::Zero()), -0.02);  // deep inside: −band
  EXPECT_FLOAT_EQ(grid.distance(Vec3(0.32, 0.1, 0.1)), 0.02);  // outside beyond the band
  EXPECT_DOUBLE_EQ(grid.distance(Vec3(5, 5, 5)), 0.02);     // outside the grid box
  EXPECT_NEAR(grid.distance(Vec3(0, 0.305, 0)), 0.005, 1e-4);
  EXPECT_NEAR(grid.distance(Vec3(0, 0, -0.29)), -0.01, 1e-4);
  EXPECT_GT(grid.band_nodes(), 0);
}

TEST(Sdf, BoxCornersAndEdges) {
  // Sharp features: sign from the pseudo-normals must hold at a box's edges and corners.
  const auto b = test::box(Vec3(0.1, 0.05, 0.08));
  const TriangleBvh bvh(b);
  EXPECT_NEAR(bvh.closest(Vec3(0.11, 0.06, 0.09)).distance, std::sqrt(3e-4), 1e-12);  // corner, outside
  EXPECT_NEAR(bvh.closest(Vec3(0.11, 0.06, 0.0)).distance, std::sqrt(2e-4), 1e-12);   // edge, outside
  EXPECT_NEAR(bvh.closest(Vec3(0.09, 0.045, 0.075)).distance, -0.005, 1e-12);          // inside near a corner
  const SignedDistanceGrid grid(b, {0.005, 0.02});
  EXPECT_NEAR(grid.distance(Vec3(0.0, 0.0, 0.0)), -0.02, 1e-6);
  EXPECT_NEAR(grid.distance(Vec3(0.0, 0.053, 0.0)), 0.003, 1e-5);
  EXPECT_NEAR(grid.distance(Vec3(0.0, 0.047, 0.0)), -0.003, 1e-5);
}

}  // namespace
}  // namespace vgd::sim
