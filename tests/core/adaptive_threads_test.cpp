// AdaptiveThreads (core/adaptive_threads.hpp) on a simulated clock: each step advances the clock by the cost of the
// thread count the chooser set for it, so which count it picks, how often it measures the other and what it costs
// are exact numbers.
#include "sphstab/core/adaptive_threads.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "sphstab/core/threads.hpp"

namespace sphstab {
namespace {

/// Runs `steps` steps; cost(threads, step) is a step's simulated wall time. Returns the total simulated time.
double simulate(AdaptiveThreads& a, double& clock, long steps, const std::function<double(int, long)>& cost) {
  const double start = clock;
  for (long n = 0; n < steps; ++n) {
    a.before_step();
    if (a.most() > 1) EXPECT_EQ(max_threads(), a.current());  // the step runs with the count the chooser set
    clock += cost(max_threads(), n);
    a.after_step();
  }
  return clock - start;
}

TEST(AdaptiveThreads, KeepsTheFasterCountAndRarelyMeasuresTheOther) {
  const ThreadCountGuard guard(1);
  for (const double two : {0.6, 1.7}) {  // two threads 1.7x faster, then 1.7x slower than one
    double clock = 0;
    AdaptiveThreads a(2, [&] { return clock; });
    const double one = 0.01;
    const double total = simulate(a, clock, 20000, [&](int t, long) { return t == 2 ? one * two : one; });
    const bool two_faster = two < 1;
    const long slow_steps = two_faster ? a.steps_with_one() : a.steps_with_most();
    EXPECT_EQ(a.steps_with_one() + a.steps_with_most(), 20000);
    // Probes once settled: one block in 65; a block lasts until it holds 0.05 s of stepping (9 or 5 steps here).
    EXPECT_LT(slow_steps, 20000 / 40) << two;
    const double best = 20000 * one * std::min(two, 1.0);
    EXPECT_LT(total, 1.03 * best) << two;  // within 3 % of always stepping with the faster count
    EXPECT_EQ(a.current(), two_faster ? 2 : 1);
  }
  EXPECT_EQ(max_threads(), 1);  // the destructors restored the count
}

TEST(AdaptiveThreads, FollowsALoadThatChangesDuringTheRun) {
  const ThreadCountGuard guard(1);
  double clock = 0;
  AdaptiveThreads a(2, [&] { return clock; });
  // Two threads twice as fast for the first 5000 steps, then (another process arrives) three times slower.
  const auto cost = [](int t, long n) { return t == 1 ? 0.01 : (n < 5000 ? 0.005 : 0.03); };
  simulate(a, clock, 5000, cost);
  EXPECT_EQ(a.current(), 2);
  const long one_before = a.steps_with_one();
  EXPECT_LT(one_before, 250);
  double clock_second = clock;
  const double second = simulate(a, clock, 5000, [&](int t, long n) { return cost(t, n + 5000); });
  EXPECT_EQ(a.current(), 1);
  EXPECT_GT(a.steps_with_one() - one_before, 4700);  // switched within the first blocks of the new load
  EXPECT_LT(second, 1.1 * 5000 * 0.01) << clock_second;
}

TEST(AdaptiveThreads, OnAnIdleMachineOnlyTheFirstMeasurementOfOneThreadIsPaid) {
  const ThreadCountGuard guard(1);
  const auto cost = [](int t, long) { return t == 2 ? 0.0066 : 0.011; };  // two threads 1.7x faster
  // The same run with the others' CPU unknown (every probe taken), idle (0 cores), and busy (one core).
  long one[3] = {}, skipped[3] = {};
  for (int k = 0; k < 3; ++k) {
    double clock = 0;
    const std::function<double()> others[3] = {
        [] { return std::numeric_limits<double>::quiet_NaN(); }, [] { return 0.0; }, [&] { return clock; }};
    AdaptiveThreads a(2, [&] { return clock; }, others[k]);
    simulate(a, clock, 20000, cost);
    EXPECT_EQ(a.current(), 2) << k;
    one[k] = a.steps_with_one(), skipped[k] = a.probes_skipped();
  }
  EXPECT_EQ(skipped[0], 0);
  EXPECT_EQ(skipped[2], 0);
  EXPECT_EQ(one[2], one[0]);  // a busy machine is probed as an unknown one
  EXPECT_GE(skipped[1], 5);   // 20000 steps: 4, 8, 16, 32, 64, 64, ... blocks between due probes
  // Idle: the first block of one thread only, against every probe's blocks otherwise. Its length: the steps that
  // bring it to 0.05 s of one-thread stepping, 5 of 0.011 s (4 are 0.044 s), not the 8 steps of the first block of
  // two threads (0.0528 s after the untimed first step).
  EXPECT_EQ(one[1], 5);
  EXPECT_GT(one[0], one[1] + 5 * 5);
}

TEST(AdaptiveThreads, AnIdleReadingDoesNotHideAContendedMachine) {
  // The others' CPU says idle throughout (e.g. a contending virtual machine without steal time), yet two threads
  // turn three times slower: the chosen count's blocks are compared with one thread's last measurement and the
  // chooser switches within blocks, as without the reading.
  const ThreadCountGuard guard(1);
  double clock = 0;
  AdaptiveThreads a(2, [&] { return clock; }, [] { return 0.0; });
  const auto cost = [](int t, long n) { return t == 1 ? 0.01 : (n < 5000 ? 0.005 : 0.03); };
  simulate(a, clock, 10000, cost);
  EXPECT_EQ(a.current(), 1);
  EXPECT_GT(a.probes_skipped(), 0);
  EXPECT_GT(a.steps_with_one(), 4700);
}

TEST(AdaptiveThreads, OthersCpuSecondsIsReadable) {
  // Linux: /proc/stat is there and the others' CPU seconds never decrease by more than a tick of rounding.
  const double a = others_cpu_seconds();
  ASSERT_TRUE(std::isfinite(a));
  volatile double x = 0;
  for (int i = 0; i < 20000000; ++i) x = x + 1e-9 * i;  // ~20 ms of this process's CPU
  const double b = others_cpu_seconds();
  EXPECT_GT(b, a - 0.05);
}

TEST(AdaptiveThreads, OneThreadIsNothingToChoose) {
  const ThreadCountGuard guard(3);
  double clock = 0;
  {
    AdaptiveThreads a(1, [&] { return clock; });
    simulate(a, clock, 100, [](int, long) { return 1.0; });
    EXPECT_EQ(a.steps_with_one(), 100);
    EXPECT_EQ(a.steps_with_most(), 100);  // most == one: the same count
  }
  EXPECT_EQ(max_threads(), 3);  // untouched: a chooser of one thread never sets the count
  EXPECT_THROW(AdaptiveThreads(0), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
