#pragma once
/// \file plate_tables.hpp
/// The study's output: one CSV row per run (the same columns in every table: periods, convergence, clamp, dt,
/// viscosity, eps, root, si) and the summary numbers and Markdown tables of each phase, rendered into summary.md by
/// summary.md.in. Resolution: the observed order of the period and its Richardson limit from the three finest plates.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "linear_period.hpp"
#include "plate_case.hpp"
#include "plate_run.hpp"
#include "sphstab/io/csv.hpp"

namespace sphstab::gms_plate {

inline std::vector<CsvCell> run_cells(const PlateRun& r) {
  const PlateCase& c = r.c;
  const double thin = thin_period(c), timo = timoshenko_period(c);
  return {c.tag,
          c.thickness,
          c.across,
          c.thickness / c.across,
          c.mu,
          c.tip_speed,
          c.eps,
          c.alpha,
          c.beta,
          c.clamp_layers,
          c.cfl,
          r.particles,
          r.dt,
          r.steps,
          r.status,
          r.osc.period,
          static_cast<int>(r.osc.crossings.size()),
          r.osc.crossings.empty() ? kNaN : r.osc.crossings[0],
          r.osc.decay_per_period,
          r.osc.extremes.empty() ? kNaN : std::abs(r.osc.extremes[0]),
          c.paper,
          r.osc.period / c.paper - 1,
          thin,
          timo,
          r.osc.period / timo - 1,
          r.max_stretch,
          *std::max_element(r.fragments.begin(), r.fragments.end()),
          r.break_time,
          r.break_x,
          r.wall,
          r.cpu};
}

inline const std::vector<std::string> kRunColumns = {"tag",
                                                     "H",
                                                     "across",
                                                     "dp",
                                                     "mu",
                                                     "tip_speed",
                                                     "eps",
                                                     "alpha",
                                                     "beta",
                                                     "clamp_layers",
                                                     "cfl",
                                                     "particles",
                                                     "dt",
                                                     "steps",
                                                     "status",
                                                     "period",
                                                     "crossings",
                                                     "first_crossing",
                                                     "decay_per_period",
                                                     "first_amplitude",
                                                     "paper_period",
                                                     "error_vs_paper",
                                                     "thin_period",
                                                     "timoshenko_period",
                                                     "error_vs_timoshenko",
                                                     "max_bond_stretch",
                                                     "max_fragments",
                                                     "break_time",
                                                     "break_x",
                                                     "wall_seconds",
                                                     "cpu_seconds"};

/// The runs of `group`, in its order, as rows of `path`.
inline void write_runs(const std::string& path, const std::vector<PlateRun>& runs,
                       const std::vector<PlateCase>& group) {
  CsvWriter w(path, kRunColumns);
  for (const PlateCase& c : group) w.row(run_cells(find_run(runs, c)));
}

/// The SI plate's numbers.
inline void summarise_si(study::Summary& sum, const PlateRun& r) {
  const PlateCase& si = r.c;
  sum.set("si_particles", r.particles);
  sum.set("si_steps", r.steps);
  sum.set("si_period", r.osc.period, 4);
  sum.set("si_thin", thin_period(si), 4);
  sum.set("si_timoshenko", timoshenko_period(si), 4);
  sum.set("si_vs_timoshenko", 100 * (r.osc.period / timoshenko_period(si) - 1), 3);
  sum.set("si_amplitude_mm", r.osc.extremes.empty() ? kNaN : 1e3 * std::abs(r.osc.extremes[0]), 3);
  sum.set("si_decay", 100 * r.osc.decay_per_period, 2);
  sum.set("si_crossings", static_cast<long>(r.osc.crossings.size()));
  sum.set("si_wall", r.wall, 3);
  sum.set("si_us", 1e6 * r.wall / (static_cast<double>(r.steps) * r.particles), 3);
  sum.set("si_status", r.status);
}

/// linear.csv: the spectral bending period of the initial state at the resolutions of `conv` whose spectrum fits (at
/// most 14 across), beside the run's period; the summary takes the row at `across`.
inline void write_linear_periods(const std::string& out, const std::vector<PlateCase>& conv, int across,
                                 const std::vector<PlateRun>& runs, study::Summary& sum) {
  CsvWriter w(out + "/linear.csv", {"H", "across", "dp", "mu", "linear_period", "overlap", "softer_modes",
                                    "growth_rate", "run_period_vf0.01", "thin_period", "timoshenko_period"});
  for (const PlateCase& c : conv) {
    if (c.across > 14) continue;
    const LinearPeriod lp = linear_period(c);
    const double run_period = find_run(runs, c).osc.period;
    w.row({c.thickness, c.across, c.thickness / c.across, c.mu, lp.period, lp.overlap, lp.softer, lp.growth_rate,
           run_period, thin_period(c), timoshenko_period(c)});
    if (c.across == across) {
      sum.set("linear_period", lp.period, 5);
      sum.set("linear_overlap", lp.overlap, 4);
      sum.set("linear_softer", lp.softer);
      sum.set("linear_vs_run", run_period / lp.period - 1, 2);
    }
  }
}

/// GMS Tables 1 and 2 against the runs: the Markdown table and the largest differences per thickness.
inline void summarise_tables(study::Summary& sum, const std::vector<PlateCase>& table,
                             const std::vector<PlateRun>& runs) {
  double worst_h2 = 0, worst_h1 = 0;
  std::string md;
  for (const PlateCase& c : table) {
    const PlateRun& r = find_run(runs, c);
    const double e = r.osc.period / c.paper - 1;
    double& worst = c.thickness == 2 ? worst_h2 : worst_h1;
    worst = std::max(worst, std::abs(e));
    study::md_row(md, {study::fixed(c.thickness, 0), study::fixed(c.mu, 2), study::sig(c.tip_speed, 2),
                       std::to_string(c.across), study::fixed(c.paper, 1), study::fixed(r.osc.period, 1),
                       study::fixed(100 * e, 1, true), study::fixed(thin_period(c), 1),
                       study::fixed(timoshenko_period(c), 1), study::fixed(100 * r.osc.decay_per_period, 1), r.status});
  }
  sum.set("table", md);
  sum.set("worst_h2", 100 * worst_h2, 2);
  sum.set("worst_h1", 100 * worst_h1, 2);
}

/// The resolution study (H = 2, mu = 0.22, V_f = 0.01): its table, and T(dp) = T0 + C dp^p through the three finest
/// plates (p from the ratio of differences, any spacing, by bisection) written to extrapolation.csv.
inline void summarise_convergence(study::Summary& sum, const std::string& out, const std::vector<PlateCase>& conv,
                                  const std::vector<PlateRun>& runs) {
  std::string md;
  std::vector<double> dps, Ts;
  for (const PlateCase& c : conv) {
    const PlateRun& r = find_run(runs, c);
    dps.push_back(c.thickness / c.across), Ts.push_back(r.osc.period);
    study::md_row(md, {std::to_string(c.across), study::sig(c.thickness / c.across, 3), std::to_string(r.particles),
                       study::fixed(r.osc.period, 1), study::fixed(100 * (r.osc.period / 1671.5 - 1), 1, true),
                       study::fixed(100 * r.osc.decay_per_period, 2), study::fixed(r.wall, 0)});
  }
  sum.set("convergence", md);
  const std::size_t m = Ts.size();
  if (m >= 3) {
    const double d1 = dps[m - 3], d2 = dps[m - 2], d3 = dps[m - 1];
    const double q = (Ts[m - 3] - Ts[m - 2]) / (Ts[m - 2] - Ts[m - 1]);
    auto g = [&](double p) { return (std::pow(d1, p) - std::pow(d2, p)) / (std::pow(d2, p) - std::pow(d3, p)) - q; };
    double lo = 0.05, hi = 8, p = kNaN;
    if (g(lo) * g(hi) < 0) {
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (g(lo) * g(mid) <= 0 ? hi : lo) = mid;
      }
      p = 0.5 * (lo + hi);
    }
    const double C = (Ts[m - 2] - Ts[m - 1]) / (std::pow(d2, p) - std::pow(d3, p));
    const double T0 = Ts[m - 1] - C * std::pow(d3, p);
    sum.set("observed_order", p, 3);
    sum.set("extrapolated_period", T0, 5);
    sum.set("extrapolated_vs_timoshenko", 100 * (T0 / timoshenko_period(gms_plate(2, 0.22)) - 1), 2);
    sum.set("extrapolated_vs_paper", 100 * (T0 / 1671.5 - 1), 2);
    CsvWriter w(out + "/extrapolation.csv", {"observed_order", "extrapolated_period", "from_across"});
    w.row({p, T0,
           std::to_string(conv[m - 3].across) + "/" + std::to_string(conv[m - 2].across) + "/" +
               std::to_string(conv[m - 1].across)});
  }
  sum.set("finest_across", conv.back().across);
  sum.set("finest_period", Ts.back(), 5);
  sum.set("finest_decay", 100 * find_run(runs, conv.back()).osc.decay_per_period, 2);
  sum.set("thin_022", thin_period(gms_plate(2, 0.22)), 5);
  sum.set("timo_022", timoshenko_period(gms_plate(2, 0.22)), 5);
  sum.set("timo_ratio_h2", timoshenko_period(gms_plate(2, 0.22)) / thin_period(gms_plate(2, 0.22)), 4);
  sum.set("timo_ratio_h1", timoshenko_period(gms_plate(1, 0.22)) / thin_period(gms_plate(1, 0.22)), 4);
}

