#pragma once
// The convergence rates of the speed-vs-error sweep, per kernel, h/dx, boundary and formulation: the slope of L1 at
// t_end and of its time mean against n over the asymptotic range n >= 200, the slope of L1 against wall seconds, L1
// at the largest n and the number of completed runs; the rows of rates.csv.
#include <cmath>
#include <string>
#include <vector>

#include "bar_formulations.hpp"
#include "common/study.hpp"
#include "sphstab/io/csv.hpp"
#include "velocity_jump_run.hpp"

namespace speed_error {

/// One row of rates.csv, keyed "kernel | h/dx | boundary | formulation" for the summary.
struct RateRow {
  std::string key;
  double rate, rate_mean, slope_s, l1_max;
  int completed;
};

/// The rates of every configuration of the sweep (kernels x ratios x boundaries x formulations, in that order),
/// written to <out>/rates.csv.
inline std::vector<RateRow> convergence_rates(const std::string& out, const std::vector<RunRecord>& records,
                                              const std::vector<KernelType>& kernels, const std::vector<double>& ratios,
                                              const std::vector<BarBoundary>& boundaries, const std::vector<int>& ns) {
  using study::sig;
  // Convergence rates: slope of L1(t = 1.5) against N over N >= 200 (asymptotic range) and against seconds.
  CsvWriter rates_csv(out + "/rates.csv", {"kernel", "h_over_dx", "boundary", "formulation", "l1_rate_vs_n",
                                           "l1_mean_rate_vs_n", "l1_vs_seconds_slope", "l1_at_nmax", "completed"});
  std::vector<RateRow> rate_rows;
  for (KernelType kt : kernels)
    for (double hr : ratios)
      for (BarBoundary bnd : boundaries)
        for (const auto& form : formulations()) {
          std::vector<double> n, e, em, s;
          int done = 0;
          double l1max = NAN;
          for (const auto& r : records)
            if (r.kernel == kernel_name(kt) && r.h_over_dx == hr && r.boundary == bar_boundary_name(bnd) &&
                r.form == form.name) {
              if (r.status == "completed") ++done;
              if (r.n == ns.back()) l1max = r.l1;
              if (r.n < 200 && ns.back() > 200) continue;
              n.push_back(r.n);
              e.push_back(r.l1);
              em.push_back(r.l1_mean);
              s.push_back(r.total_s);
            }
          // study::loglog_slope skips the NaN errors of runs that blew up (L1 >= 0, wall seconds > 0), so the rates
          // use completed runs only.
          const double rate = -study::loglog_slope(n, e), rate_m = -study::loglog_slope(n, em),
                       slope_s = study::loglog_slope(s, e);
          rates_csv.row({kernel_name(kt), hr, bar_boundary_name(bnd), form.name, rate, rate_m, slope_s, l1max,
                         static_cast<long>(done)});
          rate_rows.push_back(
              {kernel_name(kt) + " | " + sig(hr, 4) + " | " + bar_boundary_name(bnd) + " | " + form.name, rate, rate_m,
               slope_s, l1max, done});
        }
  return rate_rows;
}

}  // namespace speed_error
