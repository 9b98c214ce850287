#pragma once
// Strain of a cloth triangle between its flat rest shape and where it is now:
// the deformation gradient F = [x1−x0  x2−x0] [u1−u0  u2−u0]⁻¹ (3 × 2), with
// the rest shape in material coordinates (warp along u, weft along v, m; the
// uv of sim::Model and the `vt` of garment.obj). Used by the drape's
// certificate (per-piece percentiles) and by fit maps (render/fit_map.hpp).
#include <Eigen/Core>

namespace vgd::mesh {

struct TriangleStrain {
  bool valid = false;   // false for a degenerate rest triangle (no F)
  double warp = 0.0;    // engineering strain along the warp, |F e_u| − 1 (0.1 = 10 % longer)
  double weft = 0.0;    // along the weft, |F e_v| − 1
  double shear_deg = 0.0;  // change of the warp–weft angle from 90°, degrees (signed)
  double stretch = 0.0;    // largest principal stretch − 1 (√ of FᵀF's larger eigenvalue, − 1)
  double area_ratio = 1.0; // area now / area at rest
};

// Rest corners in material coordinates (m), current corners (m).
TriangleStrain triangle_strain(const Eigen::Vector2d& u0, const Eigen::Vector2d& u1, const Eigen::Vector2d& u2,
                               const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2);

}  // namespace vgd::mesh