/// Clamp length (change against the third, 4 columns), time step, viscosity and artificial-stress tables.
inline void summarise_sensitivities(study::Summary& sum, const std::vector<PlateCase>& clamp,
                                    const std::vector<PlateCase>& dt, const std::vector<PlateCase>& visc,
                                    const std::vector<PlateCase>& eps, const std::vector<PlateRun>& runs) {
  auto period = [&](const PlateCase& c) { return find_run(runs, c).osc.period; };
  std::string clamp_md, visc_md, eps_md;
  for (const PlateCase& c : clamp)
    study::md_row(clamp_md,
                  {std::to_string(c.clamp_layers), study::fixed(c.clamp_layers * c.thickness / c.across, 2),
                   study::fixed(period(c), 1), study::fixed(100 * (period(c) / period(clamp[2]) - 1), 2, true)});
  sum.set("clamp", clamp_md);
  sum.set("dt_change", std::abs(period(dt[0]) / period(dt[1]) - 1), 2);
  for (const PlateCase& c : visc) {
    const PlateRun& r = find_run(runs, c);
    study::md_row(visc_md, {study::sig(c.alpha, 2), study::sig(c.beta, 2), r.status, study::fixed(r.osc.period, 1),
                            study::fixed(100 * r.osc.decay_per_period, 2), study::fixed(r.max_stretch, 2)});
  }
  sum.set("viscosity", visc_md);
  for (const PlateCase& c : eps) {
    const PlateRun& r = find_run(runs, c);
    study::md_row(eps_md, {study::sig(c.eps, 2), study::sig(c.tip_speed, 2), study::fixed(r.osc.period, 1),
                           study::fixed(100 * r.osc.decay_per_period, 2)});
  }
  sum.set("eps", eps_md);
}

/// The root break: eps = 0 (root[0]) and eps = 0.3 (root[1]).
inline void summarise_root(study::Summary& sum, const std::vector<PlateCase>& root, const std::vector<PlateRun>& runs) {
  for (std::size_t k = 0; k < root.size(); ++k) {
    const PlateRun& r = find_run(runs, root[k]);
    const std::string key = k == 0 ? "root_eps0" : "root_eps03";
    sum.set(key + "_break_time", r.break_time, 4);
    sum.set(key + "_break_x", r.break_x, 3);
    sum.set(key + "_fragments", static_cast<long>(*std::max_element(r.fragments.begin(), r.fragments.end())));
    sum.set(key + "_period", r.osc.period, 5);
    sum.set(key + "_status", r.status);
  }
}

}  // namespace sphstab::gms_plate
