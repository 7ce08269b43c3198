#include "sphstab/growth/growth_fit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphstab {

LogLinearFit fit_log_linear(const std::vector<double>& t, const std::vector<double>& y, double t_begin, double t_end) {
  if (t.size() != y.size())
    throw std::invalid_argument("fit_log_linear: t has " + std::to_string(t.size()) + " samples, y has " +
                                std::to_string(y.size()));
  double st = 0, sl = 0, stt = 0, stl = 0, sll = 0;
  int n = 0;
  LogLinearFit f;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!(t[k] >= t_begin && t[k] <= t_end) || !(y[k] > 0) || !std::isfinite(y[k])) continue;
    const double l = std::log(y[k]);
    st += t[k];
    sl += l;
    stt += t[k] * t[k];
    stl += t[k] * l;
    sll += l * l;
    if (n == 0) f.t_begin = t[k];
    f.t_end = t[k];
    ++n;
  }
  if (n < 2)
    throw std::invalid_argument("fit_log_linear: fewer than 2 positive samples in [" + std::to_string(t_begin) + ", " +
                                std::to_string(t_end) + "]");
  const double mt = st / n, ml = sl / n;
  const double vtt = stt / n - mt * mt, vtl = stl / n - mt * ml, vll = sll / n - ml * ml;
  if (!(vtt > 0)) throw std::invalid_argument("fit_log_linear: all sample times are equal");
  f.slope = vtl / vtt;
  f.intercept = ml - f.slope * mt;
  f.r2 = vll > 0 ? (vtl * vtl) / (vtt * vll) : 1.0;
  f.points = n;
  return f;
}

ExponentialGrowthFit fit_exponential_growth(const std::vector<double>& t, const std::vector<double>& y,
                                            double reference, double t_linear_end, const GrowthWindowOptions& o) {
  const char* who = "fit_exponential_growth";
  if (t.size() != y.size() || t.size() < 2)
    throw std::invalid_argument(std::string(who) + ": need t and y of equal size >= 2 (got " +
                                std::to_string(t.size()) + ", " + std::to_string(y.size()) + ")");
  if (!(reference > 0) || !std::isfinite(reference))
    throw std::invalid_argument(std::string(who) + ": reference must be finite and > 0 (got " +
                                std::to_string(reference) + ")");
  if (!(o.onset_factor > 1) || !(o.min_span > 1) || o.min_points < 2 || !(o.envelope_time >= 0))
    throw std::invalid_argument(std::string(who) +
                                ": need onset_factor > 1, min_span > 1, min_points >= 2, envelope_time >= 0");
  ExponentialGrowthFit out;
  double ymax = 0;
  for (double v : y)
    if (std::isfinite(v)) ymax = std::max(ymax, v);
  out.max_ratio = ymax / reference;
  // Envelope env_k = max y over [t_k - envelope_time, t_k] (only with envelope_time > 0).
  std::vector<double> env;
  if (o.envelope_time > 0) {
    env.resize(t.size());
    std::size_t lo = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      while (t[lo] < t[k] - o.envelope_time) ++lo;
      double e = 0;
      for (std::size_t j = lo; j <= k; ++j)
        if (std::isfinite(y[j])) e = std::max(e, y[j]);
      env[k] = e;
    }
  }
  std::size_t start = t.size();
  double ref = reference;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!env.empty() && env[k] > 0) ref = std::min(ref, env[k]);
    if (t[k] <= t_linear_end && y[k] > o.onset_factor * ref && std::isfinite(y[k])) {
      start = k;
      break;
    }
  }
  if (!env.empty()) {  // late-time trend after the envelope minimum
    std::size_t kmin = 0, last = 0;
    for (std::size_t k = 0; k < t.size() && t[k] <= t_linear_end; ++k) {
      last = k;
      if (env[k] > 0 && (env[kmin] <= 0 || env[k] < env[kmin])) kmin = k;
    }
    if (last > kmin + 1 && t[last] - t[kmin] >= 0.25 * (t.back() - t.front()) && env[kmin] > 0) {
      out.late = fit_log_linear(t, y, t[kmin], t[last]);
      out.gamma_late = 0.5 * out.late.slope;
      double m = 0;
      for (std::size_t k = kmin; k <= last; ++k)
        if (std::isfinite(y[k])) m = std::max(m, y[k]);
      out.late_ratio = m / env[kmin];
    }
  }
  std::size_t last = start;
  for (std::size_t k = start; k < t.size() && t[k] <= t_linear_end; ++k) last = k;
  const int points = start < t.size() ? static_cast<int>(last - start + 1) : 0;
  if (points >= o.min_points && y[last] / y[start] >= o.min_span) {
    out.fit = fit_log_linear(t, y, t[start], t[last]);
    out.gamma = 0.5 * out.fit.slope;
    out.grew = out.gamma > 0;
  }
  if (!out.grew) {
    out.fit = LogLinearFit{};
    out.gamma = ExponentialGrowthFit::nan;
    const double span = t.back() - t.front();
    out.gamma_bound =
        span > 0 ? std::log(std::max(out.max_ratio, o.onset_factor)) / (2 * span) : ExponentialGrowthFit::nan;
  }
  return out;
}

}  // namespace sphstab
