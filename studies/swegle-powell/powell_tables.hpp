#pragma once
// The CSV files of the study: runs.csv (one row per case: verdict, measured growth, run, wall times) and ke.csv (the
// kinetic energy of every run, every 10th record and the last).
#include <fstream>
#include <string>
#include <vector>

#include "powell_cases.hpp"
#include "powell_run.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/io/csv.hpp"

namespace swegle_powell {

inline void write_tables(const std::string& out, const std::vector<Case>& cases, const std::vector<Formulation>& forms,
                         const std::vector<Outcome>& outcomes, double floor) {
  std::ofstream runs_csv(out + "/runs.csv"), ke_csv(out + "/ke.csv");
  runs_csv
      << "set,formulation,h_over_dx,n,xi,bulk_viscosity,tssfac,dt,gamma_linear_class,gamma_map_class,floor,verdict,"
         "gamma_measured,gamma_method,grew,fit_t_begin,fit_t_end,fit_r2,map_predicts_growth,status,steps,t_stop,"
         "ke_max_over_ke0,equilibrium_residual,layer_supports,particles,wall_linear,wall_run\n";
  ke_csv << "set,formulation,h_over_dx,n,xi,t,kinetic\n";
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const Formulation& form = forms[c.form];
    const Outcome& o = outcomes[k];
    const StabilityVerdict& v = o.verdict;
    runs_csv << csv_line({c.set,
                          form.name,
                          format_number(c.h_over_dx),
                          std::to_string(c.n),
                          format_number(c.xi),
                          c.bulk ? "1" : "0",
                          format_number(c.tssfac),
                          format_number(o.run.dt, 8),
                          format_number(v.semi_discrete_growth, 8),
                          format_number(v.map_growth, 8),
                          format_number(floor, 6),
                          v.letter(),
                          format_number(o.fit.gamma, 8),
                          o.gamma_method,
                          o.fit.grew ? "1" : "0",
                          format_number(o.fit.fit.t_begin, 6),
                          format_number(o.fit.fit.t_end, 6),
                          format_number(o.fit.fit.r2, 8),
                          v.map_growth > floor ? "1" : "0",
                          run_status_name(o.run.status),
                          std::to_string(o.run.steps),
                          format_number(o.run.time, 6),
                          format_number(o.ke_max, 6),
                          format_number(o.equilibrium, 3),
                          std::to_string(form.layer_supports),
                          std::to_string(o.particles),
                          format_number(o.wall_linear, 3),
                          format_number(o.wall_run, 3)});
    for (std::size_t s = 0; s < o.run.times.size(); ++s)  // every 10th record (of every 2nd step) and the last
      if (s % 10 == 0 || s + 1 == o.run.times.size())
        ke_csv << csv_line({c.set, form.name, format_number(c.h_over_dx), std::to_string(c.n), format_number(c.xi),
                            format_number(o.run.times[s], 8), format_number(o.run.kinetic_energy[s], 8)});
  }
}

}  // namespace swegle_powell
