#include "sphstab/analysis/oscillation.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sphstab {

std::vector<double> zero_crossings(const std::vector<double>& t, const std::vector<double>& y) {
  if (t.size() != y.size())
    throw std::invalid_argument("zero_crossings: " + std::to_string(t.size()) + " times but " +
                                std::to_string(y.size()) + " values");
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k]) || !std::isfinite(y[k]))
      throw std::invalid_argument("zero_crossings: non-finite sample at index " + std::to_string(k));
    if (k > 0 && !(t[k] > t[k - 1]))
      throw std::invalid_argument("zero_crossings: times not strictly increasing at index " + std::to_string(k));
  }
  std::vector<double> c;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double a = y[k - 1], b = y[k];
    if (b == 0) {
      if (a != 0) c.push_back(t[k]);  // a run of zeros counts once, at its start
    } else if (a != 0 && (a > 0) != (b > 0)) {
      c.push_back(t[k - 1] + (t[k] - t[k - 1]) * a / (a - b));
    }
  }
  return c;
}

OscillationMeasure measure_oscillation(const std::vector<double>& t, const std::vector<double>& y, bool skip_first) {
  OscillationMeasure m;
  m.crossings = zero_crossings(t, y);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Extreme of each interval [previous crossing, crossing): samples strictly before the crossing time.
  std::size_t k = 0;
  for (double c : m.crossings) {
    double e = 0;
    for (; k < t.size() && t[k] < c; ++k)
      if (std::abs(y[k]) > std::abs(e)) e = y[k];
    m.extremes.push_back(e);
  }
  const std::size_t first = skip_first ? 1 : 0;
  // Crossing intervals: with skip_first, from the first crossing on; without, t[0] counts as the start.
  std::vector<double> starts;
  if (!skip_first && !t.empty()) starts.push_back(t.front());
  starts.insert(starts.end(), m.crossings.begin(), m.crossings.end());
  m.half_cycles = starts.size() >= 2 ? static_cast<int>(starts.size()) - 1 : 0;
  m.period = m.half_cycles > 0 ? 2 * (starts.back() - starts.front()) / m.half_cycles : nan;
  const long n = static_cast<long>(m.extremes.size()) - static_cast<long>(first);
  if (n >= 2 && m.extremes[first] != 0) {
    const double ratio = std::abs(m.extremes.back() / m.extremes[first]);
    m.decay_per_period = 1 - std::pow(ratio, 2.0 / static_cast<double>(n - 1));
  } else {
    m.decay_per_period = nan;
  }
  return m;
}

}  // namespace sphstab
