#pragma once
/// \file rate_form_time_step.hpp
/// The stability limits of the rate-form integrators (integrate/rate_form_run.hpp) from the full-state spectrum at
/// rest (growth/rate_form_spectrum.hpp), set against the CFL rule dt = C h / c_p (integrate/time_step.hpp).
///
///   leap-frog            dt_max = 2 / max |Im lambda|   [Powell2012, (1.40)]; exact for the linearised staggered map
///                        when Jvv = 0 (no viscosity; XSPH and artificial stress allowed)
///   predictor-corrector  largest dt with |1 + z + z^2/2| <= 1, z = dt lambda [GMS2001, (6.14)-(6.18)]: 0 for the
///                        conservative scheme (every lambda imaginary), see time_step.hpp. R is the exact one-step
///                        factor of both PositionUpdates at rest without pre-stress (rate_form_run.hpp); with
///                        pre-stress the predictor's x_p adds a dt^3 Jvx term, not a function of lambda alone
///   effective Courant    C_eff = dt_max c_p / h, c_p = material().p_wave_speed(): the CFL constant that reaches the
///                        leap-frog limit
/// Measured C_eff (tests/growth/rate_form_time_step_test.cpp; periodic lattices at xi = 1, cubic spline; the same for
/// mu = 0 and 0.3, since the top frequency is longitudinal, omega proportional to c_p): 1D 1.9212 (h = 1.3 dx),
/// 1.9404 (1.5 dx); 2D square 1.9242, 1.8687. The customary C = 0.3 (time_step.hpp) is 15-16 % of the limit. A
/// leap-frog run at 0.98 dt_max stays at its initial energy for 1000 steps, at 1.005 dt_max it blows up within ~45
/// steps.
///
/// \code{.cpp}
/// const sphstab::RateFormTimeStep ts = sphstab::rate_form_time_step(scheme, scheme.uniform_state());
/// if (ts.info() == sphstab::Status::Successful) opts.dt = 0.9 * ts.leapfrog;
/// \endcode
#include <Eigen/Core>
#include <complex>
#include <limits>
#include <string>

#include "sphstab/core/status.hpp"
#include "sphstab/forms/rate_form.hpp"

namespace sphstab {

struct RateFormTimeStep {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double max_imag = nan;             ///< max |Im lambda| over the non-zero spectrum
  std::complex<double> dominant;     ///< an eigenvalue attaining it
  double growth_rate = nan;          ///< max Re lambda: > 0 means the semi-discrete system itself grows
  double leapfrog = nan;             ///< 2 / max_imag
  double predictor_corrector = nan;  ///< heun_time_step_limit of the spectrum (0: unstable at every dt)
  double cfl_unit = nan;             ///< h / c_p, the CFL step at C = 1
  double courant = nan;              ///< C_eff = leapfrog / cfl_unit
  Status status = Status::NotComputed;
  std::string reason;
  Status info() const { return status; }
};

/// The limits at y (a state at rest, as rate_form_spectrum needs). Throws what rate_form_spectrum throws; a failed
/// spectrum gives its status and reason.
template <int Dim>
RateFormTimeStep rate_form_time_step(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y);

}  // namespace sphstab
