#pragma once
// Running a simulation: advance frame by frame, check every step, hand frames
// to sinks. A run that fails stops with a message; the frames already emitted
// stay valid, and no non-finite value ever reaches a sink.
#include <functional>
#include <string>
#include <vector>

#include "vgd/sim/integrator.hpp"

namespace vgd::sim {

// Where frames go: memory, files (io/), the GUI, a server stream.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  virtual void begin(const Model& model) {}
  // Frame `index` at time t (s) with positions x (3N, m); index 0 is the start.
  virtual void frame(int index, double t, const VecX& x) = 0;
  // Seams merged particles just before frame `index` (called before that
  // frame): for every original particle, the original particle it is now a
  // copy of (itself when not merged; a group's lowest index otherwise).
  virtual void merged(int index, const std::vector<int>& representative) {}
  // The run ended (normally or not); `ok` false means summary.error says why.
  virtual void end(bool ok) {}
};

// Keeps every frame in memory (tests, the GUI, benchmarks).
class MemorySink : public FrameSink {
 public:
  std::vector<double> times;
  std::vector<VecX> frames;
  void frame(int index, double t, const VecX& x) override {
    times.push_back(t);
    frames.push_back(x);
  }
};

struct RunSettings {
  double fps = 30.0;        // frames per second of simulated time
  double duration = 1.0;    // s of simulated time: the time limit when rest detection is on
  // Rest detection: the run ends early once the mean kinetic energy per
  // particle of the motion between frames, ½ Σ m |Δx·fps|² / N (J), stays
  // below rest_energy for rest_frames frames
  // in a row, and no effect has work left (System::may_rest: seams all
  // closed). 0 = off (the run lasts `duration`).
  double rest_energy = 0.0;
  int rest_frames = 10;
  // Use fewer OpenMP threads than asked for while other processes keep cores
  // busy (sim/threads.hpp); false: exactly the number asked for (benchmarks of
  // a fixed team). The trajectory is the same either way.
  bool adapt_threads = true;
  // m: every coordinate of the start moved by a uniform random offset in
  // [-start_jitter, start_jitter] (seeded by start_jitter_seed) before the
  // first frame: robustness studies compare runs that differ by that much
  // (vgd bench robustness). 0 = the start as given.
  double start_jitter = 0.0;
  unsigned start_jitter_seed = 1;
};

struct Progress {
  int frame = 0, frames = 0;   // frames done, total
  double t = 0.0, duration = 0.0;  // s simulated
  double wall_s = 0.0, eta_s = 0.0;  // wall time so far and estimate of what is left
  double kinetic_energy = 0.0;  // J per particle at this frame
};

struct RunSummary {
  bool ok = true;
  std::string error;      // why the run stopped, when !ok
  int frames = 0;         // frames emitted (including frame 0)
  double simulated_s = 0.0;
  double wall_s = 0.0;
  IntegratorStats stats;
  bool at_rest = false;                // ended by rest detection (before `duration`)
  std::vector<double> times;           // s, per emitted frame
  std::vector<double> kinetic_energy;  // J per particle, per emitted frame (motion since the last frame)
  int frames_on_fewer_threads = 0;     // frames run on fewer threads than asked for (threads.hpp)
};

// Runs from s to s.t + settings.duration. s is in the system's current
// particle set (System::num_particles(): the model's full set until seams
// merge; initial_state(sys.model()) for a fresh system) and stays in it: after
// merges it holds the reduced set; System::expand(s.x) gives the positions of
// every original particle. Seam merges are applied at frame boundaries
// (System::apply_merges; the integrator is then reset); sinks always receive
// the original particle set, a merged particle's copies at one position.
// A run that fails (summary.ok false) leaves s at the last frame its sinks
// received, when there was one: a failing step can leave the integrator's
// state half-way through it, before the after-step hooks (contacts) had their
// say, and nothing downstream (a certificate) should measure that.
RunSummary run(System& sys, Integrator& integrator, State& s, const RunSettings& settings,
               const std::vector<FrameSink*>& sinks, const std::function<void(const Progress&)>& progress = {});

}  // namespace vgd::sim
