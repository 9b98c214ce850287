// Threads per frame on a shared machine (threads.hpp).
#include "vgd/sim/threads.hpp"

#include <omp.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace vgd::sim {

std::optional<CpuSample> sample_cpu() {
  CpuSample s;
  // /proc/stat's first line: "cpu user nice system idle iowait irq softirq steal ...".
  std::FILE* f = std::fopen("/proc/stat", "r");
  if (!f) return std::nullopt;
  unsigned long long v[8] = {};
  const int got = std::fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4],
                              &v[5], &v[6], &v[7]);
  std::fclose(f);
  if (got < 4) return std::nullopt;
  for (const auto x : v) s.total += x;
  s.busy = s.total - v[3] - v[4];  // not idle, not waiting for I/O
  timespec ts{};
  if (::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return std::nullopt;
  s.own_s = static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  return s;
}

int threads_for(double others, int cores, int asked, int current) {
  const double free = static_cast<double>(cores) - std::max(0.0, others);
  int n = current;
  const int up = static_cast<int>(std::floor(free + 0.1)), down = static_cast<int>(std::floor(free + 0.4));
  if (up > current) n = up;
  else if (down < current) n = down;
  return std::clamp(n, 1, std::max(1, asked));
}

namespace {

// The cores /proc/stat sums over: every online one (the process may be allowed fewer).
int machine_cores() {
  const long n = ::sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : omp_get_num_procs();
}

}  // namespace

ThreadGovernor::ThreadGovernor(int asked) : asked_(std::max(1, asked)), current_(1), cores_(machine_cores()) {
  if (asked_ > 1) {
    last_ = sample_cpu();
    current_ = last_ ? 1 : asked_;  // nothing to measure with: as asked
    omp_set_num_threads(current_);
  } else {
    current_ = asked_;
  }
}

ThreadGovernor::~ThreadGovernor() {
  if (asked_ > 1) omp_set_num_threads(asked_);
}

void ThreadGovernor::before_frame() {
  if (asked_ > 1 && last_) {
    if (const auto now = sample_cpu(); now && now->wall_s - last_->wall_s >= 0.1 && now->total > last_->total) {
      const double busy_cores =
          static_cast<double>(now->busy - last_->busy) / static_cast<double>(now->total - last_->total) * cores_;
      const double own_cores = (now->own_s - last_->own_s) / (now->wall_s - last_->wall_s);
      current_ = threads_for(busy_cores - own_cores, cores_, asked_, current_);
      omp_set_num_threads(current_);
      last_ = now;
    }
  }
  reduced_ += current_ < asked_;
}

}  // namespace vgd::sim
