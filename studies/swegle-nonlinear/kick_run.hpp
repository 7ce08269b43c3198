#pragma once
// One kicked run of the nonlinear Swegle study: the centre particle kicked along +x at v0, run with the GMS
// predictor-corrector or Powell's leap-frog (integrate/rate_form_run.hpp) at a step, and the fits of its kinetic-energy
// growth, over the whole run and before saturation. Also what every run of the study shares (Setup).
#include <Eigen/Core>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "common/rate_form_swegle.hpp"
#include "common/study.hpp"
#include "sphstab/growth/growth_fit.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace swegle_nonlinear {

using namespace sphstab;
using namespace sphstab::study::rate_form_swegle;

/// What every case of the study shares: the options, the block (with its mirror class), the steel, the runs' step,
/// the fit's detection floor and the kick speeds.
struct Setup {
  Options o;
  Block block;
  ElasticMaterial steel = ElasticMaterial::from_bulk_shear(1.0, 0.0, 1.0);
  double dt = 0, floor = 0;
  std::vector<double> v0s;
};

inline const std::vector<RateFormIntegrator> kIntegrators = {RateFormIntegrator::PredictorCorrector,
                                                             RateFormIntegrator::Leapfrog};

inline std::string integrator_name(RateFormIntegrator integrator) {
  return integrator == RateFormIntegrator::Leapfrog ? "leapfrog" : "predictor-corrector";
}

struct Measured {
  RateFormRunResult run;
  ExponentialGrowthFit fit;
  double ke_max = 0;  // max KE / KE0
  // Fit over the pre-saturation window only: it ends when KE first reaches 1e-2 of its maximum (growth, if any, is
  // then still exponential). Separates a growth RATE that depends on v0 from a growth that saturates.
  ExponentialGrowthFit early;
  std::string status;  // run_status_name, or "exception"
  double wall = 0;
};

inline Measured measure(const Setup& s, const RateFormScheme<2>& scheme, double v0, RateFormIntegrator integrator,
                        double step) {
  Eigen::VectorXd y = scheme.uniform_state();
  scheme.set_velocity(y, s.block.scene.centre, Eigen::Vector2d(v0, 0));
  Measured m;
  const auto tr = study::Clock::now();
  // A run can end in an exception (the NCSPH moment matrix turns singular when particles clump at large v0): the
  // observer keeps the kinetic-energy series up to the last record before it.
  std::vector<double> times, kinetic;
  try {
    m.run = run_rate_form(scheme, y,
                          {.dt = step,
                           .t_end = s.o.t_end,
                           .record_every = 10,
                           .energy_growth = s.o.stop_growth,
                           .observer =
                               [&](long, double t, const Eigen::VectorXd& state) {
                                 times.push_back(t);
                                 kinetic.push_back(scheme.kinetic_energy(state));
                               },
                           .integrator = integrator});
    m.status = run_status_name(m.run.status);
  } catch (const std::exception& e) {
    std::printf("  run ended by an exception: %s\n", e.what());
    m.status = "exception";
    m.run.times = times;
    m.run.kinetic_energy = kinetic;
    m.run.time = times.back();
    m.run.dt = step;
  }
  m.wall = study::seconds_since(tr);
  const double ke0 = m.run.kinetic_energy.front();
  m.fit = fit_growth(m.run, m.run.times.back(), s.o.onset);
  m.ke_max = ke_max_over_ke0(m.run);
  double t_sat = m.run.times.back();
  for (std::size_t k = 0; k < m.run.times.size(); ++k)
    if (m.run.kinetic_energy[k] >= 1e-2 * m.ke_max * ke0) {
      t_sat = m.run.times[k];
      break;
    }
  m.early = fit_growth(m.run, t_sat, s.o.onset);
  return m;
}

}  // namespace swegle_nonlinear
