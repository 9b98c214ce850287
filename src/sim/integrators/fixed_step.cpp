#include "fixed_step.hpp"

#include <cmath>

#include "vgd/core/strings.hpp"

namespace vgd::sim::detail {

void FixedStepIntegrator::prepare(System& sys, const State&) {
  if (!(settings_.step > 0.0) || !std::isfinite(settings_.step))
    throw SimulationError("the integration step must be a positive number of seconds (got " +
                          format_significant(settings_.step, 3) + ")");
  h_ = settings_.step;
  if (!is_explicit(settings_.method)) return;
  const auto& k = sys.stiffness();
  const double limit = settings_.safety * stability_limit(settings_.method, k);
  if (h_ <= limit) return;
  if (settings_.auto_substep) {
    h_ = limit;
    return;
  }
  // Refuse, and say what would work.
  const double rk4 = settings_.safety * stability_limit(Method::rk4, k);
  std::string msg = "step " + format_significant(h_, 3) + " s is above the stability limit of " +
                    to_string(settings_.method) + " for this scene: " + format_significant(limit, 3) + " s";
  if (k.particle >= 0)
    msg += " (stiffest at particle " + std::to_string(k.particle) + ", from " + k.effect + ": ω ≈ " +
           format_significant(std::sqrt(k.omega2), 3) + " rad/s" +
           (k.damping_rate > 0 ? ", damping rate " + format_significant(k.damping_rate, 3) + " 1/s"
                               : std::string()) +
           ")";
  msg += ". What would work: a step of " + format_significant(limit, 3) + " s or less (or " +
         std::to_string(static_cast<int>(std::ceil(h_ / limit))) +
         "x the iterations per frame), automatic sub-stepping";
  if (settings_.method != Method::rk4 && rk4 > h_)
    msg += ", RK4 (limit " + format_significant(rk4, 3) + " s)";
  msg += ", implicit Euler or BDF.";
  throw SimulationError(msg);
}

void FixedStepIntegrator::advance(System& sys, State& s, double t_end) {
  const double span = t_end - s.t;
  if (span <= 0.0) return;
  // Equal steps no longer than h_ that land exactly on t_end.
  const int n = std::max(1, static_cast<int>(std::ceil(span / h_ - 1e-9)));
  const double h = span / n;
  const double t0 = s.t;
  for (int k = 1; k <= n; ++k) {
    do_step(sys, s, h);
    s.t = k == n ? t_end : t0 + k * h;
    sys.apply_prescribed(s);
    sys.after_step(s);
    sys.check_state(s, settings_.max_speed);
    ++stats_.steps;
  }
  stats_.last_step = h;
}

}  // namespace vgd::sim::detail
