#pragma once
/// \file plate_tables.hpp
/// The study's output: one CSV row per run (the same columns in every table: periods, convergence, clamp, dt,
/// viscosity, eps, root, si) and the summary numbers and Markdown tables of each phase, rendered into summary.md by
/// summary.md.in. Resolution: the observed order of the period and its Richardson limit from the three finest plates.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/gms.hpp"
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

/// The fewest zero crossings behind a period of the period tables (`groups`), the full cycles they span, and the runs
/// without a period (fewer than kMinCrossings crossings), each distinct run once.
inline void summarise_crossings(study::Summary& sum, const std::vector<const std::vector<PlateCase>*>& groups,
                                const std::vector<PlateRun>& runs) {
  long fewest = -1;
  std::vector<std::string> unmeasured;
  for (const std::vector<PlateCase>* g : groups)
    for (const PlateCase& c : *g) {
      const PlateRun& r = find_run(runs, c);
      const long n = static_cast<long>(r.osc.crossings.size());
      if (std::isnan(r.osc.period)) {
        if (std::find(unmeasured.begin(), unmeasured.end(), c.tag) == unmeasured.end()) unmeasured.push_back(c.tag);
      } else if (fewest < 0 || n < fewest) {
        fewest = n;
      }
    }
  sum.set("min_crossings", fewest);
  sum.set("min_cycles", (fewest - 1) / 2);
  sum.set("unmeasured_runs", static_cast<long>(unmeasured.size()));
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
/// most 14 across), beside the run's period; the summary takes the row at `across`, and compares the eps = 0 run at
/// that resolution (`eps0`) with it too: at rest and stress free the artificial stress is off, so the spectrum does
/// not depend on eps and is computed once.
inline void write_linear_periods(const std::string& out, const std::vector<PlateCase>& conv, int across,
                                 const std::vector<PlateRun>& runs, const PlateRun& eps0, study::Summary& sum) {
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
      sum.set("eps0_vs_linear", 100 * (eps0.osc.period / lp.period - 1), 2);
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
  // The ranges the summary's prose names, each over the rows it names.
  auto row = [&](double H, double mu, double vf) -> const PlateRun& {
    for (const PlateCase& c : table)
      if (c.thickness == H && c.mu == mu && c.tip_speed == vf) return find_run(runs, c);
    throw std::logic_error("gms-plate: no table row");
  };
  study::Range small, spread, rise03, rise05, decay05, stretch03, stretch05, h1_small, h1_decay, paper_rise05;
  long fragments05 = 0;
  for (double mu : {0.22, 0.3, 0.6}) {
    const PlateRun &a = row(2, mu, 0.001), &b = row(2, mu, 0.01), &m = row(2, mu, 0.03), &l = row(2, mu, 0.05);
    for (const PlateRun* r : {&a, &b}) small.add(100 * (r->osc.period / r->c.paper - 1));
    spread.add(100 * std::abs(a.osc.period / b.osc.period - 1));
    rise03.add(100 * (m.osc.period / b.osc.period - 1)), stretch03.add(m.max_stretch);
    rise05.add(100 * (l.osc.period / b.osc.period - 1)), stretch05.add(l.max_stretch);
    decay05.add(100 * l.osc.decay_per_period);
    paper_rise05.add(100 * (l.c.paper / b.c.paper - 1));
    fragments05 = std::max<long>(fragments05, *std::max_element(l.fragments.begin(), l.fragments.end()));
    const PlateRun& h1 = row(1, mu, 0.01);
    h1_small.add(100 * (h1.osc.period / h1.c.paper - 1));
    for (double vf : {0.03, 0.05}) h1_decay.add(100 * row(1, mu, vf).osc.decay_per_period);
  }
  sum.set("small_vs_paper", small.text(1));
  sum.set("small_vf_spread", spread.hi, 2);
  sum.set("rise03", rise03.text(1)), sum.set("stretch03", stretch03.text(2));
  sum.set("rise05", rise05.text(1)), sum.set("stretch05", stretch05.text(2)), sum.set("decay05", decay05.text(0));
  sum.set("fragments05", fragments05);
  sum.set("paper_rise05", paper_rise05.text(1));
  sum.set("h1_small_vs_paper", h1_small.text(1)), sum.set("h1_large_decay", h1_decay.text(0));
}

/// A run whose initial grid bonds all stayed shorter than the fragment criterion of plate_run.hpp (1.5 dp): its square
/// lattice did not rearrange (no line sliding at the root), so its period is that of the elastic SPH plate.
inline constexpr double kRearrangedStretch = 1.5;
inline bool rearranged(const PlateRun& r) { return !(r.max_stretch <= kRearrangedStretch); }

/// T(dp) = T0 + C dp^p through three runs (p from the ratio of differences, any spacing, by bisection on [0.05, 8];
/// NaN when no p in that range fits).
struct Extrapolation {
  double order = kNaN, period = kNaN;
  std::string from;      ///< "a/b/c" particles across
  int rearranged = 0;    ///< runs of the three whose lattice rearranged
};

inline Extrapolation richardson(const std::vector<const PlateRun*>& three) {
  Extrapolation e;
  if (three.size() != 3) return e;
  double d[3], T[3];
  for (int k = 0; k < 3; ++k) {
    d[k] = three[k]->c.thickness / three[k]->c.across, T[k] = three[k]->osc.period;
    e.from += (k ? "/" : "") + std::to_string(three[k]->c.across);
    e.rearranged += rearranged(*three[k]);
  }
  const double q = (T[0] - T[1]) / (T[1] - T[2]);
  auto g = [&](double p) {
    return (std::pow(d[0], p) - std::pow(d[1], p)) / (std::pow(d[1], p) - std::pow(d[2], p)) - q;
  };
  double lo = 0.05, hi = 8;
  if (!(g(lo) * g(hi) < 0)) return e;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(lo) * g(mid) <= 0 ? hi : lo) = mid;
  }
  e.order = 0.5 * (lo + hi);
  const double C = (T[1] - T[2]) / (std::pow(d[1], e.order) - std::pow(d[2], e.order));
  e.period = T[2] - C * std::pow(d[2], e.order);
  return e;
}

