// A hand pulling one particle towards a point the user moves (effects/hand.hpp).
#include "vgd/sim/effects/hand.hpp"

#include "vgd/core/diagnostics.hpp"

namespace vgd::sim {

void HandControl::grab(int particle, const Vec3& target) {
  std::lock_guard lock(m_);
  grip_ = {particle, target};
}

void HandControl::move(const Vec3& target) {
  std::lock_guard lock(m_);
  grip_.target = target;
}

void HandControl::release() {
  std::lock_guard lock(m_);
  grip_ = {};
}

HandControl::Grip HandControl::grip() const {
  std::lock_guard lock(m_);
  return grip_;
}

namespace {

class Hand final : public Effect {
 public:
  explicit Hand(const HandDef& d) : k_(d.stiffness), c_(d.damping), control_(d.control) {}
  const char* name() const override { return "hand"; }

  void add_forces(const Eval& e, VecX& f) override {
    const auto g = held(e.model);
    if (g.particle < 0) return;
    at(f, g.particle) += k_ * (g.target - at(e.x, g.particle)) - c_ * at(e.v, g.particle);
  }
  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets& dfdv) override {
    const auto g = held(e.model);
    if (g.particle < 0) return true;
    add_block(dfdx, g.particle, g.particle, -k_ * Mat3::Identity());
    add_block(dfdv, g.particle, g.particle, -c_ * Mat3::Identity());
    return true;
  }
  double energy(const Eval& e) const override {
    const auto g = held(e.model);
    return g.particle < 0 ? 0.0 : 0.5 * k_ * (g.target - at(e.x, g.particle)).squaredNorm();
  }
  void add_stiffness_bound(const Model& m, VecX& k, VecX& c) const override {
    for (int i = 0; i < m.num_particles(); ++i) k[i] += k_, c[i] += c_;
  }
  bool blocks_rest() const override { return control_->grip().particle >= 0; }

 private:
  // The grip, or nothing when its particle is not one of the model's.
  HandControl::Grip held(const Model& m) const {
    auto g = control_->grip();
    if (g.particle >= m.num_particles() || !g.target.allFinite()) g.particle = -1;
    return g;
  }
  double k_, c_;
  std::shared_ptr<HandControl> control_;
};

}  // namespace

std::unique_ptr<Effect> make_hand(const HandDef& def) {
  if (!def.control) throw Error("", "effects.hand", "a hand needs its control (set by the program, not a scene file)");
  if (!(def.stiffness > 0) || !(def.damping >= 0))
    throw Error("", "effects.hand", "stiffness must be > 0 N/m and damping >= 0 N·s/m");
  return std::make_unique<Hand>(def);
}

}  // namespace vgd::sim
