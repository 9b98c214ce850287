// The speed limit (include/vgd/sim/effects/basic.hpp): velocities clamped to
// max_speed, and each step's displacement to max_speed × h, after each step.
#include <cmath>
#include <limits>

#include "vgd/sim/effects/basic.hpp"

namespace vgd::sim {
namespace {

class SpeedLimit final : public Effect {
 public:
  SpeedLimit(const Model& m, const SpeedLimitDef& d) : vmax_(d.max_speed) {
    if (!(d.max_speed > 0.0) || !std::isfinite(d.max_speed))
      throw SimulationError("speed limit: max_speed must be a finite speed > 0 m/s");
  }
  const char* name() const override { return "speed-limit"; }
  void add_forces(const Eval&, VecX&) override {}
  bool add_jacobian(const Eval&, Triplets&, Triplets&) override { return true; }

  void particles_merged(const Model&, const std::vector<int>&) override { x_prev_.resize(0); }

  void after_step(const Model& m, State& s) override {
    // The first step, and the first after a merge (whose copies jumped to
    // their common position), have no previous position to limit against.
    const bool known = x_prev_.size() == s.x.size();
    if (!known) x_prev_ = s.x;
    const double h = known && std::isfinite(last_t_) && s.t > last_t_ ? s.t - last_t_ : 0.0;
    last_t_ = s.t;
    const int n = static_cast<int>(s.x.size() / 3);
    for (int i = 0; i < n; ++i) {
      auto v = at(s.v, i);
      const double speed = v.norm();
      if (speed > vmax_) v *= vmax_ / speed;
      if (h > 0.0) {
        const Vec3 d = at(s.x, i) - at(x_prev_, i);
        const double len = d.norm(), lim = vmax_ * h;
        if (len > lim) at(s.x, i) = at(x_prev_, i) + (lim / len) * d;
      }
    }
    x_prev_ = s.x;
  }

 private:
  double vmax_;
  VecX x_prev_;
  double last_t_ = -std::numeric_limits<double>::infinity();  // s: time of the last after_step
};

}  // namespace

std::unique_ptr<Effect> make_speed_limit(const Model& model, const SpeedLimitDef& def) {
  return std::make_unique<SpeedLimit>(model, def);
}

}  // namespace vgd::sim
