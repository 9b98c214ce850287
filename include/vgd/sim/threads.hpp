#pragma once
// How many OpenMP threads a run uses, frame by frame, on a machine it shares.
//
// The force kernels split their work among threads that meet at barriers.
// When other processes keep cores busy, a thread waiting at a barrier spins
// on a core another process needs, and a run on two threads of a two-core
// machine shared with one busy process took 2.4-2.6 times as long as on one
// thread (docs/performance.md, "Threads"). A run therefore asks the machine,
// frame by frame, how many cores the other processes left it, and uses at
// most that many threads (at least one, at most the number asked for). The
// trajectory does not depend on the number of threads (fixed chunks), so the
// choice changes the wall time only, never the result.
//
// Cores left = cores − (busy cores measured over the frame − this process's
// own CPU use over it), from /proc/stat and the process CPU clock (Linux),
// over every online core: a process confined to fewer cores (CPU affinity, a
// container's quota) is not told apart from one that may use them all.
// Elsewhere, or when they cannot be read, the number asked for is used.
#include <cstdint>
#include <optional>

namespace vgd::sim {

// Whole-machine CPU counters: jiffies summed over all cores, and the process's
// CPU time. nullopt when the machine cannot be read.
struct CpuSample {
  std::uint64_t busy = 0, total = 0;  // jiffies of all cores: not idle, all
  double own_s = 0.0;                 // s of CPU this process used
  double wall_s = 0.0;                // s, steady clock
};
std::optional<CpuSample> sample_cpu();

// Threads to use given the cores the other processes kept busy (`others`, in
// cores) on a machine of `cores`, the number asked for (`asked` ≥ 1) and the
// number used now (`current`), with free = cores − others: more threads when
// free ≥ n − 0.1 for a larger n (the largest such n), fewer when free < current
// − 0.4 (then the largest n with free ≥ n − 0.4); between 1 and `asked`. The
// gap between the two keeps a load near a boundary from flipping the choice
// every frame; a process using 0.4 core or more of the second core takes it.
int threads_for(double others, int cores, int asked, int current);

// Chooses the team size before each frame of a run (sim::run). With one
// thread asked for it does nothing.
class ThreadGovernor {
 public:
  // `asked`: the threads the run may use (omp_get_max_threads() at its start).
  explicit ThreadGovernor(int asked);
  ~ThreadGovernor();  // gives the run's caller back the number it asked for
  ThreadGovernor(const ThreadGovernor&) = delete;
  ThreadGovernor& operator=(const ThreadGovernor&) = delete;

  // Before a frame: measures the load since the last measurement (when 0.1 s
  // or more of wall time has passed) and sets the OpenMP team size for the
  // frame. The first frame runs on one thread.
  void before_frame();
  int threads() const { return current_; }
  // Frames run with fewer threads than asked for.
  int frames_reduced() const { return reduced_; }

 private:
  int asked_, current_, cores_;
  int reduced_ = 0;
  std::optional<CpuSample> last_;
};

}  // namespace vgd::sim
