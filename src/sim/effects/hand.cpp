// A hand pulling one particle towards a point the user moves, and pins
// (effects/hand.hpp).
#include "vgd/sim/effects/hand.hpp"

#include <algorithm>

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

void HandControl::pin(const std::vector<Pin>& pins) {
  std::lock_guard lock(m_);
  for (const Pin& p : pins) {
    const auto it = std::lower_bound(pins_.begin(), pins_.end(), p.particle,
                                     [](const Pin& a, int i) { return a.particle < i; });
    if (it != pins_.end() && it->particle == p.particle)
      it->at = p.at;
    else
      pins_.insert(it, p);
  }
}

void HandControl::unpin(const std::vector<int>& particles) {
  std::lock_guard lock(m_);
  std::erase_if(pins_, [&](const Pin& p) { return std::find(particles.begin(), particles.end(), p.particle) != particles.end(); });
}

void HandControl::unpin_all() {
  std::lock_guard lock(m_);
  pins_.clear();
}

std::vector<HandControl::Pin> HandControl::pins() const {
  std::lock_guard lock(m_);
  return pins_;
}

std::size_t HandControl::pin_count() const {
  std::lock_guard lock(m_);
  return pins_.size();
}

namespace {

class Hand final : public Effect {
 public:
  explicit Hand(const HandDef& d)
      : k_(d.stiffness), c_(d.damping), kp_(d.pin_stiffness), cp_(d.pin_damping), control_(d.control) {}
  const char* name() const override { return "hand"; }

  void add_forces(const Eval& e, VecX& f) override {
    for (const Spring& s : springs(e.model)) at(f, s.i) += s.k * (s.p - at(e.x, s.i)) - s.c * at(e.v, s.i);
  }
  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets& dfdv) override {
    for (const Spring& s : springs(e.model)) {
      add_block(dfdx, s.i, s.i, -s.k * Mat3::Identity());
      add_block(dfdv, s.i, s.i, -s.c * Mat3::Identity());
    }
    return true;
  }
  double energy(const Eval& e) const override {
    double u = 0.0;
    for (const Spring& s : springs(e.model)) u += 0.5 * s.k * (s.p - at(e.x, s.i)).squaredNorm();
    return u;
  }
  void add_stiffness_bound(const Model& m, VecX& k, VecX& c) const override {
    for (int i = 0; i < m.num_particles(); ++i) k[i] += k_ + kp_, c[i] += c_ + cp_;
  }
  bool blocks_rest() const override { return control_->grip().particle >= 0; }

 private:
  struct Spring {
    int i;
    Vec3 p;
    double k, c;
  };
  // The grip and the pins, without those whose particle is not one of the model's.
  std::vector<Spring> springs(const Model& m) const {
    std::vector<Spring> out;
    auto ok = [&](int i, const Vec3& p) { return i >= 0 && i < m.num_particles() && p.allFinite(); };
    for (const auto& p : control_->pins())
      if (ok(p.particle, p.at)) out.push_back({p.particle, p.at, kp_, cp_});
    if (const auto g = control_->grip(); ok(g.particle, g.target)) out.push_back({g.particle, g.target, k_, c_});
    return out;
  }
  double k_, c_, kp_, cp_;
  std::shared_ptr<HandControl> control_;
};

}  // namespace

std::unique_ptr<Effect> make_hand(const HandDef& def) {
  if (!def.control) throw Error("", "effects.hand", "a hand needs its control (set by the program, not a scene file)");
  if (!(def.stiffness > 0) || !(def.damping >= 0) || !(def.pin_stiffness > 0) || !(def.pin_damping >= 0))
    throw Error("", "effects.hand", "stiffnesses must be > 0 N/m and dampings >= 0 N·s/m");
  return std::make_unique<Hand>(def);
}

}  // namespace vgd::sim
