#include "sphstab/analysis/oscillation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sphstab {
namespace oscillation_test {

TEST(Oscillation, DampedSineGivesItsPeriodAndDecay) {
  // y = e^{-g t} sin(2 pi t / T): crossings at multiples of T/2 exactly (the envelope does not move them), extremes
  // shrink by e^{-g T} per period. Sampled at dt = T/400, linear interpolation of a sine's crossing is O(dt^3)-exact.
  const double T = 7.3, g = 0.02, dt = T / 400;
  std::vector<double> t, y;
  for (int k = 0; k <= 2200; ++k)
    t.push_back(k * dt), y.push_back(std::exp(-g * k * dt) * std::sin(2 * M_PI * k * dt / T));
  const OscillationMeasure m = measure_oscillation(t, y);
  ASSERT_EQ(m.crossings.size(), 10u);  // t = T/2 ... 5T (t = 0 is the first sample, not a crossing)
  for (std::size_t i = 0; i < m.crossings.size(); ++i) EXPECT_NEAR(m.crossings[i], (i + 1) * T / 2, 1e-6 * T);
  EXPECT_NEAR(m.period, T, 1e-6 * T);
  EXPECT_EQ(m.half_cycles, 9);
  // Extremes of a damped sine sit slightly before the quarter points; their ratio per period is still e^{-g T}.
  EXPECT_NEAR(m.decay_per_period, 1 - std::exp(-g * T), 1e-4);
  EXPECT_GT(m.extremes[0], 0);
  EXPECT_LT(m.extremes[1], 0);
  // A phase-shifted start: the first interval is short, and skip_first keeps it out of the period.
  std::vector<double> y2;
  for (double tk : t) y2.push_back(std::sin(2 * M_PI * tk / T + 0.4));
  EXPECT_NEAR(measure_oscillation(t, y2).period, T, 1e-6 * T);
  EXPECT_GT(std::abs(measure_oscillation(t, y2, false).period - T), 0.01 * T);
}

TEST(Oscillation, EdgeCasesAndBadInput) {
  EXPECT_TRUE(zero_crossings({0, 1, 2}, {1, 2, 3}).empty());
  EXPECT_EQ(zero_crossings({0, 1, 2, 3}, {1, 0, 0, -1}), std::vector<double>({1}));
  EXPECT_EQ(zero_crossings({0, 1}, {1, -3}), std::vector<double>({0.25}));
  EXPECT_TRUE(std::isnan(measure_oscillation({0, 1, 2}, {1, -1, -1}).period));
  EXPECT_THROW(zero_crossings({0, 1}, {1}), std::invalid_argument);
  EXPECT_THROW(zero_crossings({0, 0}, {1, -1}), std::invalid_argument);
  EXPECT_THROW(zero_crossings({0, 1}, {1, NAN}), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
