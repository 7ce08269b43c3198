#pragma once
// Is the growth at xi = 1 (linearly neutral) made by the time integrator? Measured gamma versus dt, GMS positions
// and corrected (trapezoid) positions, against the one-step map's rate: an integrator-made growth falls as dt^3.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include "common/study.hpp"
#include "rate_form_case.hpp"
#include "sphstab/io/csv.hpp"

namespace swegle_rate_form {

/// The summary's dt table and, per position update, measured / map rate at the study's dt.
struct DtStudy {
  std::string table;
  std::map<std::string, double> ratio;
};

/// Writes <out>/dt_study.csv: basic SPH at xi = 1 on the block of one support of fixed layers, at dt and dt/2.
inline DtStudy dt_study(const Setup& s) {
  const Block& b = s.block(1);
  const SwegleScene& scene = b.scene;
  std::ofstream dt_csv(s.o.out + "/dt_study.csv");
  dt_csv << "formulation,xi,positions,dt,t_end,gamma_measured,gamma_map_class,verdict,grew\n";
  DtStudy d;
  for (double scale : {1.0, 0.5}) {  // the same t_end: at dt/2 the map grows 8x slower
    const RateFormScheme<2> scheme(scene.discretisation, s.steel, {}, scene.options.density);
    Eigen::VectorXd y = scheme.uniform_state();
    scheme.set_velocity(y, scene.centre, kick(scene));
    for (PositionUpdate pu : {PositionUpdate::Gms, PositionUpdate::Trapezoid}) {
      const RateFormRunResult run = run_rate_form(scheme, y,
                                                  {.dt = scale * s.dt,
                                                   .positions = pu,
                                                   .t_end = s.o.t_end,
                                                   .record_every = 10,
                                                   .energy_growth = s.o.stop_growth});
      const ExponentialGrowthFit fit = fit_growth(run, run.times.back(), s.o.onset);
      // The exact one-step map of this position update (stability_verdict's reduced route), in the excited class.
      const StabilityVerdict mv = stability_verdict(scheme, scheme.uniform_state(), {.dt = run.dt, .positions = pu},
                                                    {.floor = s.detect, .basis = b.excited});
      const double map = mv.map_growth;
      const std::string name = pu == PositionUpdate::Gms ? "gms" : "trapezoid";
      if (scale == 1.0) d.ratio[name] = fit.grew ? fit.gamma / map : NAN;
      dt_csv << csv_line({"sph", "1", name, format_number(run.dt, 8), format_number(s.o.t_end, 6),
                          format_number(fit.gamma, 8), format_number(map, 8), mv.letter(), fit.grew ? "1" : "0"});
      study::md_row(d.table, {name, study::sig(run.dt, 4), fit.grew ? study::sig(fit.gamma, 4) : "– (below the window)",
                              study::sig(map, 4), mv.letter()});
      std::printf("dt study: %s dt %.4g: measured %.4g, map %.4g (%s)\n", name.c_str(), run.dt, fit.gamma, map,
                  mv.letter().c_str());
    }
  }
  return d;
}

}  // namespace swegle_rate_form
