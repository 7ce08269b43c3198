#pragma once
/// \file rate_form_run.hpp
/// Time stepping of the rate-form scheme (forms/rate_form.hpp) by the predictor-corrector of Gray, Monaghan & Swift
/// [GMS2001, (6.14)-(6.18)], with the stress integrated like the density (GMS do not say; the natural reading):
///   predictor   v_p = v0 + dt a0,  rho_p = rho0 + dt drho0,  S_p = S0 + dt dS0,
///               x = x0 + dt vhat0 + dt^2/2 a0   (particles move with the XSPH velocity; x is not corrected)
///   corrector   v = v_p + dt/2 (a - a0),  rho = rho_p + dt/2 (drho - drho0),  S likewise,
/// with (a, drho, dS) = F(x, v_p, rho_p, S_p). Two rate evaluations per step. Second order in dt without XSPH; with
/// XSPH, d^2x/dt^2 = d vhat/dt is not a0, so GMS's uncorrected x is FIRST order
/// (tests/growth/rate_form_spectrum_test.cpp measures 1.25). PositionUpdate::Trapezoid corrects x like the rest, x = x0
/// + dt/2 (vhat0 + vhat_p) (Heun for the whole state), which is second order with XSPH too.
///
/// An unstable run is a result, not an exception: the run stops at the first non-finite state, non-positive density
/// or kinetic-energy growth beyond the limit, and reports the step, time and particle (RunStatus, message), keeping
/// the record written so far.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/leapfrog.hpp"

namespace sphstab {

enum class PositionUpdate { Gms, Trapezoid };

struct RateFormRunOptions {
  double dt = 0;                                   ///< > 0
  PositionUpdate positions = PositionUpdate::Gms;  ///< GMS (6.15) uncorrected, or trapezoid-corrected (see above)
  double t_end = 0;                                ///< > 0; dt is reduced to t_end / ceil(t_end / dt)
  int record_every = 1;  ///< kinetic energy recorded every k steps (>= 1), and at the last step
  double energy_growth = std::numeric_limits<double>::infinity();  ///< stop when KE > energy_growth * KE(0)
  /// Called at every record with (step, time, state); may be empty.
  std::function<void(long, double, const Eigen::VectorXd&)> observer;
};

struct RateFormRunResult {
  RunStatus status = RunStatus::Completed;
  std::string message;
  long steps = 0;
  double time = 0, dt = 0;
  int particle = -1;  ///< the particle that stopped the run (non-finite or non-positive density), or -1
  std::vector<double> times, kinetic_energy;
  Eigen::VectorXd y;  ///< the last state (the failing one for a stopped run)
  long rate_evaluations = 0;
  double wall_seconds = 0;
  bool completed() const { return status == RunStatus::Completed; }
};

/// Runs the GMS predictor-corrector from y0 (size scheme.size()). Throws std::invalid_argument for dt <= 0,
/// t_end <= 0, record_every < 1 or a state of the wrong size.
template <int Dim>
RateFormRunResult run_rate_form(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0,
                                const RateFormRunOptions& options);

}  // namespace sphstab
