#pragma once
// The outputs of one case of the rate-form Swegle study: its row of runs.csv, its KE(t) in ke.csv, its cell of the
// summary's stability table and row of the ratios table, and its progress line.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "rate_form_case.hpp"
#include "sphstab/io/csv.hpp"

namespace swegle_rate_form {

inline const char* kRunsHeader =
    "formulation,xi,density,pressure,gamma_linear_class,lambda_imag_class,gamma_linear_all,gamma_map_class,"
    "invariance_residual,structure_residual,equilibrium_residual,gamma_measured,grew,fit_t_begin,fit_t_end,"
    "fit_r2,ratio,"
    "verdict,floor,integrator_excess,map_predicts_growth,status,steps,t_stop,ke_max_over_ke0,wall_linear,"
    "wall_run,layer_supports,particles\n";

inline void write_run(std::ostream& csv, const CaseResult& c, const Setup& s) {
  const ElasticMaterial& steel = s.steel;
  csv << csv_line({c.form,
                   format_number(c.xi),
                   format_number(c.rho, 8),
                   format_number(steel.bulk_modulus() * (c.rho / steel.density() - 1), 8),
                   format_number(c.cls.growth_rate, 8),
                   format_number(std::abs(c.cls.lambda.imag()), 8),
                   format_number(c.all.growth_rate, 8),
                   format_number(c.v.map_growth, 8),
                   format_number(c.cls.invariance_residual, 3),
                   format_number(c.all.structure_residual, 3),
                   format_number(c.equilibrium, 3),
                   format_number(c.fit.gamma, 8),
                   c.fit.grew ? "1" : "0",
                   format_number(c.fit.fit.t_begin, 6),
                   format_number(c.fit.fit.t_end, 6),
                   format_number(c.fit.fit.r2, 8),
                   format_number(c.ratio, 6),
                   c.v.letter(),
                   format_number(s.detect, 6),
                   format_number(c.v.integrator_excess, 6),
                   c.map_unstable ? "1" : "0",
                   run_status_name(c.run.status),
                   std::to_string(c.run.steps),
                   format_number(c.run.time, 6),
                   format_number(c.ke_max, 6),
                   format_number(c.wall_linear, 3),
                   format_number(c.wall_run, 3),
                   std::to_string(c.layer_supports),
                   std::to_string(c.particles)});
}

inline const char* kKeHeader = "formulation,xi,t,kinetic\n";

inline void write_ke(std::ostream& csv, const CaseResult& c) {
  for (std::size_t k = 0; k < c.run.times.size(); ++k)
    csv << csv_line(
        {c.form, format_number(c.xi), format_number(c.run.times[k], 8), format_number(c.run.kinetic_energy[k], 8)});
}

/// The stability table's cell: class, then gamma_J / gamma_M, then the run's measured rate (or "-" when it stayed
/// below the window).
inline std::string stability_cell(const CaseResult& c) {
  const StabilityVerdict& v = c.v;
  const std::string letter = v.verdict == VerdictClass::Stable ? "S" : "**" + v.letter() + "**";
  return letter + " " + study::sig(std::max(v.semi_discrete_growth, 0.0), 2) + " / " +
         study::sig(std::max(v.map_growth, 0.0), 2) + " · " + (c.fit.grew ? study::sig(c.fit.gamma, 2) : "–");
}

/// The ratios table's row: linear rates (class, all), the measured one and their ratio.
inline std::vector<std::string> ratios_row(const CaseResult& c) {
  return {c.form,
          study::fixed(c.xi, 2),
          study::sig(c.cls.growth_rate, 4),
          study::sig(c.all.growth_rate, 4),
          study::sig(c.fit.gamma, 4),
          study::fixed(c.ratio, 3)};
}

inline void print_case(const CaseResult& c) {
  std::printf(
      "%-9s xi %.2f: %s (J %.4g, map %.4g), all classes %.4g, measured %.4g (%s), ratio %.3f, %s "
      "(%.1f + %.1f s)\n",
      c.form.c_str(), c.xi, c.v.letter().c_str(), c.cls.growth_rate, c.v.map_growth, c.all.growth_rate, c.fit.gamma,
      c.fit.grew ? "grew" : "bounded", c.ratio, c.run.message.c_str(), c.wall_linear, c.wall_run);
  std::fflush(stdout);
}

}  // namespace swegle_rate_form
