#pragma once
// Cloth against a static closed body (the avatar): detection against a signed
// distance grid (or an exact BVH), a clearance, and the two seeds' responses
// (docs/collisions.md).
//
//  - provot (seed 000 §4.1.3, after Provot 1997): after each step a particle
//    closer to the body than the clearance is pushed out along the normal to
//    the clearance; an approaching normal velocity v_n < 0 is reversed to
//    −e·v_n (e = restitution, only for impacts faster than min_bounce_speed;
//    slower ones stop: resting contact) and the tangential velocity loses
//    μ·Δv_n (Coulomb: the friction impulse is at most μ times the normal one),
//    stopping if that is more than it has.
//  - slide (seed 002 §3.2.1): inelastic and frictionless. A particle in
//    contact loses the inward normal component of its force (constrain_forces)
//    and of its velocity, and slides.
//
// Seam particles (seed 002 §3.2.2, while seams are being closed), three ways
// (SeamContact): seed 002's rule (force and velocity turned tangential keeping
// their magnitude), a frictionless slide on force and velocity, or a glide on
// the velocity only (frictionless, the force left to the integrator). A seam
// particle becomes an ordinary one when its pair merges.
// Sticky particles (seed 002's belt and sleeve points): once they touch the
// body they stay where they touched, on the surface, with zero velocity.
//
// The body between particles: a particle kept outside the body does not keep
// the body out of the cloth between particles. Where the body is sharper than
// the mesh (toes, heels, the crotch under a seam junction) it would pass
// through the triangles. After the particles, two more rules
// (docs/collisions.md, "Between particles"):
//  - cloth points: every edge's midpoint and triangle's centre found inside
//    the body is moved out to its surface along the body's normal;
//  - body points: every point of a sharp part of the body (its vertices of a
//    radius of curvature under 3 cm, and points 6 mm apart on their
//    triangles) whose projection falls inside a nearby cloth triangle and
//    that lies less than `vertex_clearance` under the triangle's plane (seen
//    along the body's normal) pushes the triangle out.
// Both share the push among the particles by barycentric weight, stop the
// approach, take off slip by Coulomb friction (provot), and mark the
// particles as touching the body along the push.
//
// Prescribed (pinned) particles are left alone only if listed in `fixed`: an
// effect cannot see the other effects' prescribed particles.
#include <memory>
#include <vector>

#include "vgd/mesh/surface.hpp"
#include "vgd/sim/effect.hpp"
#include "vgd/sim/sdf.hpp"

