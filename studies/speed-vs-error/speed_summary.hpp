#pragma once
// The key numbers of the speed-vs-error study for summary.md.in, assembled from the runs (velocity_jump_run.hpp),
// the rates (convergence_rates.hpp), the stability limits (stability_limits.hpp), the UL instability
// (ul_tensile_instability.hpp) and the [Powell2012, Table 2.1] comparison (powell_table21.hpp): findings 1-3 (rates
// and L1 at the largest n), finding 4 (updated Lagrangian: blow-ups, tensile growth rate by both routes), findings 5-6
// (cost per particle-step, C_max of the time step), and the Markdown tables (stability, UL linearised, rates, Pareto
// front, TL/UL cost, Table 2.1, blow-ups).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "convergence_rates.hpp"
#include "stability_limits.hpp"
#include "ul_tensile_instability.hpp"
#include "velocity_jump_run.hpp"

namespace speed_error {

using study::fixed;
using study::md_row;
using study::sig;

/// The run of kernel k, h/dx hr, boundary b, formulation f and n particles, nullptr if there is none.
inline const RunRecord* find_run(const std::vector<RunRecord>& records, const std::string& k, double hr,
                                 const std::string& b, const std::string& f, int n) {
  for (const auto& r : records)
    if (r.kernel == k && r.h_over_dx == hr && r.boundary == b && r.form == f && r.n == n) return &r;
  return nullptr;
}

/// The L1 rate against n of one configuration, NaN if absent.
inline double find_rate(const std::vector<RateRow>& rate_rows, const std::string& k, double hr, const std::string& b,
                        const std::string& f) {
  const std::string key = k + " | " + sig(hr, 4) + " | " + b + " | " + f;
  for (const auto& r : rate_rows)
    if (r.key == key) return r.rate;
  return NAN;
}

/// Findings 1-3: rates and L1 at n = nmax (k0 the cubic kernel, k1 the second kernel of the sweep).
inline void summarise_accuracy(study::Summary& sum, const std::vector<RunRecord>& records,
                               const std::vector<RateRow>& rate_rows, const std::string& k0, const std::string& k1,
                               int nmax) {
  auto rate_of = [&](const std::string& k, double hr, const std::string& b, const std::string& f) {
    return find_rate(rate_rows, k, hr, b, f);
  };
  auto l1_of = [&](const std::string& k, double hr, const std::string& b, const std::string& f) -> double {
    const RunRecord* r = find_run(records, k, hr, b, f, nmax);
    return r ? r->l1 : NAN;
  };
  sum.set("rate_plain_1", fixed(rate_of(k0, 1.0, "mirror", "tl-plain"), 2));
  sum.set("rate_plain_2", fixed(rate_of(k0, 2.0, "mirror", "tl-plain"), 2));
  sum.set("rate_xsph_1", fixed(rate_of(k0, 1.0, "mirror", "tl-plain-xsph"), 2));
  sum.set("rate_xsph_2", fixed(rate_of(k0, 2.0, "mirror", "tl-plain-xsph"), 2));
  sum.set("l1_plain_1", l1_of(k0, 1.0, "mirror", "tl-plain"), 4);
  sum.set("l1_xsph_1", l1_of(k0, 1.0, "mirror", "tl-plain-xsph"), 4);
  sum.set("rate_plain_13", fixed(rate_of(k0, 1.3, "mirror", "tl-plain"), 2));
  sum.set("l1_plain_13", l1_of(k0, 1.3, "mirror", "tl-plain"), 4);
  sum.set("rate_plain_k1_1", fixed(rate_of(k1, 1.0, "mirror", "tl-plain"), 2));
  sum.set("l1_plain_k1_1", l1_of(k1, 1.0, "mirror", "tl-plain"), 4);
  sum.set("rate_corrected_13", fixed(rate_of(k0, 1.3, "mirror", "tl-corrected"), 2));
  sum.set("l1_corrected_13", l1_of(k0, 1.3, "mirror", "tl-corrected"), 4);
  sum.set("l1_corrected_k1_1", l1_of(k1, 1.0, "mirror", "tl-corrected"), 4);
  sum.set("l1_plain_none_13", fixed(l1_of(k0, 1.3, "none", "tl-plain"), 2));
  sum.set("l1_minus_none_13", fixed(l1_of(k0, 1.3, "none", "tl-minus"), 2));
  sum.set("l1_corrected_none_13", l1_of(k0, 1.3, "none", "tl-corrected"), 4);
}

/// Finding 4: updated Lagrangian (blow-ups of ul-plain and their drift, ul-minus-plus against tl-plain, the tensile
/// growth rate linearised at +2 % strain, cubic, h/dx = 1, and seeded).
inline void summarise_updated_lagrangian(study::Summary& sum, const std::vector<RunRecord>& records,
                                         const std::string& k0, int nmax, const std::vector<LinRow>& lin_rows,
                                         const SeededGrowth& seeded) {
  int ul_done = 0, ul_total = 0, ump_done = 0, ump_total = 0;
  long smin = 1L << 40, smax = 0;
  double dmin = INFINITY, dmax = 0;
  std::string ump_fail;
  for (const auto& r : records) {
    if (r.form == "ul-plain") {
      ++ul_total;
      if (r.status == "completed") {
        ++ul_done;
      } else {
        smin = std::min(smin, r.steps);
        smax = std::max(smax, r.steps);
        const double drift = 0.01 * r.dt * r.steps * r.n;  // rigid drift v0 t in units of dx = 1/n
        dmin = std::min(dmin, drift);
        dmax = std::max(dmax, drift);
      }
    }
    if (r.form == "ul-minus-plus") {
      ++ump_total;
      if (r.status == "completed")
        ++ump_done;
      else
        ump_fail += (ump_fail.empty() ? "" : ", ") + r.kernel + " " + sig(r.h_over_dx, 4) + " " + r.boundary +
                    " n=" + std::to_string(r.n);
    }
  }
  sum.set("ul_plain_completed", ul_done);
  sum.set("ul_plain_runs", ul_total);
  sum.set("ul_plain_steps_min", smin);
  sum.set("ul_plain_steps_max", smax);
  sum.set("ul_plain_drift_min", fixed(dmin, 1));
  sum.set("ul_plain_drift_max", fixed(dmax, 1));
  sum.set("ul_minus_plus_completed", ump_done);
  sum.set("ul_minus_plus_runs", ump_total);
  sum.set("ul_minus_plus_failed", ump_fail.empty() ? "" : " (failed: " + ump_fail + ")");
  const RunRecord* um = find_run(records, k0, 1.3, "mirror", "ul-minus-plus", nmax);
  const RunRecord* ts = find_run(records, k0, 1.3, "mirror", "tl-plain", nmax);
  sum.set("l1_ul_minus_plus_13", um ? sig(um->l1, 4) : "-");
  sum.set("l1_tl_plain_13", ts ? sig(ts->l1, 4) : "-");
  double lin_rate_h1 = NAN;
  for (const auto& l : lin_rows)
    if (l.kernel == "cubic" && l.hr == 1.0 && l.strain == 0.02) lin_rate_h1 = l.growth;
  sum.set("lin_rate_h1", fixed(lin_rate_h1, 1));
  sum.set("seeded_rate", fixed(seeded.rate, 1));
  sum.set("seeded_saturation", seeded.saturation, 2);
}

/// Findings 5-6: cost (µs per particle-step, TL against UL) and time step (C_max over the stability cases, its
/// change from n = 200 to nmax, the stability table at n = 200).
inline void summarise_cost_and_time_step(study::Summary& sum, const std::vector<RunRecord>& records,
                                         const std::vector<StabRow>& stab_rows, const std::string& k0, int nmax,
                                         double courant) {
  const RunRecord* tl13 = find_run(records, k0, 1.3, "mirror", "tl-plain", nmax);
  const RunRecord* ul13 = find_run(records, k0, 1.3, "mirror", "ul-minus-plus", nmax);
  const double tl_us = tl13 ? tl13->us_per_particle_step : NAN, ul_us = ul13 ? ul13->us_per_particle_step : NAN;
  sum.set("tl_us", fixed(tl_us, 3));
  sum.set("ul_us", fixed(ul_us, 3));
  sum.set("ul_over_tl", fixed(ul_us / tl_us, 1));
  double cmax_min = INFINITY, cmax_diff = 0;  // C_max at n = 200 (dense) vs n = nmax (Spectra)
  std::string table;
  for (std::size_t k = 0; k < stab_rows.size(); ++k) {
    const StabRow& r = stab_rows[k];
    if (std::isfinite(r.courant_max)) cmax_min = std::min(cmax_min, r.courant_max);
    if (k + 1 < stab_rows.size() && r.n == 200 && stab_rows[k + 1].n == nmax && nmax != 200)
      cmax_diff = std::max(cmax_diff, std::abs(r.courant_max - stab_rows[k + 1].courant_max) / r.courant_max);
    if (r.n == 200)
      md_row(table, {r.key, sig(r.lambda_max, 4), fixed(r.courant_max, 3), sig(r.min_re, 3), fixed(r.m1, 6)});
  }
  sum.set("courant_max_min", fixed(cmax_min, 2));
  sum.set("courant_pct", fixed(courant / cmax_min * 100, 0));
  sum.set("courant_max_diff_pct", fixed(100 * cmax_diff, 3));
  sum.set("stability_table", table);
}

/// The UL linearised and rates tables, the Pareto front and the TL/UL cost table (cubic, mirror, n = nmax).
inline void summarise_tables(study::Summary& sum, const std::vector<RunRecord>& records,
                             const std::vector<LinRow>& lin_rows, const std::vector<RateRow>& rate_rows,
                             const std::vector<double>& ratios, const std::string& k0, int nmax) {
  std::string table;
  for (const auto& l : lin_rows)
    md_row(table, {l.kernel, sig(l.hr, 6), fixed(l.strain, 2, true), sig(l.minre, 3), sig(l.growth, 3)});
  sum.set("ul_linearised_table", table);

  table.clear();
  for (const auto& r : rate_rows)
    md_row(table, {r.key, sig(r.l1_max, 4), fixed(r.rate, 2), fixed(r.rate_mean, 2), fixed(r.slope_s, 2),
                   std::to_string(r.completed)});
  sum.set("rates_table", table);

  // Pareto front: completed runs not beaten in both error and time, fastest first.
  std::vector<const RunRecord*> ok;
  for (const auto& r : records)
    if (r.status == "completed") ok.push_back(&r);
  std::sort(ok.begin(), ok.end(), [](auto a, auto b) { return a->total_s < b->total_s; });
  table.clear();
  double best = INFINITY;
  for (const auto* r : ok)
    if (r->l1 < best) {
      best = r->l1;
      md_row(table, {fixed(r->total_s, 4), sig(r->l1, 4), r->kernel, sig(r->h_over_dx, 6), r->boundary, r->form,
                     std::to_string(r->n)});
    }
  sum.set("pareto_table", table);

  table.clear();
  for (double hr : ratios) {
    const RunRecord* tl = find_run(records, k0, hr, "mirror", "tl-plain", nmax);
    const RunRecord* ul = find_run(records, k0, hr, "mirror", "ul-minus-plus", nmax);
    const RunRecord* up = find_run(records, k0, hr, "mirror", "ul-plain", nmax);
    if (tl && ul && up)
      md_row(table,
             {sig(hr, 6), fixed(tl->us_per_particle_step, 4), fixed(up->us_per_particle_step, 4),
              fixed(ul->us_per_particle_step, 4), fixed(ul->us_per_particle_step / tl->us_per_particle_step, 1)});
  }
  sum.set("cost_table", table);
}

/// Powell Table 2.1: the table and the error of each of our case families.
inline void summarise_powell(study::Summary& sum,
                             const std::vector<std::pair<std::string, std::pair<double, double>>>& powell_rows) {
  std::string table;
  for (const auto& [k, v] : powell_rows) {
    auto sep = k.find(" | ");
    md_row(table,
           {k.substr(0, sep), k.substr(sep + 3), std::isnan(v.first) ? "blew up" : sig(v.first, 4), sig(v.second, 4)});
    for (auto [prefix, key] : {std::pair{"SPH (tl-plain)", "powell_sph"},
                               {"XSPH replace", "powell_xsph_replace"},
                               {"XSPH drift-only", "powell_xsph_drift"},
                               {"corrected (tl", "powell_corrected"},
                               {"corrected + XSPH", "powell_corrected_xsph"}})
      if (k.rfind(prefix, 0) == 0) sum.set(key, v.first, 4);
  }
  sum.set("powell_table", table);
}

/// The runs that did not complete, with the reason.
inline void summarise_blowups(study::Summary& sum, const std::vector<RunRecord>& records) {
  std::string table;
  for (const auto& r : records)
    if (r.status != "completed")
      table += (table.empty() ? "- " : "\n- ") + r.kernel + " h/Δx = " + sig(r.h_over_dx, 6) + ", " + r.boundary +
               ", " + r.form + ", n = " + std::to_string(r.n) + ": " + r.message;
  sum.set("blowups", table.empty() ? "- none" : table);
}

}  // namespace speed_error