/// The resolution study (H = 2, mu = 0.22, V_f = 0.01): its table, and the Richardson fit through the three finest
/// runs whose lattice did not rearrange (the headline) and through the three finest runs (the sensitivity: the
/// rearranged plates' periods mix the elastic period with the sliding), both written to extrapolation.csv.
inline void summarise_convergence(study::Summary& sum, const std::string& out, const std::vector<PlateCase>& conv,
                                  const std::vector<PlateRun>& runs) {
  std::string md, rearranged_list;
  std::vector<const PlateRun*> all, clean;
  for (const PlateCase& c : conv) {
    const PlateRun& r = find_run(runs, c);
    all.push_back(&r);
    if (rearranged(r))
      rearranged_list += (rearranged_list.empty() ? "" : ", ") + std::to_string(c.across);
    else
      clean.push_back(&r);
    study::md_row(md, {std::to_string(c.across), study::sig(c.thickness / c.across, 3), std::to_string(r.particles),
                       study::fixed(r.osc.period, 1), std::to_string(r.osc.crossings.size()),
                       study::fixed(100 * (r.osc.period / 1671.5 - 1), 1, true),
                       study::fixed(100 * r.osc.decay_per_period, 2), study::fixed(r.max_stretch, 2),
                       study::fixed(r.wall, 0)});
  }
  sum.set("convergence", md);
  sum.set("rearranged_stretch", kRearrangedStretch, 2);
  sum.set("rearranged_across", rearranged_list.empty() ? std::string("none") : rearranged_list);
  auto last3 = [](const std::vector<const PlateRun*>& v) {
    return v.size() < 3 ? std::vector<const PlateRun*>{} : std::vector<const PlateRun*>(v.end() - 3, v.end());
  };
  const Extrapolation head = richardson(last3(clean)), finest = richardson(last3(all));
  const double timo = timoshenko_period(gms_plate(2, 0.22));
  sum.set("observed_order", head.order, 3);
  sum.set("extrapolated_period", head.period, 5);
  sum.set("extrapolation_from", head.from.empty() ? std::string("fewer than three runs") : head.from);
  sum.set("extrapolated_vs_timoshenko", 100 * (head.period / timo - 1), 2);
  sum.set("extrapolated_vs_paper", 100 * (head.period / 1671.5 - 1), 2);
  sum.set("finest_fit_order", finest.order, 3);
  sum.set("finest_fit_period", finest.period, 5);
  sum.set("finest_fit_from", finest.from);
  sum.set("finest_fit_rearranged", static_cast<long>(finest.rearranged));
  sum.set("finest_fit_vs_timoshenko", 100 * (finest.period / timo - 1), 2);
  CsvWriter w(out + "/extrapolation.csv",
              {"fit", "observed_order", "extrapolated_period", "from_across", "rearranged_runs"});
  w.row({"unrearranged", head.order, head.period, head.from, head.rearranged});
  w.row({"finest", finest.order, finest.period, finest.from, finest.rearranged});
  // Where GMS's T_sph falls in the resolution sequence (the period falls with dp when the plate converges).
  std::string between = "outside the runs' range";
  for (std::size_t k = 0; k + 1 < all.size(); ++k)
    if ((all[k]->osc.period - 1671.5) * (all[k + 1]->osc.period - 1671.5) <= 0)
      between = "between " + std::to_string(all[k]->c.across) + " and " + std::to_string(all[k + 1]->c.across);
  sum.set("paper_between", between);
  const PlateRun* closest = all.front();
  for (const PlateRun* r : all)
    if (std::abs(r->osc.period / 1671.5 - 1) < std::abs(closest->osc.period / 1671.5 - 1)) closest = r;
  sum.set("closest_across", closest->c.across);
  sum.set("closest_vs_paper", 100 * (closest->osc.period / 1671.5 - 1), 2);
  sum.set("finest_across", conv.back().across);
  sum.set("finest_period", all.back()->osc.period, 5);
  sum.set("finest_decay", 100 * all.back()->osc.decay_per_period, 2);
  sum.set("thin_022", thin_period(gms_plate(2, 0.22)), 5);
  sum.set("timo_022", timo, 5);
  sum.set("timo_ratio_h2", timo / thin_period(gms_plate(2, 0.22)), 4);
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
  study::Range clamp_periods;
  for (const PlateCase& c : clamp) clamp_periods.add(period(c));
  sum.set("clamp_spread", clamp_periods.hi / clamp_periods.lo - 1, 2);
  sum.set("dt_change", std::abs(period(dt[0]) / period(dt[1]) - 1), 2);
  for (const PlateCase& c : visc) {
    const PlateRun& r = find_run(runs, c);
    study::md_row(visc_md, {study::sig(c.alpha, 2), study::sig(c.beta, 2), r.status, study::fixed(r.osc.period, 1),
                            study::fixed(100 * r.osc.decay_per_period, 2), study::fixed(r.max_stretch, 2)});
  }
  sum.set("viscosity", visc_md);
  study::Range visc_period, visc_decay;  // alpha >= 0.5 (visc[1..]); visc[0] is the MCM deck's alpha = 0.06
  for (std::size_t k = 1; k < visc.size(); ++k) {
    visc_period.add(period(visc[k]));
    visc_decay.add(100 * find_run(runs, visc[k]).osc.decay_per_period);
  }
  sum.set("visc_period_spread", 100 * (visc_period.hi / visc_period.lo - 1), 2);
  sum.set("visc_decay", visc_decay.text(1));
  sum.set("mcm_stretch", find_run(runs, visc[0]).max_stretch, 2);
  sum.set("mcm_decay", 100 * find_run(runs, visc[0]).osc.decay_per_period, 2);
  for (const PlateCase& c : eps) {
    const PlateRun& r = find_run(runs, c);
    study::md_row(eps_md, {study::sig(c.eps, 2), study::sig(c.tip_speed, 2), study::fixed(r.osc.period, 1),
                           study::fixed(100 * r.osc.decay_per_period, 2)});
  }
  sum.set("eps", eps_md);
  // eps = 0.3 against eps = 0 at each V_f (eps[0..1]: eps = 0 at V_f 0.001 and 0.01; eps[2..3]: eps = 0.3).
  study::Range lengthening;
  for (std::size_t k = 0; k < 2; ++k) lengthening.add(100 * (period(eps[k + 2]) / period(eps[k]) - 1));
  sum.set("eps_lengthening", lengthening.text(1));
}

