#pragma once
// A hand on the cloth while it drapes (the studio's 3-D view): one particle
// drawn towards a point the user moves, by a zero-length spring with a
// dashpot,
//   f_i = k (p - x_i) - c v_i,
// on the grabbed particle i only, nothing while nothing is grabbed; and pins
// (seed 000's constrictions; a frozen piece is every particle of it pinned):
// particles held where they were pinned by stiffer springs of the same form
// (k_pin, c_pin), until unpinned. Implicit integrators get the Jacobian
// (-k I, -c I per held particle); the explicit stability bound counts k + k_pin
// and c + c_pin on every particle, since any may be held. While it holds a
// particle the run is not at rest; pins do not keep it from resting. The grip
// and the pins are set from another thread (the user interface) through
// HandControl; each evaluation reads them once.
#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

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

  struct Pin {
    int particle = -1;
    Vec3 at = Vec3::Zero();  // m, world frame
  };
  // Pins particles where they are (`at`, one each); a particle pinned again
  // takes the new place. Unpins some, or all.
  void pin(const std::vector<Pin>& pins);
  void unpin(const std::vector<int>& particles);
  void unpin_all();
  std::vector<Pin> pins() const;  // by increasing particle
  std::size_t pin_count() const;

 private:
  mutable std::mutex m_;
  Grip grip_;
  std::vector<Pin> pins_;  // sorted by particle, unique
};

struct HandDef {
  double stiffness = 20.0;  // N/m: 10 cm of pull is 2 N, about a T-shirt lifted and held by one point
  double damping = 0.06;    // N·s/m: about critical for a 40 mg particle at 20 N/m
  // Pins: a 30 mg particle's weight sags 0.3 mm at 1000 N/m; three pins hold
  // a 150 g garment within 0.5 mm; a frozen piece's seam edges give about a
  // millimetre to the seams pulling on them. 0.3 N·s/m is about critical for
  // 30 mg. Stiff for the explicit integrators' bound; the studio's drapes are
  // implicit.
  double pin_stiffness = 1000.0;  // N/m
  double pin_damping = 0.3;       // N·s/m
  std::shared_ptr<HandControl> control;  // required
};
std::unique_ptr<Effect> make_hand(const HandDef& def);

}  // namespace vgd::sim