namespace vgd::sim {

enum class ContactResponse {
  provot,  // friction and bounce (seed 000)
  slide,   // inelastic, frictionless slide (seed 002)
};

// How seam particles in contact respond until their pair merges.
enum class SeamContact {
  seed,   // seed 002 §3.2.2: force and velocity tangential, magnitudes kept
  slide,  // force and velocity lose their inward normal parts; no friction
  // Velocity only: the inward normal velocity is removed, no friction. The
  // force is not touched, so implicit steps (whose Jacobian knows nothing of a
  // redirected force) stay stable; the default of drapes (docs/collisions.md).
  glide,
};

enum class BodyQuery {
  grid,   // SignedDistanceGrid: O(1), tens of ns per particle (default; docs/collisions.md)
  exact,  // TriangleBvh: exact closest point, ~10x the cost
};

struct BodyCollisionDef {
  mesh::SurfaceMesh body;        // static, closed, CCW seen from outside (m)
  double clearance = 0.003;      // m: particles are kept at least this far outside the surface
  ContactResponse response = ContactResponse::provot;
  double friction = 0.5;         // Coulomb μ (provot); seed 000 "objectcloth friction const .5"
  // Restitution e (provot): the normal velocity after an impact is −e times the
  // incoming one. Seed 000 calls it "objectcloth damping const .3" and states
  // only that it sets the bouncing; read as e = 0.3 (docs/collisions.md).
  double restitution = 0.3;
  double min_bounce_speed = 0.1;  // m/s: slower impacts are inelastic (no micro-bounces at rest)
  std::vector<int> seam_particles;    // respond as seam_contact says until their pair merges
  SeamContact seam_contact = SeamContact::seed;
  std::vector<int> sticky_particles;  // belt and sleeve points: stay where they touch
  std::vector<int> fixed;             // particles never moved (the scene's pins)
  BodyQuery query = BodyQuery::grid;
  SdfOptions grid;                    // spacing and band of the distance grid
  // m/s: the body moves rigidly, by velocity × t from where `body` puts it at
  // t = 0 (a hanger lifted, a mannequin carried). Its distance grid is built
  // once all the same: a query asks at the particle's position in the body's
  // frame, and the response acts on the velocity relative to the body.
  // Deforming bodies (an animated avatar) are not supported.
  Vec3 velocity = Vec3::Zero();
  // The body between particles (above). m: a cloth triangle's plane is kept
  // this far out from every sharp body point under it (0.001 when on); 0,
  // the default, turns both rules off. Off by default: on the shared real
  // garments they keep the body from showing through the tights' and
  // leggings' crotch and the trousers' heels, but the drapes' outcome moves
  // with them (docs/collisions.md, "Between particles").
  // Smaller than the particles' clearance, so that a chord lying over a
  // convex body (sag L²/8R: 0.6 mm for a 1.5 cm edge over a 5 cm radius) is
  // left alone and only a body sharper than the mesh is pushed against.
  double vertex_clearance = 0.0;
  // m: a vertex deeper than this through a triangle's plane is taken to be on
  // the far side of something (a limb between), not through the triangle: a
  // step moves cloth by millimetres, so a vertex kept out at every step is
  // never found deeper.
  double vertex_reach = 0.01;
};

struct BodyCollisionStats {
  int in_contact = 0;              // particles within the clearance after the last step
  int stuck = 0;                   // sticky particles stuck so far
  double max_penetration = 0.0;    // m: deepest a particle was found inside the surface (before correction), whole run
  double max_clearance_violation = 0.0;  // m: largest (clearance − distance) found before correction, whole run
  long queries = 0;                // distance queries made
  long contacts = 0;               // particle-step contacts handled, whole run
  long vertex_contacts = 0;        // body vertex-triangle corrections, whole run
  double max_vertex_depth = 0.0;   // m: deepest a body vertex was found past a triangle's plane (before correction)
  long sample_contacts = 0;        // cloth edge-midpoint and triangle-centre corrections, whole run
  double max_sample_depth = 0.0;   // m: deepest such a point was found inside the body (before correction)
};

std::unique_ptr<Effect> make_body_collision(const Model& model, const BodyCollisionDef& def);

// The statistics of an effect made by make_body_collision (asserts otherwise).
const BodyCollisionStats& body_collision_stats(const Effect& effect);
// The distance grid of a body-collision effect (BodyQuery::grid), so that
// measurements after a run need not build another; nullptr for any other
// effect or for the exact query.
const SignedDistanceGrid* body_collision_grid(const Effect& effect);

// The contacts an implicit step holds inside its solve (Baraff & Witkin 1998
// §5.3; src/sim/integrators/implicit_euler.cpp): the particles (Model
// indexing) found touching the body (within 1.5 × the clearance, neither
// stuck nor fixed) by the last after-step, with the body's outward normal at
// each, whether friction stopped it there (static friction: the step may
// hold it still while the reaction stays inside the friction cone), the
// body's velocity and the Coulomb coefficient (0 for the slide response).
struct BodyContacts {
  std::vector<int> particle;
  std::vector<Vec3> normal;
  std::vector<unsigned char> stuck;
  Vec3 body_velocity = Vec3::Zero();
  double friction = 0.0;
};
// nullptr when `effect` is not a body collision.
const BodyContacts* body_collision_contacts(const Effect& effect);
// The step held `particle` (Model indexing) against the body, taking `dv`
// (m/s, > 0) of normal velocity change off it: the next after-step's Coulomb
// friction counts it in the normal velocity change it may take μ times off
// the tangential velocity (with the impulse the after-step itself applies).
void body_collision_add_normal_impulse(Effect& effect, int particle, double dv);

}  // namespace vgd::sim
