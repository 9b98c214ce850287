// The block Jacobian (System::jacobian on a fixed block pattern) and the
// implicit Euler paths built on it: the pattern assembly gives the matrices
// setFromTriplets gives, before and after seam merges; the lagged Cholesky
// preconditioner and the warm start give the exact solve's step to within
// the CG tolerance.
#include <gtest/gtest.h>

#include <cstdlib>

#include "helpers.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/strain_rosette.hpp"
#include "vgd/sim/effects/bending.hpp"
#include "vgd/sim/effects/seam.hpp"
#include "vgd/sim/integrator.hpp"

using namespace vgd::sim;
using namespace vgd::sim::test;

namespace {

// Two 4 × 3 grids 1 mm apart (below the seam's merge distance), sewn along
// A's right and B's left column; particle 0 pinned.
Model two_grids() { return test::two_grids(4, 3, 0.001, 0.01, 0.02); }

System sewn_system(const Model& m) {
  SeamDef def;
  SeamPairs side{"side", {}};
  for (int j = 0; j < 3; ++j) side.pairs.push_back({j * 4 + 3, 12 + j * 4});
  def.seams = {side};
  MassSpringMaterial mat;
  mat.damping = 0.05;  // N·s/m: a non-symmetric ∂f/∂x term as well as ∂f/∂v
  // mass-spring writes blocks; damping, viscosity and the seam go through triplets.
  return System(m, effects(make_mass_spring(m, {mat}), make_damping(m, {0.3}), make_viscosity({0.1, 0.5}),
                           make_gravity({}), make_seam(m, def), make_pins(m, {{0}})));
}

// Relative Frobenius distance of the block Jacobian from setFromTriplets'.
void expect_same_jacobians(System& sys, const VecX& x, const VecX& v) {
  SparseMatrix kx, kv;
  sys.jacobian(0.0, x, v, kx, kv);
  BlockJacobian J;
  sys.jacobian(0.0, x, v, J);
  ASSERT_EQ(J.pattern.n, sys.num_particles());
  EXPECT_LE(SparseMatrix(kx - J.to_sparse(J.dfdx)).norm(), 1e-12 * kx.norm());
  EXPECT_LE(SparseMatrix(kv - J.to_sparse(J.dfdv)).norm(), 1e-12 * kv.norm());
  // The pattern holds the transpose of every block and every diagonal block.
  for (int i = 0; i < J.pattern.n; ++i) {
    EXPECT_EQ(J.pattern.col[J.pattern.diag[i]], i);
    for (int q = J.pattern.row[i]; q < J.pattern.row[i + 1]; ++q)
      EXPECT_EQ(J.pattern.col[J.pattern.transpose[q]], i);
  }
  // The block product is the sparse one.
  const VecX p = VecX::Random(sys.num_dofs());
  VecX y;
  J.multiply(J.dfdx, p, y);
  EXPECT_LE((y - kx * p).norm(), 1e-12 * (kx * p).norm());
}

}  // namespace

TEST(BlockJacobian, EqualsTripletAssemblyBeforeAndAfterSeamMerges) {
  const Model m = two_grids();
  System sys = sewn_system(m);
  std::srand(5);
  VecX x = m.x0 + 0.01 * VecX::Random(m.num_dofs()), v = VecX::Random(m.num_dofs());
  expect_same_jacobians(sys, x, v);
  // A second call reuses the pattern (same version) and still agrees.
  BlockJacobian J;
  sys.jacobian(0.0, x, v, J);
  const long version = J.pattern.version;
  x += 0.001 * VecX::Random(m.num_dofs());
  sys.jacobian(0.0, x, v, J);
  EXPECT_EQ(J.pattern.version, version);
  expect_same_jacobians(sys, x, v);

  // Merge the seam: the pattern is rebuilt for the reduced particles.
  State s = initial_state(m);
  s.v = v;
  ASSERT_TRUE(sys.apply_merges(s));
  ASSERT_LT(sys.num_particles(), m.num_particles());
  const VecX xr = s.x + 0.01 * VecX::Random(sys.num_dofs()), vr = VecX::Random(sys.num_dofs());
  sys.jacobian(0.0, xr, vr, J);
  EXPECT_NE(J.pattern.version, version);
  expect_same_jacobians(sys, xr, vr);
}

