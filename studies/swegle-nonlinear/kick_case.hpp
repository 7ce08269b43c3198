#pragma once
// One (formulation, xi) of the nonlinear Swegle study: the full-state linear growth rate (over all classes and in the
// excited mirror class), the stability verdicts of the three (integrator, dt) the runs use, the kicked runs at every
// v0 with both integrators and the predictor-corrector's run at dt/2 and the smallest kick; and its rows of runs.csv.
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <string>

#include "kick_run.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/io/csv.hpp"

namespace swegle_nonlinear {

struct KickCase {
  std::string form;
  double xi = 1;
  RateFormSpectrum all, cls;         // over all classes and in the excited class
  StabilityVerdict vpc, vlf, vhalf;  // predictor-corrector and leap-frog at dt, predictor-corrector at dt/2
  std::map<RateFormIntegrator, std::map<double, Measured>> runs;  // integrator -> v0 -> run at dt
  Measured half;                                                  // predictor-corrector at dt/2, smallest kick
  double wall_linear = 0, wall_runs = 0;

  /// The verdict of the runs at dt with `integrator`.
  const StabilityVerdict& verdict(RateFormIntegrator integrator) const {
    return integrator == RateFormIntegrator::Leapfrog ? vlf : vpc;
  }
};

inline KickCase run_case(const Setup& s, const Formulation& form, double xi) {
  const RateFormScheme<2> scheme(s.block.scene.discretisation, s.steel, form.options, s.steel.density() / xi);
  KickCase c{.form = form.name, .xi = xi};
  const Eigen::VectorXd y_rest = scheme.uniform_state();
  const auto tl = study::Clock::now();
  c.all = rate_form_spectrum(scheme, y_rest);
  c.cls = rate_form_spectrum(scheme, y_rest, {.basis = s.block.excited});
  // The verdicts of the three (integrator, dt) the runs use, in the excited class.
  const auto verdict = [&](RateFormIntegrator integrator, double step) {
    return checked_verdict(scheme, {.dt = step, .integrator = integrator}, s.floor, s.block.excited);
  };
  c.vpc = verdict(RateFormIntegrator::PredictorCorrector, s.dt);
  c.vlf = verdict(RateFormIntegrator::Leapfrog, s.dt);
  c.vhalf = verdict(RateFormIntegrator::PredictorCorrector, 0.5 * s.dt);
  c.wall_linear = study::seconds_since(tl);
  for (RateFormIntegrator integrator : kIntegrators)
    for (double v0 : s.v0s) {
      const Measured m = measure(s, scheme, v0, integrator, s.dt);
      c.wall_runs += m.wall;
      const StabilityVerdict& v = c.verdict(integrator);
      std::printf(
          "%-12s xi %.2f %-19s v0 %.0e: %s, gamma linear %.5g (class %.5g, map %.5g), measured %.5g (%s), "
          "pre-saturation %.5g, %s t %.3g (%.1f s)\n",
          form.name.c_str(), xi, integrator_name(integrator).c_str(), v0, v.letter().c_str(), c.all.growth_rate,
          c.cls.growth_rate, v.map_growth, m.fit.gamma, m.fit.grew ? "grew" : "bounded", m.early.gamma,
          m.status.c_str(), m.run.time, m.wall);
      std::fflush(stdout);
      c.runs[integrator][v0] = m;
    }
  // dt dependence, predictor-corrector at the smallest kick: dt/2.
  c.half = measure(s, scheme, s.v0s.front(), RateFormIntegrator::PredictorCorrector, 0.5 * s.dt);
  c.wall_runs += c.half.wall;
  std::printf("%-12s xi %.2f dt/2: measured %.5g (%s)\n", form.name.c_str(), xi, c.half.fit.gamma,
              c.half.fit.grew ? "grew" : "bounded");
  return c;
}

inline const char* kRunsHeader =
    "formulation,xi,v0,integrator,dt,gamma_linear,gamma_measured,grew,status,t_stop,ke_max_over_ke0,"
    "gamma_linear_class,gamma_map_class,verdict,floor,ratio,fit_r2,fit_t_begin,fit_t_end,gamma_bound,"
    "gamma_presaturation,presaturation_t_end,wall\n";

/// The case's rows of runs.csv: every (integrator, v0) at dt, then the predictor-corrector at dt/2.
inline void write_runs(std::ostream& csv, const KickCase& c, const Setup& s) {
  const auto row = [&](double v0, RateFormIntegrator integrator, const StabilityVerdict& v, const Measured& m) {
    csv << csv_line({c.form,
                     format_number(c.xi),
                     format_number(v0),
                     integrator_name(integrator),
                     format_number(m.run.dt, 8),
                     format_number(c.all.growth_rate, 8),
                     format_number(m.fit.gamma, 8),
                     m.fit.grew ? "1" : "0",
                     m.status,
                     format_number(m.run.time, 6),
                     format_number(m.ke_max, 6),
                     format_number(c.cls.growth_rate, 8),
                     format_number(v.map_growth, 8),
                     v.letter(),
                     format_number(s.floor, 6),
                     format_number(m.fit.grew ? m.fit.gamma / c.all.growth_rate : NAN, 6),
                     format_number(m.fit.fit.r2, 8),
                     format_number(m.fit.fit.t_begin, 6),
                     format_number(m.fit.fit.t_end, 6),
                     format_number(m.fit.gamma_bound, 6),
                     format_number(m.early.gamma, 8),
                     format_number(m.early.fit.t_end, 6),
                     format_number(m.wall, 3)});
  };
  for (RateFormIntegrator integrator : kIntegrators)
    for (double v0 : s.v0s) row(v0, integrator, c.verdict(integrator), c.runs.at(integrator).at(v0));
  row(s.v0s.front(), RateFormIntegrator::PredictorCorrector, c.vhalf, c.half);
  csv.flush();
}

}  // namespace swegle_nonlinear
