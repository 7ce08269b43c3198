#pragma once
// The pulse run of one tl-bar-wave-1d case [Ismail2009, §4.6.3, §5.3.1, Fig. 4.14] and its tables:
// - the leap-frog run of BarRun (bar_runs.hpp) to 1.9 L / c with the probe stresses at x = 0.05, 0.10, 0.15 m against
//   the exact linear solution sigma(x, t) = sigma_in(t - x / c) + sigma_in(t - (2L - x) / c) (common/ismail_bar.hpp):
//   the largest error per probe, the arrival (the first time the probe stress reaches half of its exact first peak,
//   linear in time between steps), the end-particle error every step (Hooke runs), probes_<run>.csv (base
//   resolution);
// - arrivals.csv (the three materials, base resolution) against c_b = sqrt(E / rho) and c_L = sqrt((lambda + 2 mu) /
//   rho), speeds.csv (the speed from the arrivals at 0.05 and 0.10 m, independent of the source) and the Markdown
//   tables of the arrivals, the speeds and the fixed-end comparison.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bar_runs.hpp"
#include "common/ismail_bar.hpp"
#include "common/study.hpp"
#include "fixed_end.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/run_observer.hpp"
#include "sphstab/io/csv.hpp"

namespace bar_wave {

struct PulseResult {
  std::vector<double> worst;           ///< per probe: max |sigma_sph - sigma_exact| over time, kPa
  std::vector<double> arrival;         ///< per probe: the arrival time (NaN if the threshold was not reached)
  std::vector<double> end_t, end_err;  ///< |sigma - exact| at the fixed-end probe, every step (Hooke runs)
  long steps = 0;
};

/// Runs r from rest; writes <out>/probes_<run>.csv when `write_probes`.
inline PulseResult pulse_run(BarRun& r, const Bar& bar, bool write_probes, const std::string& out) {
  const auto& disc = bar.disc;
  const double c = r.c;
  const bool fixed_end_run = r.run.fixed_end_run();
  PulseResult res;
  LeapfrogStepper stepper(r.sys, Eigen::VectorXd::Zero(r.tl.dofs()), Eigen::VectorXd::Zero(r.tl.dofs()));
  std::vector<std::string> cols{"t_us"};
  for (double xp : kProbes) {
    cols.push_back("sigma_sph_kpa_x" + format_number(xp));
    cols.push_back("sigma_exact_kpa_x" + format_number(xp));
  }
  std::unique_ptr<CsvWriter> pcsv;
  if (write_probes) pcsv = std::make_unique<CsvWriter>(out + "/probes_" + r.run.name + ".csv", cols, false);
  res.arrival.assign(kProbes.size(), std::nan(""));
  // arrival: the first time the probe stress reaches half of the exact first peak at the probe (-100 kPa in the
  // interior, -200 kPa at the fixed end where incident and reflected waves add), linear in time between steps
  std::vector<double> threshold(kProbes.size()), previous(kProbes.size(), 0.0);
  for (std::size_t p = 0; p < kProbes.size(); ++p) {
    const double xp = bar.probe_x(p);
    const double t_peak = xp / c + 0.5 * kDuration;  // mid-plateau of the incident wave
    threshold[p] = 0.5 * kStress * (shape(t_peak - xp / c) + shape(t_peak - (2 * kLength - xp) / c));
  }
  res.worst.assign(kProbes.size(), 0.0);
  double t_previous = 0;
  SnapshotFunction probes([&](const StepView& view) {
    const double t = view.time;
    r.set_time(t);
    const Eigen::MatrixXd P = r.tl.stresses(view.u);
    std::vector<CsvCell> row{t * 1e6};
    for (std::size_t p = 0; p < kProbes.size(); ++p) {
      const double xp = bar.probe_x(p);
      // 1D: T11 = P F / J; at this amplitude (strain 5e-7) P11 and T11 agree to 1e-6 relative
      const double s = P(disc->free[bar.probe_slot[p]], 0);
      const double exact = exact_stress(xp, t, c);
      row.push_back(s / 1e3);
      row.push_back(exact / 1e3);
      res.worst[p] = std::max(res.worst[p], std::abs(s - exact) / 1e3);
      if (fixed_end_run && p + 1 == kProbes.size())
        res.end_t.push_back(t), res.end_err.push_back(std::abs(s - exact) / 1e3);
      if (std::isnan(res.arrival[p]) && s <= threshold[p])
        res.arrival[p] = crossing_time(t_previous, previous[p], t, s, threshold[p]);
      previous[p] = s;
    }
    t_previous = t;
    if (write_probes) pcsv->row(row);
  });
  study::run_probed(stepper, r.dt, r.t_end, probes);
  res.steps = stepper.steps();
  return res;
}

/// arrivals.csv, speeds.csv and the Markdown tables of the arrivals, the speeds and the fixed ends.
struct PulseTables {
  CsvWriter arrivals, speeds;
  std::string md_arrivals, md_speed, md_fixed;
  explicit PulseTables(const std::string& out)
      : arrivals(out + "/arrivals.csv", {"run", "c_model", "probe_x", "particle_x", "t_arrival_sph_us",
                                         "t_expected_cb_us", "t_expected_cl_us", "error_vs_model_us"}),
        speeds(out + "/speeds.csv", {"run", "fixed_end", "n", "dx", "c_model", "speed_sph_005_010",
                                     "max_error_kpa_x0.05", "max_error_kpa_x0.1", "max_error_kpa_x0.15", "steps"}) {}

