#pragma once
// The CSV files of the study: series/<tag>.csv (v_x, v_y at every probe over time), speeds.csv (the peaks fitted for
// the wave speeds) and runs.csv (one row per run: the error at the probes, the reflected speed, wall and CPU time).
#include <string>
#include <vector>

#include "impact_cases.hpp"
#include "impact_measures.hpp"
#include "impact_run.hpp"
#include "sphstab/io/csv.hpp"

namespace nrbc_impact {

/// series/<tag>.csv of every run: t and v_x, v_y at each probe.
inline void write_series(const std::string& out, const std::vector<ImpactRun>& runs) {
  const std::vector<Probe> pr = probes();
  std::vector<std::string> header{"t"};
  for (const Probe& q : pr) header.push_back("vx_" + q.name), header.push_back("vy_" + q.name);
  for (const ImpactRun& r : runs) {
    CsvWriter s(out + "/series/" + tag_of(r.c) + ".csv", header, false);
    for (std::size_t k = 0; k < r.t.size(); ++k) {
      std::vector<CsvCell> row{r.t[k]};
      for (std::size_t q = 0; q < pr.size(); ++q) row.emplace_back(r.v[k][q][0]), row.emplace_back(r.v[k][q][1]);
      s.row(row);
    }
  }
}

/// speeds.csv: the incident wave's peaks, then the reflected waves' peaks run by run.
inline void write_speeds(const std::string& out, const Incident& in, const std::vector<Measures>& measures) {
  CsvWriter sp(out + "/speeds.csv", {"run", "wave", "probe", "x", "t_peak", "peak"});
  const auto write = [&](const std::vector<Arrival>& arrivals) {
    for (const Arrival& a : arrivals) sp.row({a.run, a.wave, a.probe, a.x, a.t_peak, a.peak});
  };
  write(in.arrivals);
  for (const Measures& m : measures) write(m.arrivals);
}

/// runs.csv: one row per run.
inline void write_runs(const std::string& out, const std::vector<ImpactRun>& runs,
                       const std::vector<Measures>& measures) {
  CsvWriter w(out + "/runs.csv",
              {"run", "boundary", "particles", "absorbing", "status", "v_patch", "error_surface", "error_depth",
               "reflected_speed", "reflected_speed_stderr", "wall_seconds", "cpu_seconds"});
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const ImpactRun& r = runs[k];
    const Measures& m = measures[k];
    w.row({r.c.name, boundary_name(r.c.boundary), r.particles, r.absorbing, r.status, r.c.v_patch, m.error_surface,
           m.error_depth, m.reflected, m.reflected_err, r.wall, r.cpu});
  }
}

}  // namespace nrbc_impact
