#pragma once
// Basic types of the cloth engine. Units: SI throughout (m, kg, s, N).
// Positions and velocities of N particles are stacked in VecX of size 3N
// (x0 y0 z0 x1 y1 z1 ...); per-particle scalars (masses) are VecX of size N.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace vgd::sim {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using VecX = Eigen::VectorXd;
using Triplet = Eigen::Triplet<double>;
using Triplets = std::vector<Triplet>;
using SparseMatrix = Eigen::SparseMatrix<double>;

// The 3-vector of particle i inside a stacked 3N vector.
inline auto at(VecX& x, int i) { return x.segment<3>(3 * i); }
inline auto at(const VecX& x, int i) { return x.segment<3>(3 * i); }

// Adds a 3x3 block at particle block (i, j) of a 3N x 3N matrix.
inline void add_block(Triplets& t, int i, int j, const Mat3& b) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (b(r, c) != 0.0) t.emplace_back(3 * i + r, 3 * j + c, b(r, c));
}

// Per particle, the largest absolute row sum of its three rows in a 3N x 3N
// matrix given as triplets (duplicates summed first): the Gershgorin bound the
// effects report for the explicit stability limit (System::stiffness).
inline VecX particle_row_sums(const Triplets& t, int particles) {
  SparseMatrix s(3 * particles, 3 * particles);
  s.setFromTriplets(t.begin(), t.end());
  VecX rows = VecX::Zero(3 * particles);
  for (int c = 0; c < s.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(s, c); it; ++it) rows[it.row()] += std::abs(it.value());
  VecX out(particles);
  for (int i = 0; i < particles; ++i) out[i] = rows.segment<3>(3 * i).maxCoeff();
  return out;
}

// A simulation that cannot go on: non-finite values, runaway energy, a solver
// failure, a step refused as unstable. The message says what happened, where,
// and what would work. Frames already emitted stay valid.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vgd::sim
