#pragma once
/// \file oscillation.hpp
/// Period and amplitude of a sampled oscillation y(t) (a plate's tip displacement): zero crossings by linear
/// interpolation between samples of opposite sign, the signed extreme of every half cycle between crossings, and the
/// period and decay they imply. The first half cycle (from t[0] to the first crossing) is reported but left out of
/// the period when asked: a run started from an approximate mode shape has a transient there.
#include <vector>

namespace sphstab {

/// Times where y changes sign, linearly interpolated between consecutive samples (a sample exactly 0 counts as a
/// crossing at that time, once). t must be strictly increasing and as long as y; throws std::invalid_argument
/// otherwise or for non-finite values.
std::vector<double> zero_crossings(const std::vector<double>& t, const std::vector<double>& y);

struct OscillationMeasure {
  std::vector<double> crossings;  ///< zero-crossing times
  /// Signed extreme of y on each interval between consecutive crossings (the first from t[0]); one per half cycle
  /// that ended at a crossing.
  std::vector<double> extremes;
  double period = 0;    ///< 2 x mean crossing interval over the crossings used (NaN with fewer than 2)
  int half_cycles = 0;  ///< crossing intervals used for the period
  /// Mean fractional amplitude loss per period, 1 - (|e_last| / |e_first|)^(2 / (n - 1)) over the extremes used
  /// (NaN with fewer than 2); negative for growth.
  double decay_per_period = 0;
};

/// The oscillation's crossings, extremes, period and decay. skip_first: leave the first crossing interval and the
/// first extreme out of the period and the decay. Throws what zero_crossings throws.
OscillationMeasure measure_oscillation(const std::vector<double>& t, const std::vector<double>& y,
                                       bool skip_first = true);

}  // namespace sphstab
