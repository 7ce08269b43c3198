#pragma once
// The per-run tables of the Turek & Hron (2006) CSM3 study: runs.csv (every run: resolution, form, clamp, time step,
// energy drift, the mean / amplitude / frequency of u_x(A) and u_y(A) over the window and over the last period) and
// the Markdown tables of summary.md.in (runs; measures against the CSM3 reference with the relative errors).
#include <string>
#include <vector>

#include "common/study.hpp"
#include "csm3_cases.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

namespace csm3_study {

using namespace sphstab;

/// The relative error of v against the reference ref, "+1.23 %".
inline std::string rel(double v, double ref) { return study::fixed(100 * (v / ref - 1), 2, true) + " %"; }

struct RunTables {
  std::string runs, table;  ///< Markdown rows: the runs; the measures against the reference (last row)
};

/// Writes <out>/runs.csv and returns the Markdown tables of the runs.
inline RunTables run_tables(const std::string& out, const std::vector<CaseResult>& results) {
  CsvWriter rcsv(
      out + "/runs.csv",
      {"run",           "across",       "gradient",     "clamp_layers",      "dx",           "particles",
       "free",          "clamp",        "dt",           "dt_limit",          "steps",        "wall_seconds",
       "status",        "energy_drift", "ux_mean",      "ux_amplitude",      "ux_frequency", "uy_mean",
       "uy_amplitude",  "uy_frequency", "ux_last_mean", "ux_last_amplitude", "uy_last_mean", "uy_last_amplitude",
       "uy_half_cycles"});
  RunTables md;
  for (const CaseResult& r : results) {
    rcsv.row({r.spec.name(),
              r.spec.across,
              r.spec.gradient,
              r.spec.clamp_layers,
              r.dx,
              r.particles,
              r.free,
              r.clamp,
              r.dt,
              r.dt_limit,
              r.steps,
              r.wall,
              r.status,
              r.energy_drift,
              r.ux.mean,
              r.ux.amplitude,
              r.ux.frequency,
              r.uy.mean,
              r.uy.amplitude,
              r.uy.frequency,
              r.ux.last_mean,
              r.ux.last_amplitude,
              r.uy.last_mean,
              r.uy.last_amplitude,
              r.uy.half_cycles});
    study::md_row(md.runs, {r.spec.name(), std::to_string(r.particles), std::to_string(r.free), std::to_string(r.clamp),
                            study::sig(r.dt * 1e6, 4), study::fixed(r.dt / r.dt_limit, 3), std::to_string(r.steps),
                            study::fixed(r.wall, 1), study::sig(r.energy_drift, 2), study::sig(r.growth, 3),
                            study::fixed(r.f_linear, 4), r.status});
    study::md_row(
        md.table,
        {r.spec.name(), study::fixed(1e3 * r.ux.mean, 3), study::fixed(1e3 * r.ux.amplitude, 3),
         study::fixed(r.ux.frequency, 4), study::fixed(1e3 * r.uy.mean, 3), study::fixed(1e3 * r.uy.amplitude, 3),
         study::fixed(r.uy.frequency, 4), rel(r.ux.mean, C::ux_mean), rel(r.ux.amplitude, C::ux_amplitude),
         rel(r.uy.mean, C::uy_mean), rel(r.uy.amplitude, C::uy_amplitude), rel(r.uy.frequency, C::frequency)});
  }
  study::md_row(md.table, {"**reference**", study::fixed(1e3 * C::ux_mean, 3), study::fixed(1e3 * C::ux_amplitude, 3),
                           study::fixed(C::frequency, 4), study::fixed(1e3 * C::uy_mean, 3),
                           study::fixed(1e3 * C::uy_amplitude, 3), study::fixed(C::frequency, 4), "", "", "", "", ""});
  return md;
}

}  // namespace csm3_study
