#pragma once
// A hand pulling the cloth: one particle drawn towards a point the user moves
// (the studio's drag in its 3-D view while a drape runs), by a zero-length
// spring with a dashpot,
//   f_i = k (p - x_i) - c v_i,
// on the grabbed particle i only, nothing while nothing is grabbed. Implicit
// integrators get its Jacobian (-k I, -c I); the explicit stability bound
// counts k and c on every particle, since any may be grabbed. While it holds
// a particle the run is not at rest. The grip is set from another thread (the
// user interface) through HandControl; each evaluation reads it once.
#include <memory>
#include <mutex>

#include "vgd/sim/effect.hpp"

namespace vgd::sim {

class HandControl {
 public:
  struct Grip {
    int particle = -1;               // -1: nothing held
    Vec3 target = Vec3::Zero();      // m, world frame
  };
  // Takes hold of a particle (an index of the model), pulling it towards `target`.
  void grab(int particle, const Vec3& target);
  // Moves the point the held particle is pulled to.
  void move(const Vec3& target);
  void release();
  Grip grip() const;

 private:
  mutable std::mutex m_;
  Grip grip_;
};

struct HandDef {
  double stiffness = 20.0;  // N/m: 10 cm of pull is 2 N, about a T-shirt lifted and held by one point
  double damping = 0.06;    // N·s/m: about critical for a 40 mg particle at 20 N/m
  std::shared_ptr<HandControl> control;  // required
};
std::unique_ptr<Effect> make_hand(const HandDef& def);

}  // namespace vgd::sim
