// A cloth triangle's strain against its flat rest shape (mesh/strain.hpp),
// checked against the closed forms of uniform stretch, rigid motion and
// simple shear.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "vgd/mesh/strain.hpp"

namespace vgd::mesh {
namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

// The rest triangle (0,0), (0.02,0), (0,0.015) m mapped by x = A u (+ t).
TriangleStrain mapped(const Eigen::Matrix<double, 3, 2>& A, const V3& t = V3::Zero()) {
  const V2 u0(0, 0), u1(0.02, 0), u2(0, 0.015);
  return triangle_strain(u0, u1, u2, A * u0 + t, A * u1 + t, A * u2 + t);
}

TEST(TriangleStrain, AStretchAlongTheWarpIsWarpStrainOnly) {
  Eigen::Matrix<double, 3, 2> A = Eigen::Matrix<double, 3, 2>::Zero();
  A(0, 0) = 1.10, A(1, 1) = 1.0;
  const auto s = mapped(A);
  ASSERT_TRUE(s.valid);
  EXPECT_NEAR(s.warp, 0.10, 1e-12);
  EXPECT_NEAR(s.weft, 0.0, 1e-12);
  EXPECT_NEAR(s.shear_deg, 0.0, 1e-10);
  EXPECT_NEAR(s.stretch, 0.10, 1e-12);
  EXPECT_NEAR(s.area_ratio, 1.10, 1e-12);
}

TEST(TriangleStrain, ARigidMotionInSpaceStrainsNothing) {
  // The flat triangle turned 40° about a tilted axis, lifted and moved.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, V3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix<double, 3, 2> A = R.leftCols<2>();
  const auto s = mapped(A, V3(0.3, 1.2, -0.4));
  ASSERT_TRUE(s.valid);
  EXPECT_NEAR(s.warp, 0.0, 1e-12);
  EXPECT_NEAR(s.weft, 0.0, 1e-12);
  EXPECT_NEAR(s.shear_deg, 0.0, 1e-9);
  EXPECT_NEAR(s.stretch, 0.0, 1e-12);
}

TEST(TriangleStrain, SimpleShearTurnsTheWeftByItsAngle) {
  // x = u + γ v: the weft turns by atan γ towards the warp, its length √(1 + γ²);
  // the largest stretch is √λ − 1 with λ = 1 + γ²/2 + γ √(1 + γ²/4).
  const double g = 0.25;
  Eigen::Matrix<double, 3, 2> A = Eigen::Matrix<double, 3, 2>::Zero();
  A(0, 0) = 1, A(0, 1) = g, A(1, 1) = 1;
  const auto s = mapped(A);
  ASSERT_TRUE(s.valid);
  EXPECT_NEAR(s.warp, 0.0, 1e-12);
  EXPECT_NEAR(s.weft, std::sqrt(1 + g * g) - 1, 1e-12);
  EXPECT_NEAR(s.shear_deg, std::atan(g) * 180 / std::numbers::pi, 1e-9);
  EXPECT_NEAR(s.stretch, std::sqrt(1 + g * g / 2 + g * std::sqrt(1 + g * g / 4)) - 1, 1e-12);
  EXPECT_NEAR(s.area_ratio, 1.0, 1e-12);
}

TEST(TriangleStrain, ADegenerateRestTriangleHasNone) {
  const auto s = triangle_strain(V2(0, 0), V2(0.01, 0), V2(0.02, 0), V3(0, 0, 0), V3(0.01, 0, 0), V3(0, 0.01, 0));
  EXPECT_FALSE(s.valid);
}

}  // namespace
}  // namespace vgd::mesh
