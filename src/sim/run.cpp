#include "vgd/sim/run.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "vgd/core/diagnostics.hpp"
#include "vgd/sim/threads.hpp"

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

  VGD_ASSERT(s.x.size() == sys.num_dofs() && s.v.size() == sys.num_dofs(),
             "sim::run takes the state in the system's current (reduced) particle set");
  if (settings.start_jitter > 0.0) {
    std::mt19937 rng(settings.start_jitter_seed);
    std::uniform_real_distribution<double> offset(-settings.start_jitter, settings.start_jitter);
    for (Eigen::Index k = 0; k < s.x.size(); ++k) s.x[k] += offset(rng);
  }
  for (auto* sink : sinks) sink->begin(sys.model());
  // Sinks see the model's original particles (seed 002 §3.3: E-Fabric's client
  // keeps an eliminated particle with its survivor's attributes), so every
  // frame of a run has one topology whatever merged.
  VecX full, prev_x;
  std::optional<State> last;  // the last state the sinks saw
  auto emit = [&](int index) {
    const VecX* x = &s.x;
    if (sys.merged()) {
      full = sys.expand(s.x);
      x = &full;
    }
    for (auto* sink : sinks) sink->frame(index, s.t, *x);
    last = s;
    summary.frames = index + 1;
    summary.times.push_back(s.t);
    // The kinetic energy of the motion between frames, ½ Σ m |Δx fps|² / N:
    // what a viewer sees move. The state's own velocities also hold the
    // contact jitter a collision projection removes every step (a particle
    // pressed on the body keeps an inward v that never moves it), which would
    // keep a garment resting on a body from ever counting as at rest.
    double ke = 0.0;
    if (prev_x.size() == s.x.size()) {
      const VecX& m = sys.mass();
      for (int i = 0; i < sys.num_particles(); ++i)
        ke += 0.5 * m[i] * (at(s.x, i) - at(prev_x, i)).squaredNorm() * settings.fps * settings.fps;
      ke /= std::max(1, sys.num_particles());
    } else {
      ke = index == 0 ? 0.0 : sys.kinetic_energy(s.v) / std::max(1, sys.num_particles());  // just after a merge
    }
    prev_x = s.x;
    summary.kinetic_energy.push_back(ke);
  };
  // Seam merges at frame boundaries only: the integrator then starts afresh
  // on the smaller system.
  // Sinks hear of it in original indices (a reduced particle's lowest original one).
  auto merge = [&](bool prepared, int index) {
    if (!sys.apply_merges(s)) return;
    if (prepared) integrator.reset(sys, s);
    const std::vector<int>& rep = sys.representative();
    std::vector<int> first(sys.num_particles(), -1), copy_of(rep.size());
    for (std::size_t i = 0; i < rep.size(); ++i) {
      if (first[rep[i]] < 0) first[rep[i]] = static_cast<int>(i);
      copy_of[i] = first[rep[i]];
    }
    for (auto* sink : sinks) sink->merged(index, copy_of);
  };
  int calm = 0;  // frames in a row below the rest energy
  // As many threads as the machine has cores free, up to those asked for
  // (threads.hpp): the result does not depend on it.
  ThreadGovernor threads(settings.adapt_threads ? omp_get_max_threads() : 1);
  try {
    sys.apply_prescribed(s);
    merge(false, 0);
    integrator.prepare(sys, s);
    sys.check_state(s, std::numeric_limits<double>::infinity());
    emit(0);
    for (int k = 1; k <= frames; ++k) {
      // A failing step throws before its frame is emitted: sinks only ever see checked states.
      threads.before_frame();
      integrator.advance(sys, s, t0 + k / settings.fps);
      merge(true, k);
      emit(k);
      const double ke = summary.kinetic_energy.back();
      calm = settings.rest_energy > 0.0 && ke < settings.rest_energy && sys.may_rest() ? calm + 1 : 0;
      if (progress) {
        const double w = wall();
        progress({k, frames, s.t - t0, settings.duration, w, w / k * (frames - k), ke});
      }
      if (settings.rest_energy > 0.0 && calm >= std::max(1, settings.rest_frames)) {
        summary.at_rest = true;
        break;
      }
    }
  } catch (const SimulationError& e) {
    summary.ok = false;
    summary.error = e.what();
    if (last) s = *last;
  }
  summary.simulated_s = s.t - t0;
  summary.wall_s = wall();
  summary.stats = integrator.stats();
  summary.frames_on_fewer_threads = threads.frames_reduced();
  for (auto* sink : sinks) sink->end(summary.ok);
  return summary;
}

}  // namespace vgd::sim
