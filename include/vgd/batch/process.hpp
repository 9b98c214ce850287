#pragma once
// Child processes for catalogue runs: a command run with its output appended
// to a log file, in its own process group (so a time-out stops it and
// everything it started), killed with its parent (PR_SET_PDEATHSIG), and
// waited for with a deadline.
#include <chrono>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace vgd::batch {

struct ProcessResult {
  int exit_code = -1;  // when it exited
  int signal = 0;      // when a signal ended it
  bool timed_out = false;
  double wall_s = 0.0;
  bool ok() const { return signal == 0 && !timed_out && exit_code == 0; }
  std::string describe() const;  // "exit 3", "killed by signal 9 (Killed)", "stopped after its 600 s"
};

struct ProcessOptions {
  std::filesystem::path log;  // stdout and stderr appended here; empty = /dev/null
  std::vector<std::pair<std::string, std::string>> env;  // set in the child
  double deadline_s = 0.0;    // wall seconds, then SIGTERM and (5 s later) SIGKILL to its group; 0 = none
  // Address space of the child and all it starts (RLIMIT_AS), MB; 0 = none.
  // An allocation past it fails (vgd: "internal error: std::bad_alloc").
  // Not applied in an AddressSanitizer build (its shadow memory needs terabytes of address space).
  long memory_mb = 0;
};

class Process {
 public:
  // Starts `exe` with `args`. Throws vgd::Error naming exe when it cannot fork.
  Process(const std::filesystem::path& exe, const std::vector<std::string>& args, const ProcessOptions& options);
  Process(Process&&) noexcept;
  Process& operator=(Process&&) = delete;
  ~Process();  // a child still running is killed (its group) and reaped

  int pid() const { return pid_; }
  // Whether it has ended (reaped), without blocking; applies the deadline.
  bool poll();
  // Blocks until it ends (applying the deadline).
  const ProcessResult& wait();
  const ProcessResult& result() const { return result_; }
  // SIGKILL to its group (it is reaped by poll/wait).
  void kill();

 private:
  int pid_ = -1;
  bool done_ = false;
  std::chrono::steady_clock::time_point start_;
  double deadline_s_ = 0.0;
  bool termed_ = false;
  std::chrono::steady_clock::time_point term_at_;
  ProcessResult result_;
};

// Runs a command to its end.
ProcessResult run_process(const std::filesystem::path& exe, const std::vector<std::string>& args,
                          const ProcessOptions& options);

}  // namespace vgd::batch
