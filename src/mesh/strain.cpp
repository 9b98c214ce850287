#include "vgd/mesh/strain.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgd::mesh {

TriangleStrain triangle_strain(const Eigen::Vector2d& u0, const Eigen::Vector2d& u1, const Eigen::Vector2d& u2,
                               const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2) {
  TriangleStrain s;
  Eigen::Matrix2d D;
  D.col(0) = u1 - u0;
  D.col(1) = u2 - u0;
  const double det = D.determinant();
  // A rest triangle of (nearly) no area has no deformation gradient.
  if (!(std::abs(det) >= 1e-14)) return s;
  Eigen::Matrix<double, 3, 2> X;
  X.col(0) = x1 - x0;
  X.col(1) = x2 - x0;
  const Eigen::Matrix<double, 3, 2> F = X * D.inverse();
  const double lu = F.col(0).norm(), lv = F.col(1).norm();
  s.valid = true;
  s.warp = lu - 1.0;
  s.weft = lv - 1.0;
  const double c = std::clamp(F.col(0).dot(F.col(1)) / std::max(lu * lv, 1e-300), -1.0, 1.0);
  s.shear_deg = 90.0 - std::acos(c) * 180.0 / std::numbers::pi;
  // FᵀF (2 × 2, symmetric): its larger eigenvalue is the largest squared stretch.
  const Eigen::Matrix2d C = F.transpose() * F;
  const double tr = C.trace(), dt = C.determinant();
  const double disc = std::sqrt(std::max(0.0, 0.25 * tr * tr - dt));
  s.stretch = std::sqrt(std::max(0.0, 0.5 * tr + disc)) - 1.0;
  s.area_ratio = std::sqrt(std::max(0.0, dt));
  return s;
}

}  // namespace vgd::mesh
