// The speed limit (include/vgd/sim/effects/basic.hpp): velocities clamped to
// max_speed, and each step's displacement to max_speed × h, after each step.
#include <cmath>
#include <limits>

#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/topology.hpp"

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

  // Merged copies jumped to their common position: the next step starts
  // there (every other particle keeps its start, so the limit still holds).
  void particles_merged(const Model& m, const std::vector<int>& representative) override {
    average_merged_copies(representative, m.mass, x_prev_);
  }

  void after_step(const Model& m, State& s) override {
    // The first step starts from the model's initial positions at t = 0.
    if (x_prev_.size() != s.x.size()) {
      x_prev_ = m.x0.size() == s.x.size() ? m.x0 : s.x;
      last_t_ = m.x0.size() == s.x.size() ? 0.0 : s.t;
    }
    const double h = s.t > last_t_ ? s.t - last_t_ : 0.0;
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
