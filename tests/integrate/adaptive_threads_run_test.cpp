// The run loop's thread choice (core/adaptive_threads.hpp) on a real run: with two threads the run steps with both
// counts (the first two blocks measure each), ends in the same bits as one thread and as two fixed threads, and says
// how many steps it took on one thread.
#include <gtest/gtest.h>

#include "sphstab/core/adaptive_threads.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/integrate/scene_run.hpp"
#include "sphstab/problems/gms_scenes.hpp"

namespace sphstab {
namespace adaptive_threads_run_test {

TEST(AdaptiveThreadsRun, BothCountsStepTheSameBits) {
  const Scene<2> rings = gms_rings_scene({});  // 4392 particles: 2 threads really split the rows (threads_for)
  ASSERT_GE(rings.scheme->discretisation().particles.size(), 2 * kMinRowsPerThread);
  RateFormRunOptions o = scene_run_options(rings);
  o.t_end = 300 * o.dt;
  RateFormRunResult one, adaptive, fixed;
  {
    const ThreadCountGuard guard(1);
    one = run_rate_form(*rings.scheme, rings.y0, o);
  }
  {
    const ThreadCountGuard guard(2);
    adaptive = run_rate_form(*rings.scheme, rings.y0, o);
    set_fixed_threads(true);
    fixed = run_rate_form(*rings.scheme, rings.y0, o);
    set_fixed_threads(false);
  }
  ASSERT_TRUE(one.completed() && adaptive.completed() && fixed.completed());
  EXPECT_EQ(one.threads, 1);
  EXPECT_EQ(one.steps_on_one_thread, one.steps);
  EXPECT_EQ(adaptive.threads, 2);
  // The first block (two threads) ends once it has stepped kMinBlockSeconds, at most twice that with the doubling;
  // a run of 4 x kMinBlockSeconds has measured one thread too (on this machine ~0.3 s; checked when it took as long).
  if (adaptive.wall_seconds >= 4 * AdaptiveThreads::kMinBlockSeconds) EXPECT_GT(adaptive.steps_on_one_thread, 0);
  EXPECT_LT(adaptive.steps_on_one_thread, adaptive.steps);
  EXPECT_EQ(fixed.threads, 2);
  EXPECT_EQ(fixed.steps_on_one_thread, 0);
  EXPECT_EQ(one.y, adaptive.y);
  EXPECT_EQ(one.y, fixed.y);
  EXPECT_EQ(one.kinetic_energy, adaptive.kinetic_energy);
  EXPECT_EQ(max_threads(), 1);  // ctest's OMP_NUM_THREADS=1 / the guards: the run restored the count it found
}

}  // namespace adaptive_threads_run_test
}  // namespace sphstab
