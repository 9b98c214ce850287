// Air viscosity: f = -(k + α m) v per particle (seed 000's f_v = -k_v v).
#include "vgd/sim/effects/basic.hpp"

namespace vgd::sim {
namespace {

class Viscosity final : public Effect {
 public:
  explicit Viscosity(const ViscosityDef& d) : k_(d.k), alpha_(d.alpha) {}
  const char* name() const override { return "viscosity"; }
  void add_forces(const Eval& e, VecX& f) override {
    const int n = e.model.num_particles();
    for (int i = 0; i < n; ++i) at(f, i) -= (k_ + alpha_ * e.model.mass[i]) * at(e.v, i);
  }
  bool add_jacobian(const Eval& e, Triplets&, Triplets& dfdv) override {
    for (int i = 0; i < e.model.num_particles(); ++i)
      add_block(dfdv, i, i, -(k_ + alpha_ * e.model.mass[i]) * Mat3::Identity());
    return true;
  }
  void add_stiffness_bound(const Model& m, VecX&, VecX& c) const override {
    for (int i = 0; i < m.num_particles(); ++i) c[i] += k_ + alpha_ * m.mass[i];
  }

 private:
  double k_, alpha_;
};

}  // namespace

std::unique_ptr<Effect> make_viscosity(const ViscosityDef& def) { return std::make_unique<Viscosity>(def); }

}  // namespace vgd::sim
