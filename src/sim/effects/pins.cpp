// Pins: prescribed particles moving with a constant velocity from their start.
#include "vgd/sim/effects/basic.hpp"

namespace vgd::sim {
namespace {

class Pins final : public Effect {
 public:
  Pins(const Model& m, const PinDef& d) : particles_(d.particles), velocity_(d.velocity) {
    for (int p : particles_) {
      if (p < 0 || p >= m.num_particles())
        throw SimulationError("pin names particle " + std::to_string(p) + ", but the model has " +
                              std::to_string(m.num_particles()));
      start_.push_back(at(m.x0, p));
    }
  }
  const char* name() const override { return "pins"; }
  void add_forces(const Eval&, VecX&) override {}  // pins act through prescribed motion
  bool add_jacobian(const Eval&, Triplets&, Triplets&) override { return true; }
  void prescribed_particles(std::vector<int>& out) const override {
    out.insert(out.end(), particles_.begin(), particles_.end());
  }
  // Seam merges need nothing here: the System maps each pinned particle to
  // its merged particle (which is then prescribed) and never merges two pinned
  // particles into one.
  void prescribe(double t, VecX& x, VecX& v) const override {
    for (std::size_t k = 0; k < particles_.size(); ++k) {
      at(x, particles_[k]) = start_[k] + t * velocity_;
      at(v, particles_[k]) = velocity_;
    }
  }

 private:
  std::vector<int> particles_;
  std::vector<Vec3> start_;
  Vec3 velocity_;
};

}  // namespace

std::unique_ptr<Effect> make_pins(const Model& model, const PinDef& def) { return std::make_unique<Pins>(model, def); }

}  // namespace vgd::sim
