#pragma once
// The mass-spring cloth (seed 000 §4.1, Figure 1) as one Effect: particles
// joined by springs that pull along their length,
//
//   f_a = −[k (|l| − r) + k_d (l′·l)/|l|] l/|l|,   f_b = −f_a,
//
// l = x_a − x_b, l′ = v_a − v_b, r the rest length measured in the flat
// pattern (Model::uv), so a piece placed curved in 3-D still rests at its
// pattern shape. Optional Provot (1995) deformation limiting after each step.
//
// Topology (built once, in make_mass_spring):
//  - A piece whose particles form a complete axis-aligned lattice in uv (the
//    seed's flag, make_grid) gets Figure 1 exactly: structural springs between
//    neighbours along u (warp) and v (weft), shear springs on both diagonals of
//    every cell, bending springs between particles two apart along u and v.
//  - Any other piece (meshes from the mesh stage) gets
//      * a stretch spring on every mesh edge, and
//      * an "opposite-vertex" spring across every interior edge, joining the
//        two vertices the adjacent triangles do not share.
//    Both are weighted by their direction in material space. With φ the angle
//    to the warp and c = cos 2φ (+1 along the warp, 0 on the bias, −1 along
//    the weft), a spring's constant is
//        k = c² k_yarn + (1 − c²) k_shear,
//    k_yarn = warp or weft for an edge, bend_warp or bend_weft for an
//    opposite-vertex spring, by the sign of c. The blend is smooth (C¹ at the
//    bias) and reproduces Figure 1's constants on a triangulated grid: a cell
//    diagonal (an edge on the bias) and the spring across it are the two shear
//    springs; the spring across a warp edge joins particles two apart along
//    the weft, a weft bending spring, and vice versa. It does not reproduce
//    Figure 1's spring counts (the bending springs across the edges of one
//    row are fewer than the lattice's), hence the lattice detection above.
//  - Kinds (for counting and for the limiter) go by the nearest direction:
//    within 22.5° of the warp (weft) a stretch spring is `warp` (`weft`) and an
//    opposite-vertex spring `bend_warp` (`bend_weft`); otherwise `shear`.
//
// Constants are per spring (N/m), as in the seed. In 2-D, a spring network's
// in-plane stiffness (N/m of sheet) is of the order of its spring constants
// whatever the spacing; its bending stiffness is not (it falls with spacing²).
#include <memory>
#include <vector>

#include "vgd/sim/effect.hpp"

namespace vgd::sim {

// One piece's fabric. Defaults: the seed's Garment PROTO (seed 000 §4.2), a
// generic fabric for its 30 × 30 flag with 0.1 kg particles; not measured
// (no Kawabata/FAST source).
struct MassSpringMaterial {
  double warp = 1800.0;      // N/m: structural springs along the warp (u); seed warp_elastic_const 1800
  double weft = 1800.0;      // N/m: structural springs along the weft (v); seed weft_elastic_const 1800
  double shear = 400.0;      // N/m: springs on the bias (cell diagonals); seed shear_elastic_const 400
  double bend_warp = 400.0;  // N/m: springs two apart along the warp; seed warp_bending_elastic_const 400
  double bend_weft = 400.0;  // N/m: springs two apart along the weft; seed weft_bending_elastic_const 400
  double damping = 0.1;      // N·s/m: k_d of every spring; seed elastic_damping_const 0.1
  // Provot's deformation limit on warp and weft springs: after each step none
  // is longer than (1 + max_strain)·r (within MassSpringOptions::limit_tolerance,
  // when the limiter's passes converge: MassSpringStats says when they did not).
  // Dimensionless, e.g. 0.1 (10 %); 0 = off.
  double max_strain = 0.0;
};

// Settings of the effect that are not fabric properties.
struct MassSpringOptions {
  // Particles the limiter must not move (the scene's pins: an effect cannot see
  // other effects' prescribed particles). Others move in proportion to 1/mass.
  std::vector<int> fixed;
  int limit_passes = 20;          // most Gauss–Seidel passes of the limiter per step
  double limit_tolerance = 1e-3;  // relative overshoot of (1 + max_strain)·r left alone
  // From this many springs on, forces are summed in 8 fixed chunks that
  // OpenMP threads share out (bit-identical for any thread count); below, one
  // serial pass, since threads would cost more than they save.
  int parallel_min_springs = 1000;
};

enum class SpringKind : unsigned char { warp, weft, shear, bend_warp, bend_weft };
inline constexpr int kSpringKinds = 5;
const char* to_string(SpringKind k);

// The springs, structure of arrays, sorted by (a, b) with a < b.
struct SpringTopology {
  std::vector<int> a, b;            // particle indices
  std::vector<SpringKind> kind;
  std::vector<double> k;            // N/m
  std::vector<double> damping;      // N·s/m
  std::vector<double> rest;         // m, from Model::uv
  std::vector<double> max_length;   // m: Provot's limit (1 + max_strain)·rest, 0 = unlimited
  std::vector<int> lattice_pieces;  // pieces built with Figure 1's lattice topology

  int size() const { return static_cast<int>(a.size()); }
  int count(SpringKind kd) const;
};

// Builds the springs of a model (see the top of this file). One material per
// piece, indexed by Model::triangle_piece, or one for all pieces. Throws
// SimulationError naming the field or the triangle for invalid input: no
// material, a negative or non-finite constant, a piece index out of range,
// a spring of zero rest length.
SpringTopology mass_spring_topology(const Model& m, const std::vector<MassSpringMaterial>& per_piece);

// The mass-spring effect ("mass-spring"): forces, exact Jacobian (add_jacobian
// returns true), energy ½ Σ k (|l| − r)², stiffness bounds, and the strain
// limiter as its after-step hook.
std::unique_ptr<Effect> make_mass_spring(const Model& m, const std::vector<MassSpringMaterial>& per_piece,
                                         const MassSpringOptions& options = {});

// What the strain limiter did.
struct MassSpringStats {
  int springs = 0;
  int limited_springs = 0;     // springs with a max_length
  long limited_steps = 0;      // after-step calls that corrected at least one spring
  long corrections = 0;        // spring corrections (one spring in two passes counts twice)
  int last_passes = 0;         // Gauss–Seidel passes in the last after-step call
  int last_unresolved = 0;     // springs still beyond their limit after the last call
  long unresolved_steps = 0;   // calls that ran out of passes with springs beyond their limit
};

// The statistics of a mass-spring effect; nullptr for any other effect.
const MassSpringStats* mass_spring_stats(const Effect& e);

}  // namespace vgd::sim
