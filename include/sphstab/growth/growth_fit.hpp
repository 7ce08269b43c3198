#pragma once
/// \file growth_fit.hpp
/// Measured exponential growth of a time series (kinetic energy of a perturbed run): least squares on log y over an
/// "exponential window", for comparison with the linear growth rate gamma of growth_rate.hpp (KE ~ e^{2 gamma t}).
///
/// Window (fit_exponential_growth): from the first time y exceeds onset_factor * reference (the growing mode then
/// dominates whatever bounded motion carries the reference energy: with onset_factor = 100 the bounded part is at
/// most 1 % of y; with envelope_time > 0 the reference follows the envelope of a decaying y down) up to t_linear_end
/// (the caller's end of the linear regime, e.g. when the largest displacement reaches a small fraction of the spacing).
/// The run counts as growing when the window holds at least min_points samples spanning a ratio of at least min_span in
/// y.
#include <limits>
#include <vector>

namespace sphstab {

/// Least-squares line log y = intercept + slope t.
struct LogLinearFit {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double slope = nan;
  double intercept = nan;
  double r2 = nan;  ///< coefficient of determination of the log-linear fit
  int points = 0;
  double t_begin = nan, t_end = nan;  ///< first and last sample time used
};

/// Fits log y against t over the samples with t_begin <= t <= t_end and y > 0 (others skipped).
/// Throws std::invalid_argument if t and y differ in size or fewer than 2 samples qualify.
LogLinearFit fit_log_linear(const std::vector<double>& t, const std::vector<double>& y, double t_begin, double t_end);

struct GrowthWindowOptions {
  double onset_factor = 100;  ///< window starts when y > onset_factor * reference (> 1)
  double min_span = 10;       ///< y(end)/y(start) of the window needed to call it growth (> 1)
  int min_points = 8;         ///< samples needed in the window (>= 2)
  /// > 0: adaptive reference for damped runs (e.g. with XSPH): at sample k the reference is
  /// min(reference, min_{j <= k} env_j) with the envelope env_j = max y over [t_j - envelope_time, t_j], so that a
  /// mode growing from the bottom of a decaying signal is found. 0: the fixed reference.
  double envelope_time = 0;
};

struct ExponentialGrowthFit {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  bool grew = false;       ///< a qualifying exponential window was found
  double gamma = nan;      ///< amplitude growth rate = slope / 2 (y ~ e^{2 gamma t}); NaN unless grew
  LogLinearFit fit;        ///< the window fit (NaN fields unless grew)
  double max_ratio = nan;  ///< max y / reference over the whole series
  /// Upper bound of gamma when no growth was detected: log(max(max_ratio, onset_factor)) / (2 (t_last - t_first)),
  /// the rate that would have reached the onset within the series; NaN when grew.
  double gamma_bound = nan;
  /// With envelope_time > 0: fit of log y from the minimum of the envelope to t_linear_end (the late-time trend
  /// of a damped run), computed when that span is at least a quarter of the series; NaN fields otherwise.
  LogLinearFit late;
  double gamma_late = nan;  ///< late.slope / 2
  double late_ratio = nan;  ///< max y after the envelope minimum / the envelope minimum
};

/// Exponential growth of y (e.g. kinetic energy) relative to `reference` (> 0, e.g. its initial value), with the
/// window described in the file comment. t must be increasing. Throws std::invalid_argument for size mismatches,
/// fewer than 2 samples, reference <= 0 or invalid options.
ExponentialGrowthFit fit_exponential_growth(const std::vector<double>& t, const std::vector<double>& y,
                                            double reference, double t_linear_end,
                                            const GrowthWindowOptions& options = {});

}  // namespace sphstab