/// The numbers the prose of the frozen spectra names: unstable counts, the eps = 0.3 / eps = 0 growth-rate ratios, and
/// for the viscosity-on linearisation at `visc_time` the mode's place, its e-folding time and the growth factor it
/// implies by the eps = 0 run's break at `break_time`.
inline void summarise_frozen(study::Summary& sum, const std::vector<study::FrozenRow>& rows, double visc_time,
                             double break_time) {
  auto find = [&](double t, double eps, bool visc) -> const study::FrozenSpectrum& {
    for (const study::FrozenRow& r : rows)
      if (std::abs(r.t - t) < 1 && r.eps == eps && r.viscosity == visc) return r.spectrum;
    throw std::logic_error("gms-plate: no frozen spectrum");
  };
  study::Range unstable_novisc, ratio_novisc;
  for (const study::FrozenRow& r : rows)
    if (r.state != "start" && !r.viscosity && r.eps == 0) {
      unstable_novisc.add(r.spectrum.unstable);
      ratio_novisc.add(find(r.t, 0.3, false).growth_rate / r.spectrum.growth_rate);
    }
  sum.set("frozen_novisc_unstable", unstable_novisc.text(0));
  sum.set("frozen_novisc_ratio", ratio_novisc.text(2));
  const study::FrozenSpectrum &v0 = find(visc_time, 0, true), &v3 = find(visc_time, 0.3, true);
  sum.set("frozen_visc_unstable", study::Range{std::min<double>(v0.unstable, v3.unstable),
                                               std::max<double>(v0.unstable, v3.unstable)}
                                      .text(0));
  sum.set("frozen_visc_peak_x", v0.peak_x, 2);
  sum.set("frozen_visc_efold", 1 / v0.growth_rate, 2);
  sum.set("frozen_visc_factor", std::exp(v0.growth_rate * (break_time - visc_time)), 2);
  sum.set("frozen_visc_ratio", v3.growth_rate / v0.growth_rate, 2);
  sum.set("frozen_visc_eps03_peak_x", v3.peak_x, 2);
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
