// The shared critical-load search: bracket and bisection against a known threshold, the two open outcomes, the
// test count, and bad input.
#include "sphstab/stability/load_bracket.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace sphstab {
namespace load_bracket_test {

TEST(LoadBracket, FindsAKnownThresholdUpAndDown) {
  const double t_star = 0.0123456789;
  int calls = 0;
  auto stable = [&](double t) {
    ++calls;
    return t < t_star;
  };
  for (double start : {1e-6, 3.0}) {  // doubling up from below, halving down from above
    calls = 0;
    LoadBracket b = bracket_critical_load(stable, start, 1e6, 1e-14, 2.0);
    ASSERT_EQ(b.outcome, LoadBracket::Outcome::Bracketed);
    EXPECT_TRUE(b.lo < t_star && t_star <= b.hi && b.hi == 2 * b.lo) << start;
    bisect_critical_load(b, stable, 1e-13);
    EXPECT_LE(b.hi / b.lo - 1, 1e-13);
    EXPECT_NEAR(b.critical(), t_star, 1e-13 * t_star);
    EXPECT_EQ(b.tests, calls);
  }
}

TEST(LoadBracket, ThresholdBetweenLastStepAndMaxIsBracketedByMax) {
  auto stable = [](double t) { return t < 7.0; };
  const LoadBracket b = bracket_critical_load(stable, 1.0, 7.5, 1e-3, 8.0);  // 8 > max, but max = 7.5 is unstable
  ASSERT_EQ(b.outcome, LoadBracket::Outcome::Bracketed);
  EXPECT_EQ(b.lo, 1.0);
  EXPECT_EQ(b.hi, 7.5);
}

TEST(LoadBracket, OpenOutcomes) {
  const LoadBracket always = bracket_critical_load([](double) { return true; }, 1.0, 100.0, 1e-3, 2.0);
  EXPECT_EQ(always.outcome, LoadBracket::Outcome::StableToMax);
  EXPECT_TRUE(std::isinf(always.critical()));
  EXPECT_EQ(always.lo, 100.0);
  const LoadBracket never = bracket_critical_load([](double) { return false; }, 1.0, 100.0, 1e-3, 2.0);
  EXPECT_EQ(never.outcome, LoadBracket::Outcome::UnstableToMin);
  EXPECT_EQ(never.critical(), 0.0);
  EXPECT_LT(never.hi, 2e-3);
}

TEST(LoadBracket, BadInput) {
  auto s = [](double) { return true; };
  EXPECT_THROW(bracket_critical_load(s, 1.0, 10.0, 1e-3, 1.0), std::invalid_argument);
  EXPECT_THROW(bracket_critical_load(s, -1.0, 10.0, 1e-3, 2.0), std::invalid_argument);
  EXPECT_THROW(bracket_critical_load(s, 1.0, INFINITY, 1e-3, 2.0), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