  /// The rows of one run; cb, cl: the bar and longitudinal speeds.
  void add(const BarRun& r, const Bar& bar, bool base, const PulseResult& res, double cb, double cl) {
    const Run& run = r.run;
    const double c = r.c;
    const std::vector<double>& worst = res.worst;
    // the half-amplitude time of the incoming stress at x = 0: shape(t) = 1/2 at t = kRise / 2
    const double t_half = kRise / 2;
    const bool with_arrivals = base && run.fixed_end == FixedEnd::Clamped;  // the arrival table: the three materials
    for (std::size_t p = 0; with_arrivals && p < kProbes.size(); ++p) {
      const double xp = bar.probe_x(p);
      const double tb = t_half + xp / cb, tlong = t_half + xp / cl, tm = t_half + xp / c;
      arrivals.row(
          {run.name, c, kProbes[p], xp, res.arrival[p] * 1e6, tb * 1e6, tlong * 1e6, (res.arrival[p] - tm) * 1e6});
      study::md_row(md_arrivals, {run.name, study::fixed(kProbes[p], 2), study::fixed(res.arrival[p] * 1e6, 3),
                                  study::fixed(tb * 1e6, 3), study::fixed(tlong * 1e6, 3),
                                  study::fixed((res.arrival[p] - tm) * 1e6, 3, true)});
    }
    // speed from the arrivals at 0.05 and 0.10 m (independent of the source)
    const double x0 = bar.probe_x(0), x1 = bar.probe_x(1);
    const double speed = (x1 - x0) / (res.arrival[1] - res.arrival[0]);
    speeds.row(
        {run.name, fixed_end_name(run.fixed_end), bar.n, bar.dx, c, speed, worst[0], worst[1], worst[2], res.steps});
    if (run.fixed_end_run())  // the fixed-end comparison: Hooke 1D stress, every method
      study::md_row(md_fixed, {fixed_end_name(run.fixed_end), std::to_string(bar.n), study::sig(worst[0], 3),
                               study::sig(worst[1], 3), study::sig(worst[2], 3)});
    study::md_row(md_speed, {run.name, std::to_string(bar.n), study::sig(c, 6), study::sig(speed, 6),
                             study::fixed(100 * (speed / c - 1), 3, true) + " %", study::sig(worst[0], 3),
                             study::sig(worst[1], 3), study::sig(worst[2], 3), std::to_string(res.steps)});
  }

  void summarise(study::Summary& summary) const {
    summary.set("arrivals", md_arrivals);
    summary.set("speeds", md_speed);
    summary.set("fixed_end", md_fixed);
  }
};

}  // namespace bar_wave
