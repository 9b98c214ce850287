#pragma once
// Cloth against itself, within a piece and between pieces (docs/collisions.md):
// point–triangle proximity found through a spatial hash of the particles,
// rebuilt at every call (O(N)), with the two parts of Bridson, Fedkiw and
// Anderson (2002):
//
//  - a repulsion spring (add_forces): a particle closer than `thickness` to a
//    triangle (its projection inside the triangle, not one of its corners) is
//    pushed away along the triangle normal with f = k (thickness − d), the
//    triangle's corners take −f shared by barycentric weight;
//  - after each step, for the same pairs: an inelastic impulse stops the
//    particle's normal approach to the triangle, and a position correction
//    puts it back to `thickness` on the side it came from (the side before the
//    step, so a particle that went through in one step is brought back), both
//    shared by inverse mass and barycentric weight. A few Gauss–Seidel passes.
//
// Edge–edge pairs (the edges at particles near a triangle against its edges,
// closest points interior to both) get the same correction and impulse along
// their closest-point direction before the step: a fold can pass two edges
// through each other with no corner near a face (found by the fold test).
// The repulsion force is point–triangle only.
//
// After those, a history-free pass (untangle): any edge found through a
// triangle (within one layer, not exempt) has its end nearer the plane pulled
// back through it, whatever side the step started on: the corrections above
// defend the side a pair had at the step's start, so a crossing that came in
// with the start would otherwise stay for good.
// The scene switches this effect on only when it asks for self-collisions.
#include <array>
#include <memory>
#include <vector>

#include "vgd/sim/effect.hpp"
#include "vgd/sim/sdf.hpp"

namespace vgd::sim {

struct SelfCollisionDef {
  double thickness = 0.003;  // m: the smallest particle–triangle distance kept (the cloth's collision thickness)
  // N/m: repulsion spring within the thickness. Enters the explicit stability
  // bound (2k per particle: a particle rarely presses on more than two
  // triangles at once). 0 = impulses and corrections only.
  double stiffness = 1.0;
  // Damping of the repulsion, as a fraction of critical (0 = none): a pressed
  // pair's relative normal velocity is taken off at 2 ζ √(k m) (m the pressed
  // particle's mass), with its velocity Jacobian in the implicit step. A flap
  // standing against other cloth (the men's tee's sleeve tip over the
  // shoulder) swayed on the undamped spring as its pairs came and went, and
  // the drape never came to rest (docs/collisions.md, "Damped repulsion").
  double damping = 0.0;
  bool skip_one_ring = false;  // also skip particles sharing an edge with the triangle
  int passes = 4;              // Gauss–Seidel passes of the after-step correction
  // Detections per step: after the correction, the whole step's motion (start
  // to corrected end) is checked again, until a round finds no crossing. With
  // one, a push that carried a neighbour through other cloth went unseen, the
  // next step defended the wrong side, and a T-shirt's seams pulling against
  // that made the contacts grow from 20 to 10⁶ pairs in 0.6 s.
  int rounds = 4;
  // History-free untangling after each step (Gauss–Seidel passes; 0 = off):
  // edges found through a triangle are pulled back whatever the step started
  // with (self_collision.cpp, untangle).
  int untangle_passes = 4;
  int untangle_every = 1;  // steps between untanglings (every 4th left a skirt crossed)
  std::vector<int> fixed;      // particles never moved (the scene's pins)
  // Particles that are, or are about to become, one (seam pairs): a particle
  // never collides with a triangle or an edge holding its partner, and a
  // particle on a seam's hem never with a triangle or edge touching a hem (the
  // strips along a seam meet edge on while it closes), or seams could not
  // close. Merged particles (System::apply_merges) are joined too.
  std::vector<std::array<int, 2>> joined;
  // Layers (garments worn over one another, docs/collisions.md): per particle
  // its garment's layer, 0 next to the body; empty, or one layer, for none.
  // Between two layers:
  //  - the side a particle must keep is not the one it came from but the
  //    body's order: the outer layer's particle stays on the triangle's side
  //    away from the body (the gradient of `body` at the triangle), so a
  //    crossing an earlier step left is undone while it is no deeper than
  //    `layer_depth`. Where the body's normal lies along the triangle (|cos|
  //    < 0.5: a fold standing out) the side it came from still rules;
  //  - the outer layer gives way: an inner particle within `held_distance` of
  //    the body does not move in these corrections;
  //  - the impulses carry Coulomb friction `layer_friction` (without it a
  //    T-shirt slid down over a skirt and never came to rest).
  std::vector<int> layer;
  // Not owned: the body collision's grid, which outlives this effect (a body
  // at rest). Given, it is one more constraint of the corrections and the
  // untangling: a particle they push inside the body goes back to its surface
  // (the strips along the seams excepted while seams sew). Layers need it.
  const SignedDistanceGrid* body = nullptr;
  double layer_depth = 0.01;                 // m
  double held_distance = 0.0045;             // m: 1.5 × the body collision's default clearance
  double layer_friction = 0.2;               // Coulomb μ between layers
};

struct SelfCollisionStats {
  int pairs = 0;                  // point–triangle pairs within the thickness after the last step (before correction)
  int crossings = 0;              // of those, particles that had gone through their triangle in the last step
  long pairs_total = 0;           // whole run
  double min_distance = 0.0;      // m: smallest pair distance after the last correction (thickness if none)
  long reverted = 0;              // whole run: particles the fail-safe put back to their step's start
  long detections = 0;            // whole run: detection passes (rounds and fail-safe included)
  int tangled = 0;                // edges through a triangle at the end of the last step, before untangling
  long untangled = 0;             // whole run: untangling moves
};

std::unique_ptr<Effect> make_self_collision(const Model& model, const SelfCollisionDef& def);

// The statistics of an effect made by make_self_collision (asserts otherwise).
const SelfCollisionStats& self_collision_stats(const Effect& effect);

}  // namespace vgd::sim
