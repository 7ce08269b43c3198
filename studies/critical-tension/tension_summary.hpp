#pragma once
// The key numbers of the critical-tension study for summary.md.in [Powell2012, ch. 3, Fig. 3.2 and conclusions
// p. 99-100], assembled from the cases of tension_cases.hpp: route timings, agreement of the two routes, the ratio of
// the first-minor estimate (3.42) to T_crit (conclusion 1), the h/dx band of the largest T_crit per kernel (3), the
// spread over kernels (4, 5), the form ratios (6), the windows of a positive infinite-lattice limit, the exponents of
// T_crit ~ N^-p and the growth rates above T_crit.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "tension_cases.hpp"
#include "tension_tables.hpp"

namespace tcrit {

using study::sig;

/// Smallest and largest of the values added.
struct Range {
  double lo = INFINITY, hi = -INFINITY;
  void add(double v) { lo = std::min(lo, v), hi = std::max(hi, v); }
  /// Summary keys <key>_min and <key>_max.
  void put(study::Summary& s, const std::string& key, int digits = 3) const {
    s.set(key + "_min", lo, digits);
    s.set(key + "_max", hi, digits);
  }
};

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? std::nan("") : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

inline bool near(double a, double b) { return std::abs(a - b) < 1e-12; }

/// Appends a Markdown table row to `table` (study::md_row).
template <class... T>
void md_row(std::string& table, const T&... v) {
  study::md_row(table, {std::string(v)...});
}

/// The wall time of the N = 30 sweep per route (the target: below 1 s with both routes) and of T_crit versus N.
inline void summarise_timing(study::Summary& sum, const std::map<std::string, double>& timing, int versus_n_cases,
                             double versus_n_seconds) {
  sum.set("t_eig", timing.at("eig"));
  sum.set("t_bisect", timing.at("bisect"));
  sum.set("t_both", timing.at("both"));
  sum.set("target_met", timing.at("both") < 1.0 ? "met" : "NOT met");
  sum.set("versus_n_cases", versus_n_cases);
  sum.set("versus_n_seconds", versus_n_seconds);
}

/// The N = 30 sweep: route agreement, estimate ratios, forms, the per-kernel table and the spread over kernels.
inline void summarise_sweep(study::Summary& sum, const std::vector<SweepRow>& sweep) {
  double max_form_dev = 0;
  for (const auto& s : sweep) {
    const double ru = s.t_uncorrected / s.r.load, rp = s.t_plus / s.r.load;
    max_form_dev = std::max({max_form_dev, std::abs(ru / 4 - 1), std::abs(rp / 2 - 1)});
  }
  const SweepRow* worst = nullptr;  // largest disagreement of the two routes
  int finite = 0, successful = 0, above_1e8 = 0, zero_limit = 0, positive_limit = 0, neutral = 0;
  Range above_1e8_tcrit, ratios, ratio_small, ratio_mid, minor_ratio;
  std::map<KernelType, std::vector<double>> ratio_by_kernel, tcrit_large_h, window;  // window: h with T_inf > 1e-12
  std::map<KernelType, Range> ratio_small_h, band;                                   // band: T_crit over 1.2 <= h <= 2
  std::map<KernelType, std::pair<double, double>> peak;                              // (T_crit max, h at max)
  std::map<double, Range> spread;                                                    // h -> T_crit over kernels
  std::map<double, std::pair<double, KernelType>> leader;                            // h -> (max T_crit, kernel)
  std::vector<double> all_ratios;
  for (const auto& s : sweep) {
    finite += std::isfinite(s.r.load);
    successful += s.r.status == Status::Successful;
    if (s.r.relative_difference > 1e-8) ++above_1e8, above_1e8_tcrit.add(s.r.load);
    if (s.r.relative_difference > (worst ? worst->r.relative_difference : 0)) worst = &s;
    const double ratio = s.est.first_minor / s.r.load;
    ratio_by_kernel[s.kernel].push_back(ratio);
    all_ratios.push_back(ratio);
    ratios.add(ratio);
    if (s.h <= 1.0 + 1e-12) ratio_small_h[s.kernel].add(ratio), ratio_small.add(ratio);
    if (s.h > 1.0 + 1e-12 && s.h <= 1.4 + 1e-12) ratio_mid.add(ratio);
    if (s.r.load > peak[s.kernel].first) peak[s.kernel] = {s.r.load, s.h};
    if (s.h >= 1.2 - 1e-12 && s.h <= 2.0 + 1e-12) band[s.kernel].add(s.r.load);
    if (s.h >= 1.5 - 1e-12) tcrit_large_h[s.kernel].push_back(s.r.load);
    if (s.inf.tcrit > 1e-12) window[s.kernel].push_back(s.h);
    spread[s.h].add(s.r.load);
    minor_ratio.add(s.est.first_minor / s.est.second_minor);
    if (s.r.load > leader[s.h].first) leader[s.h] = {s.r.load, s.kernel};
    (s.inf.tcrit == 0 ? zero_limit : s.inf.tcrit > 1e-12 ? positive_limit : neutral) += 1;
  }
  sum.set("max_rel_diff", worst ? worst->r.relative_difference : 0.0, 2);
  sum.set("max_rel_diff_kernel", worst ? kernel_name(worst->kernel) : std::string());
  sum.set("max_rel_diff_h", num(worst ? worst->h : 0.0));
  sum.set("above_1e8_range", above_1e8 ? " (all with T_crit between " + sig(above_1e8_tcrit.lo) + " and " +
                                             sig(above_1e8_tcrit.hi) +
                                             ", where K is ill-conditioned; see Numerical reliability)"
                                       : std::string());
  sum.set("max_form_dev", max_form_dev, 2);
  sum.set("cases", static_cast<int>(sweep.size()));
  sum.set("finite", finite);
  sum.set("successful", successful);
  sum.set("above_1e8", above_1e8);
  sum.set("zero_limit_cases", zero_limit);
  sum.set("positive_limit_cases", positive_limit);
  sum.set("neutral_cases", neutral);
  sum.set("ratio_min", ratios.lo);
  sum.set("ratio_max", ratios.hi);
  sum.set("ratio_median", median(all_ratios));
  sum.set("ratio_small", ratio_small.lo, 4);
  ratio_mid.put(sum, "ratio_mid");
  minor_ratio.put(sum, "minor_ratio");

  std::string kernel_table, peak_list, median_list;
  Range band_max;
  int peaks_in_range = 0;
  for (KernelType type : kKernels) {
    const std::string name = kernel_name(type);
    const auto& v = ratio_by_kernel[type];
    md_row(kernel_table, name, sig(peak[type].first), num(peak[type].second),
           sig(band[type].lo) + " .. " + sig(band[type].hi),
           sig(ratio_small_h[type].lo) + " .. " + sig(ratio_small_h[type].hi), sig(median(v)),
           sig(*std::max_element(v.begin(), v.end())));
    band_max.add(band[type].hi);
    if (peak[type].second >= 1.2 - 1e-12 && peak[type].second <= 2.0 + 1e-12) ++peaks_in_range;
    peak_list += (peak_list.empty() ? "" : ", ") + name + " " + num(peak[type].second);
    median_list += (median_list.empty() ? "" : ", ") + name + " " + sig(median(tcrit_large_h[type]));
    // h/dx with T_crit,inf > 1e-12, as runs of consecutive grid values.
    const auto& w = window[type];
    std::string t;
    for (size_t i = 0, j = 0; i < w.size(); i = ++j) {
      while (j + 1 < w.size() && std::abs(w[j + 1] - w[j] - 0.05) < 1e-9) ++j;
      t += (t.empty() ? "" : ", ") + num(w[i]) + (j > i ? "-" + num(w[j]) : "");
    }
    sum.set("window_" + name, t.empty() ? "none" : t);
  }
  sum.set("kernel_table", kernel_table);
  band_max.put(sum, "band_max");
  sum.set("peaks_in_range", peaks_in_range);
  sum.set("kernels", static_cast<int>(kKernels.size()));
  sum.set("peak_list", peak_list);
  sum.set("median_tcrit_large_h", median_list);
  Range spread_small;
  double spread_large_max = 0;
  for (auto& [h, sp] : spread) {
    if (h <= 1.4 + 1e-12)
      spread_small.add(sp.hi / sp.lo);
    else
      spread_large_max = std::max(spread_large_max, sp.hi / sp.lo);
  }
  spread_small.put(sum, "spread_small", 2);
  sum.set("spread_large_max", spread_large_max, 2);
  double c2_leads_up_to = 0;
  for (auto& [h, ld] : leader) {
    if (ld.second != KernelType::WendlandC2) break;
    c2_leads_up_to = h;
  }
  sum.set("c2_leads_up_to", num(c2_leads_up_to));
}

/// T_crit versus N: the exponent table, the exponents where T_crit,inf = 0 and L^(pi/dx) > 0, the first-minor ratio
/// and T_crit at N = 960 (h/dx = 1.2), and the first N at which the cubic spline at h/dx = 2 is not reliable.
inline void summarise_versus_n(study::Summary& sum, const std::vector<NRow>& nrows,
                               const std::vector<ExponentFit>& fits, int n_cons) {
  std::string exponent_table;
  Range p_zero_limit;  // exponents where T_crit,inf = 0 and L^(pi/dx) > 0
  for (const auto& e : fits) {
    if (e.inf.tcrit == 0 && e.inf.l_hat_sawtooth > 1e-12) p_zero_limit.add(e.p);
    if (e.kernel == KernelType::CubicSpline && near(e.h, 2.0)) sum.set("cubic2_p", e.p, 2);
    md_row(exponent_table, kernel_name(e.kernel), num(e.h), sig(e.inf.l_hat_sawtooth), sig(e.inf.tcrit), sig(e.t30),
           sig(e.t960), sig(e.p), sig(e.pe), std::to_string(e.n_lo) + "-" + std::to_string(e.n_hi));
  }
  sum.set("exponent_table", exponent_table);
  p_zero_limit.put(sum, "p_zero_limit");
  Range r960, t960;
  for (const auto& r : nrows)
    if (r.n == 960 && near(r.h, 1.2) && r.r.status == Status::Successful) {
      r960.add(tension_estimates_1d(Kernel<1>(r.kernel), r.h, 1.0, n_cons).first_minor / r.r.load);
      t960.add(r.r.load);
    }
  r960.put(sum, "ratio_960");
  t960.put(sum, "tcrit_960");
  int cubic2_first_bad = 0;
  for (const auto& r : nrows)
    if (r.kernel == KernelType::CubicSpline && near(r.h, 2.0) && r.r.status != Status::Successful && !cubic2_first_bad)
      cubic2_first_bad = r.n;
  sum.set("cubic2_first_bad", cubic2_first_bad);
}

/// The growth rate at T = 1.5 T_crit over the kernels.
inline void summarise_growth(study::Summary& sum, const std::vector<GrowthRow>& growth) {
  Range growth_15;
  for (const auto& r : growth)
    if (r.factor == 1.5) growth_15.add(r.g.growth_rate);
  growth_15.put(sum, "growth", 2);
}

}  // namespace tcrit
