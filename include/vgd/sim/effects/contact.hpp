#pragma once
// Contact with a guarantee (docs/collisions.md, "Offset contact"): cloth
// against itself and against a static body, kept free of intersections at
// the end of every step by construction, after Chen et al., "Offset Geometric
// Contact" (SIGGRAPH 2025). One effect replaces the body collision and the
// self-collision with their repairs.
//
//  - Detection, at the start of every step: every pair of primitives closer
//    than the reach R that share no particle: cloth vertex–cloth triangle,
//    cloth edge–cloth edge, cloth vertex–body triangle, body vertex–cloth
//    triangle, cloth edge–body edge.
//  - Bound: two convex primitives d apart stay apart while every point of one
//    moves at most δ₁ towards the other along the normal of their closest
//    points and every point of the other at most δ₂, δ₁ + δ₂ < d (the plane
//    between them keeps separating them along the whole straight-line move).
//    A point of a primitive moves by a convex combination of its corners'
//    moves, so each particle keeps u · Δ ≥ −γ (d − floor) for every pair it
//    is in (u: the normal away from the other primitive, γ < ½) and moves at
//    most γ R in all: no vertex passes through a triangle, no edge through an
//    edge, so no triangle through a triangle (a first touch between two
//    moving triangles is one of those). Sideways and away a particle moves
//    freely.
//  - After the integrator's step: each particle's move is cut to the largest
//    fraction that keeps its half-spaces; the particles still short of their
//    end are detected again at the cut positions and the rest of the move cut
//    to their new half-spaces, up to `rounds` times; the step's last
//    detection is whole. A particle that was cut leaves with the velocity of
//    the move it made (never faster than the step gave it).
//  - Forces (implicit): within the contact radius r < R a pair repels with
//    k (r − d) along its closest points' normal, shared by barycentric
//    weight, normal and weights frozen at the detection (linear over the
//    step; full Jacobian blocks); against the body only each cloth vertex's
//    nearest body triangle pushes, with Coulomb friction μ k (r − d) against
//    the slip, viscous below `slip_speed`. The forces keep cloth off cloth and
//    off the body; the bounds make the promise.
//
// What the promise needs and what it leaves out: the start must be free of
// intersections (not checked here: scene::build moves cloth out of the body,
// the arrangement keeps pieces apart). Seam pairs get no exemption; merges
// (System::apply_merges) are let through by review_merges only when their
// jumps keep the promise; the seam's two sides do not repel each other (the
// bound holds them apart, the forces would hold them open). Prescribed particles (pins) move by their path,
// outside the bound. The body is static.
#include <array>
#include <memory>
#include <vector>

#include "vgd/mesh/surface.hpp"
#include "vgd/sim/effect.hpp"

namespace vgd::sim {

struct ContactDef {
  double radius = 0.003;    // m: contact radius r; the forces act below it
  double reach = 0.006;     // m: detection reach R ≥ r; a particle moves at most γ R per step
  double gamma = 0.45;      // bound factor, < 0.5
  // N/m: k of the repulsion k (r − d). Soft on purpose: the bound keeps the
  // promise, the repulsion only holds cloth off cloth; at 1000 N/m a pair
  // entering the radius within a step changed the force so much that
  // implicit Euler refused the skirt's steps right after its first merges.
  double stiffness = 100.0;
  // m: the smallest gap the bound lets any pair close to (10 µm): the bound
  // is γ (d − floor), so d never falls below it, however hard the cloth is
  // pressed, instead of closing geometrically down to rounding.
  double floor = 1e-5;
  double friction = 0.5;    // Coulomb μ against the body
  double slip_speed = 0.01; // m/s: below it friction grows linearly with the slip
  int rounds = 4;           // cut-and-detect rounds per step
  mesh::SurfaceMesh body;   // static obstacle (m); empty for none
  // Seam pairs (particles a seam will join): two primitives that hold a
  // particle and its seam partner do not push each other, so the seam can
  // pull its sides together; the bound still keeps them apart until the
  // merge. Nothing else is exempt.
  std::vector<std::array<int, 2>> sewn;
  std::vector<int> fixed;   // prescribed particles: moved by their path, not bounded
};

struct ContactStats {
  long steps = 0;
  long detections = 0;        // whole run: whole detections (one per step at least)
  long local_detections = 0;  // whole run: detections between a step's rounds, of the particles still moving
  long cut = 0;               // whole run: particle moves cut to their bound (all rounds)
  long unfinished = 0;        // whole run: particles still short of the step's end after the last round
  long merges_held = 0;       // whole run: seam merges held back (their jump could carry cloth through cloth)
  int pairs = 0;              // pairs within the reach at the last detection
  int touching = 0;           // of those, within the contact radius
  double min_cloth = 1e300;   // m: smallest cloth–cloth distance at any detection, whole run
  double min_body = 1e300;    // m: smallest cloth–body distance at any detection, whole run
};

std::unique_ptr<Effect> make_contact(const Model& model, const ContactDef& def);

// The statistics of an effect made by make_contact (asserts otherwise).
const ContactStats& contact_stats(const Effect& effect);

// Distances used by the bound (exposed for tests), m.
// Point p to triangle abc; w receives the closest point's barycentric weights.
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& w);
// Segment p0p1 to segment q0q1 (parallel and degenerate segments included);
// s, t receive the closest points' parameters.
double segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, double& s, double& t);

}  // namespace vgd::sim
