#pragma once
// One (formulation, xi) of the rate-form Swegle study: the full-state linear growth rate (in the mirror class the kick
// excites and over all classes), the block's residual of equilibrium, the kicked run with the GMS predictor-corrector
// and the fit of its kinetic-energy growth, and the stability verdict at the run's dt. Also what every case shares
// (Setup).
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "common/rate_form_swegle.hpp"
#include "common/study.hpp"
#include "sphstab/growth/growth_fit.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace swegle_rate_form {

using namespace sphstab;
using namespace sphstab::study::rate_form_swegle;

/// What every case of the study shares: the options, the blocks with fixed layers of 1, 2, 3 supports (each with
/// the mirror class its kick excites), the steel, the runs' step and the fit's detection floor.
struct Setup {
  Options o;
  std::vector<Block> blocks;
  ElasticMaterial steel = ElasticMaterial::from_bulk_shear(1.0, 0.0, 1.0);
  double dt = 0, detect = 0;

  /// The block with the fixed layers a formulation needs.
  const Block& block(int layer_supports) const { return blocks[layer_supports - 1]; }
};

struct CaseResult {
  std::string form;
  double xi = 1, rho = 0;
  int layer_supports = 1, particles = 0;
  RateFormSpectrum all, cls;  // over all classes and in the excited class
  double equilibrium = 0;     // the unkicked block's residual over the kick's acceleration scale
  RateFormRunResult run;
  ExponentialGrowthFit fit;
  double ke_max = 0;  // max KE / KE0
  StabilityVerdict v;
  bool map_unstable = false;  // what the run at this dt amplifies
  double ratio = NAN;         // measured / linear growth where both grow
  double wall_linear = 0, wall_run = 0;
};

inline CaseResult run_case(const Setup& s, const Formulation& form, double xi) {
  const Block& b = s.block(form.layer_supports);
  const auto& disc = b.scene.discretisation;
  CaseResult c{.form = form.name,
               .xi = xi,
               .rho = b.scene.options.density / xi,
               .layer_supports = form.layer_supports,
               .particles = disc->size()};
  const RateFormScheme<2> scheme(disc, s.steel, form.options, c.rho);
  Eigen::VectorXd y = scheme.uniform_state();
  auto tl = study::Clock::now();
  c.all = rate_form_spectrum(scheme, y);
  c.cls = rate_form_spectrum(scheme, y, {.basis = b.excited});
  c.wall_linear = study::seconds_since(tl);
  c.equilibrium = equilibrium_residual(scheme, b.scene, s.steel);
  scheme.set_velocity(y, b.scene.centre, kick(b.scene));
  tl = study::Clock::now();
  c.run =
      run_rate_form(scheme, y, {.dt = s.dt, .t_end = s.o.t_end, .record_every = 10, .energy_growth = s.o.stop_growth});
  c.wall_run = study::seconds_since(tl);
  c.fit = fit_growth(c.run, c.run.times.back(), s.o.onset);
  c.ke_max = ke_max_over_ke0(c.run);
  // The verdict at the run's dt (run_rate_form rounds dt to t_end / steps), in the excited class, at rest.
  tl = study::Clock::now();
  c.v = checked_verdict(scheme, {.dt = c.run.dt}, s.detect, b.excited, form.name + ": ");
  c.wall_linear += study::seconds_since(tl);
  const bool lin_unstable = c.cls.growth_rate > s.detect;
  c.map_unstable = c.v.map_growth > s.detect;
  c.ratio = c.fit.grew && lin_unstable ? c.fit.gamma / c.cls.growth_rate : NAN;
  return c;
}

}  // namespace swegle_rate_form