// The strain rosette and its bending write their blocks too (definite and
// exact Jacobians alike), before and after the seam merges.
TEST(BlockJacobian, StrainRosetteAndBendingBlocksEqualTheirTriplets) {
  for (const bool definite : {true, false}) {
    const Model m = two_grids();
    SeamDef def;
    SeamPairs side{"side", {}};
    for (int j = 0; j < 3; ++j) side.pairs.push_back({j * 4 + 3, 12 + j * 4});
    def.seams = {side};
    OrthotropicMaterial mat;
    System sys(m, effects(make_strain_rosette(m, {mat}, RosetteOptions{.definite_jacobian = definite}),
                          make_bending(m, {mat}, BendingOptions{.definite_jacobian = definite}), make_gravity({}),
                          make_seam(m, def), make_pins(m, {{0}})));
    std::srand(7);
    // Compressed by 2 mm on 1 cm edges here and there: indefinite exact Hessians.
    const VecX x = m.x0 + 0.002 * VecX::Random(m.num_dofs()), v = VecX::Random(m.num_dofs());
    expect_same_jacobians(sys, x, v);
    // The pattern kept, the flat start: hinges without moment keep their places.
    BlockJacobian J;
    sys.jacobian(0.0, x, v, J);
    const long version = J.pattern.version;
    sys.jacobian(0.0, m.x0, v, J);
    EXPECT_EQ(J.pattern.version, version);
    SparseMatrix kx, kv;
    sys.jacobian(0.0, m.x0, v, kx, kv);
    EXPECT_LE(SparseMatrix(kx - J.to_sparse(J.dfdx)).norm(), 1e-12 * kx.norm());
    State s = initial_state(m);
    ASSERT_TRUE(sys.apply_merges(s));
    expect_same_jacobians(sys, s.x + 0.002 * VecX::Random(sys.num_dofs()), VecX::Random(sys.num_dofs()));
  }
}

namespace {

// A 12 × 12 shirting-like square (40 mg particles, k = 4 560 N/m: h²k/m ≈ 10⁴
// at h = 10 ms, the conditioning of the drapes), two corners pinned, released
// crumpled.
System stiff_square() {
  const int side = 12;
  Model m = make_grid(side, side, 0.01, 0.01, Vec3::Zero(), Vec3::UnitX(), -Vec3::UnitY(), 4e-5);
  MassSpringMaterial mat;
  mat.warp = mat.weft = 4560.0;
  mat.shear = 2560.0;
  mat.bend_warp = mat.bend_weft = 400.0;
  mat.damping = 0.01;
  std::vector<int> pins = {0, side - 1};
  return System(m, effects(make_mass_spring(m, {mat}), make_gravity({}), make_viscosity({0.0, 0.5}),
                           make_pins(m, {pins})));
}

State crumpled(const System& sys) {
  State s = initial_state(sys.model());
  std::srand(3);
  s.x += 0.001 * VecX::Random(s.x.size());
  sys.apply_prescribed(s);
  return s;
}

// Positions after `steps` steps of 10 ms.
VecX run(IntegratorSettings st, int steps) {
  System sys = stiff_square();
  State s = crumpled(sys);
  st.method = Method::implicit_euler;
  st.step = 0.01;
  auto integ = make_integrator(st);
  integ->prepare(sys, s);
  integ->advance(sys, s, steps * st.step);
  return s.x - sys.model().x0;
}

}  // namespace

TEST(BlockJacobian, LaggedCholeskyAndWarmStartGiveTheExactSolvesStep) {
  IntegratorSettings exact;
  exact.linear_solver = IntegratorSettings::LinearSolver::cholesky;
  IntegratorSettings jacobi;
  jacobi.cg_tolerance = 1e-8;  // relative residual: the step then agrees to ~1e-8 · cond
  jacobi.cg_max_iterations = 2000;
  jacobi.warm_start = true;  // off by default (integrator.hpp); correct at a tight tolerance
  IntegratorSettings lagged = jacobi;
  lagged.preconditioner = IntegratorSettings::Preconditioner::cholesky;
  lagged.refactor_iterations = 3;
  // One step: no warm start yet; 20 steps: warm starts and lagged factors.
  for (int steps : {1, 20}) {
    const VecX d0 = run(exact, steps);
    ASSERT_GT(d0.norm(), 0.0);
    EXPECT_LE((run(jacobi, steps) - d0).norm(), 1e-5 * d0.norm()) << steps;
    EXPECT_LE((run(lagged, steps) - d0).norm(), 1e-5 * d0.norm()) << steps;
  }
}
