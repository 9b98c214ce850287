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
  double duration = 1.0;    // s of simulated time
};

struct Progress {
  int frame = 0, frames = 0;   // frames done, total
  double t = 0.0, duration = 0.0;  // s simulated
  double wall_s = 0.0, eta_s = 0.0;  // wall time so far and estimate of what is left
};

struct RunSummary {
  bool ok = true;
  std::string error;      // why the run stopped, when !ok
  int frames = 0;         // frames emitted (including frame 0)
  double simulated_s = 0.0;
  double wall_s = 0.0;
  IntegratorStats stats;
};

RunSummary run(System& sys, Integrator& integrator, State& s, const RunSettings& settings,
               const std::vector<FrameSink*>& sinks, const std::function<void(const Progress&)>& progress = {});

}  // namespace vgd::sim
