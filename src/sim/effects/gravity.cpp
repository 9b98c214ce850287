// Gravity: f = m g. No Jacobian (constant), no stiffness.
#include "vgd/sim/effects/basic.hpp"

namespace vgd::sim {
namespace {

class Gravity final : public Effect {
 public:
  explicit Gravity(const GravityDef& d) : g_(d.g) {}
  const char* name() const override { return "gravity"; }
  void add_forces(const Eval& e, VecX& f) override {
    const int n = e.model.num_particles();
    for (int i = 0; i < n; ++i) at(f, i) += e.model.mass[i] * g_;
  }
  bool add_jacobian(const Eval&, Triplets&, Triplets&) override { return true; }  // constant force
  double energy(const Eval& e) const override {
    double u = 0.0;
    for (int i = 0; i < e.model.num_particles(); ++i) u -= e.model.mass[i] * g_.dot(at(e.x, i));
    return u;
  }

 private:
  Vec3 g_;
};

}  // namespace

std::unique_ptr<Effect> make_gravity(const GravityDef& def) { return std::make_unique<Gravity>(def); }

}  // namespace vgd::sim
