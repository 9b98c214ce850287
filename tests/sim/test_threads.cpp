// Threads per frame on a shared machine (sim/threads.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include <chrono>
#include <ctime>
#include <thread>

#include "vgd/sim/threads.hpp"

namespace vgd::sim {

// Two cores: idle, two threads; a busy process, one; one using 0.4 core or
// more of the second core takes it back; near the boundaries the choice holds.
TEST(ThreadsFor, AsManyThreadsAsCoresTheOthersLeaveFree) {
  EXPECT_EQ(threads_for(0.0, 2, 2, 1), 2);
  EXPECT_EQ(threads_for(0.05, 2, 2, 2), 2);
  EXPECT_EQ(threads_for(1.0, 2, 2, 2), 1);
  EXPECT_EQ(threads_for(2.0, 2, 2, 2), 1) << "never fewer than one";
  EXPECT_EQ(threads_for(0.45, 2, 2, 2), 1);
  EXPECT_EQ(threads_for(0.35, 2, 2, 2), 2) << "kept: the load is below the margin for dropping";
  EXPECT_EQ(threads_for(0.35, 2, 2, 1), 1) << "not added: more than 0.1 core is taken";
  EXPECT_EQ(threads_for(0.05, 2, 2, 1), 2);
  EXPECT_EQ(threads_for(0.0, 8, 4, 1), 4) << "never more than asked for";
  EXPECT_EQ(threads_for(3.2, 8, 8, 8), 5) << "4.8 cores free: five threads, the fifth on the core 80 % free";
  EXPECT_EQ(threads_for(-0.3, 2, 2, 1), 2) << "measurement noise below zero counts as idle";
}

// The machine's counters move forward and the process's CPU time counts its
// work: 60 ms of CPU by the C library's clock (however busy the machine).
TEST(SampleCpu, CountersAdvanceWithWork) {
  const auto a = sample_cpu();
  ASSERT_TRUE(a.has_value()) << "/proc/stat could not be read";
  volatile double x = 0;
  const std::clock_t start = std::clock();
  while (static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC < 0.06) x = x + 1.0;
  const auto b = sample_cpu();
  ASSERT_TRUE(b.has_value());
  EXPECT_GE(b->total, a->total);
  EXPECT_GE(b->busy, a->busy);
  EXPECT_LE(b->busy, b->total);
  EXPECT_GE(b->own_s - a->own_s, 0.06);
  EXPECT_GT(b->wall_s - a->wall_s, 0.0);
}

// One thread asked: nothing changes. Two: the first frame runs on one, and the
// caller's number comes back when the run ends.
TEST(ThreadGovernor, StartsOnOneThreadAndGivesTheNumberBack) {
  omp_set_num_threads(1);
  {
    ThreadGovernor g(1);
    g.before_frame();
    EXPECT_EQ(g.threads(), 1);
    EXPECT_EQ(g.frames_reduced(), 0);
  }
  omp_set_num_threads(2);
  {
    ThreadGovernor g(2);
    EXPECT_EQ(omp_get_max_threads(), 1);
    g.before_frame();  // no 0.1 s measured yet: still one thread
    EXPECT_EQ(g.threads(), 1);
    EXPECT_EQ(g.frames_reduced(), 1);
    std::this_thread::sleep_for(std::chrono::milliseconds(120));
    g.before_frame();
    EXPECT_GE(g.threads(), 1);
    EXPECT_LE(g.threads(), 2);
    EXPECT_EQ(omp_get_max_threads(), g.threads());
  }
  EXPECT_EQ(omp_get_max_threads(), 2);
  omp_set_num_threads(1);
}

}  // namespace vgd::sim
