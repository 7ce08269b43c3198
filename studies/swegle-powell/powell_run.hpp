#pragma once
// One case of the study (powell_cases.hpp): the block's residual of equilibrium, the kicked run by the staggered
// leap-frog (algorithm 1.1) with Powell's XSPH, its fitted kinetic-energy growth, and the verdict at rest
// (growth/stability_verdict.hpp) in the mirror class the kick excites; and every case on the threads.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "common/rate_form_swegle.hpp"
#include "common/study.hpp"
#include "powell_cases.hpp"
#include "sphstab/growth/growth_fit.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/problems/swegle.hpp"

namespace swegle_powell {

namespace rfs = study::rate_form_swegle;

/// The blocks (h / dx, n, fixed layers) the cases need, each with the mirror class (px, py) = (-1, +1) its kick
/// excites.
using Blocks = std::map<std::tuple<double, int, int>, rfs::Block>;

inline std::tuple<double, int, int> block_key(const Case& c, const std::vector<Formulation>& forms) {
  return {c.h_over_dx, c.n, forms[c.form].layer_supports};
}

inline Blocks make_blocks(const std::vector<Case>& cases, const std::vector<Formulation>& forms) {
  Blocks blocks;
  for (const Case& c : cases) {
    const auto key = block_key(c, forms);
    if (blocks.count(key)) continue;
    SwegleOptions so;
    so.n = c.n;
    so.h_over_dx = c.h_over_dx;
    so.layer_supports = forms[c.form].layer_supports;
    blocks.emplace(key, rfs::make_block(so));
  }
  return blocks;
}

struct Outcome {
  StabilityVerdict verdict;
  ExponentialGrowthFit fit;
  RateFormRunResult run;  ///< status, steps, time and dt (rounded to t_end / steps), the kinetic-energy records
  double ke_max = 0, equilibrium = 0, wall_linear = 0, wall_run = 0;
  int particles = 0;
  std::string gamma_method;  // "fit" (the growth fit) or "mean" (energy limit reached before a fit window)
};

inline Outcome run_case(const Case& c, const Formulation& form, const rfs::Block& block, double t_end, double floor) {
  Outcome out;
  const SwegleScene& scene = block.scene;
  const auto& disc = scene.discretisation;
  const SwegleOptions& so = scene.options;
  const ElasticMaterial steel = rfs::steel(so);
  RateFormOptions o = form.options;
  if (!c.bulk) o.bulk_viscosity_quadratic = o.bulk_viscosity_linear = 0;
  const RateFormScheme<2> scheme(disc, steel, o, so.density / c.xi);
  const RateFormRunOptions run{.dt = c.tssfac * scene.h / steel.p_wave_speed(),
                               .t_end = t_end,
                               .record_every = 2,
                               .energy_growth = kStopGrowth,
                               .integrator = RateFormIntegrator::Leapfrog,
                               .leapfrog_xsph = form.xsph};
  Eigen::VectorXd y = scheme.uniform_state();
  // The unkicked block's largest acceleration over the kick's acceleration scale v0 c_P / h.
  out.equilibrium = rfs::equilibrium_residual(scheme, scene, steel);
  scheme.set_velocity(y, scene.centre, rfs::kick(scene));
  auto t0 = study::Clock::now();
  out.run = run_rate_form(scheme, y, run);
  out.wall_run = study::seconds_since(t0);
  const RateFormRunResult& r = out.run;
  out.ke_max = rfs::ke_max_over_ke0(r);
  out.fit = rfs::fit_growth(r, r.times.back(), kOnset);
  // A run that reached the energy limit grew, even when too few records lie in the window for a fit (the fastest
  // cases stop within a few dozen steps): its rate is then the mean ln(KE_max / KE0) / (2 t_stop), a lower bound.
  out.gamma_method = "fit";
  if (!out.fit.grew && r.status == RunStatus::EnergyGrowth) {
    out.fit.grew = true;
    out.fit.gamma = std::log(out.ke_max) / (2 * r.time);
    out.gamma_method = "mean";
  }
  // The verdict at the run's dt (run_rate_form rounds dt to t_end / steps), in the excited class, at rest.
  RateFormRunOptions at = run;
  at.dt = r.dt;
  t0 = study::Clock::now();
  out.verdict = rfs::checked_verdict(scheme, at, floor, block.excited, form.name + ": ");
  out.wall_linear = study::seconds_since(t0);
  out.particles = disc->size();
  return out;
}

/// Every case on `threads` threads (each scheme on one), a line per case on stdout as it ends.
inline std::vector<Outcome> run_all(const std::vector<Case>& cases, const std::vector<Formulation>& forms,
                                    const Blocks& blocks, double t_end, double floor, int threads) {
  std::vector<Outcome> outcomes(cases.size());
  study::parallel_for(cases.size(), threads, [&](std::size_t k) {
    const Case& c = cases[k];
    const Formulation& form = forms[c.form];
    outcomes[k] = run_case(c, form, blocks.at(block_key(c, forms)), t_end, floor);
    const Outcome& o = outcomes[k];
    std::printf("%-8s h %.1f n %d %-7s xi %.2f: %s (J %.4g, map %.4g), measured %.4g (%s), %s (%.1f + %.1f s)\n",
                c.set.c_str(), c.h_over_dx, c.n, form.name.c_str(), c.xi, o.verdict.letter().c_str(),
                o.verdict.semi_discrete_growth, o.verdict.map_growth, o.fit.gamma, o.fit.grew ? "grew" : "bounded",
                run_status_name(o.run.status).c_str(), o.wall_linear, o.wall_run);
    std::fflush(stdout);
  });
  return outcomes;
}

}  // namespace swegle_powell
