#include "vgd/sim/run.hpp"

#include <chrono>
#include <cmath>
#include <limits>

namespace vgd::sim {

RunSummary run(System& sys, Integrator& integrator, State& s, const RunSettings& settings,
               const std::vector<FrameSink*>& sinks, const std::function<void(const Progress&)>& progress) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto wall = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  RunSummary summary;
  if (!(settings.fps > 0.0) || !(settings.duration >= 0.0))
    throw SimulationError("frame rate must be > 0 and duration >= 0");
  const int frames = static_cast<int>(std::floor(settings.duration * settings.fps + 1e-9));
  const double t0 = s.t;

  for (auto* sink : sinks) sink->begin(sys.model());
  auto emit = [&](int index) {
    for (auto* sink : sinks) sink->frame(index, s.t, s.x);
    summary.frames = index + 1;
  };
  try {
    sys.apply_prescribed(s);
    integrator.prepare(sys, s);
    sys.check_state(s, std::numeric_limits<double>::infinity());
    emit(0);
    for (int k = 1; k <= frames; ++k) {
      // A failing step throws before its frame is emitted: sinks only ever see checked states.
      integrator.advance(sys, s, t0 + k / settings.fps);
      emit(k);
      if (progress) {
        const double w = wall();
        progress({k, frames, s.t - t0, settings.duration, w, w / k * (frames - k)});
      }
    }
  } catch (const SimulationError& e) {
    summary.ok = false;
    summary.error = e.what();
  }
  summary.simulated_s = s.t - t0;
  summary.wall_s = wall();
  summary.stats = integrator.stats();
  for (auto* sink : sinks) sink->end(summary.ok);
  return summary;
}

}  // namespace vgd::sim
