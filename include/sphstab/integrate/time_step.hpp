#pragma once
/// \file time_step.hpp
/// Time-step rules for explicit leap-frog: the CFL rule dt = C h / c and the linear stability limit
/// dt < 2 / sqrt(lambda_max(A)) of ü = -A u; for first-order systems y' = F(y) (the rate form), the staggered
/// leap-frog limit 2 / max |Im lambda(J)| and Heun's amplification (below; growth/rate_form_time_step.hpp applies
/// them to the rate-form spectrum).
///
/// \note CFL constant. The default C = 0.3 is the Courant factor customary in SPH since Monaghan's time-step
///       criterion dt = 0.3 min h / (c + ...) (Monaghan 1992, Annu. Rev. Astron. Astrophys. 30:543; quoted from
///       memory, the reference text is not in the seeds), here without its viscous terms, with h the smoothing
///       length and c the (bar) wave speed. Powell's MCM input uses a time-step scale factor TSSFAC = 0.8 on its own
///       critical step (thesis App. B), a different normalisation. The linear limit in the same units is
///       C_max = 2 c / (h sqrt(lambda_max)); measured for the 1D bar operators (results/speed-vs-error/summary.md):
///       C_max = 2.000 (cubic B-spline, h = dx), 1.906 (h = 1.3 dx), 1.932 (h = 2 dx) with mirror ghosts, down to
///       1.245 for the ghost-free corrected gradient, so C = 0.3 is 16-24 % of the limit. Leap-frog for ü = -A u
///       with real A-eigenvalue mu > 0 is stable iff dt <= 2 / sqrt(mu) (the amplification factors of the mode then
///       have modulus 1).
#include <Eigen/Core>
#include <complex>
#include <string>

#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

/// Monaghan's Courant factor (see the note above).
inline constexpr double kDefaultCourant = 0.3;

/// dt = courant * h / wave_speed; throws std::invalid_argument unless all three are finite and > 0.
double cfl_time_step(double courant, double h, double wave_speed);

struct StabilityOptions {
  /// A is symmetric in the Euclidean inner product (Spectra SymEigsSolver; eigenvalues real). Use false
  /// (general Arnoldi) when only similar to a symmetric matrix (unequal masses) or non-symmetric.
  bool symmetric = false;
  /// Up to this many DOFs A is built densely (ndof evaluations of a) and all eigenvalues are computed.
  long dense_limit = 400;
  int max_iterations = 2000;  ///< Spectra restarts
  double tolerance = 1e-10;   ///< Spectra relative tolerance
  /// A v = -(a(s v) - a(0)) / s: exact for a linear a (any s); for a nonlinear force, a finite-difference
  /// linearisation at u = 0 with step s.
  double probe_scale = 1.0;
};

/// The largest-modulus part of the spectrum of A = -da/du and the leap-frog limit it implies.
struct StabilityEstimate {
  double lambda_max = 0;            ///< |mu| of the largest-modulus eigenvalue of A
  std::complex<double> dominant{};  ///< that eigenvalue
  /// dt limit 2 / sqrt(lambda_max); meaningful when `dominant` is real and positive (the semi-discrete modes
  /// are oscillatory). A dominant eigenvalue with negative real part or a large imaginary part means the
  /// semi-discrete system itself is unstable (no dt helps).
  double dt_limit = 0;
  bool dominant_real_positive = false;  ///< Re > 0 and |Im| <= 1e-8 |mu|
  /// Minimum real part over all eigenvalues (dense method only; NaN otherwise): < 0 means an exponentially
  /// growing mode of ü = -A u for every dt.
  double min_real = 0;
  bool converged = false;
  std::string method;  ///< "dense", "spectra-sym" or "spectra-gen"
};

/// Estimates the leap-frog stability limit of ü = a(u) linearised at u = 0 (a(0) subtracted). Throws
/// std::invalid_argument for ndof < 1 or a missing callable.
StabilityEstimate estimate_stability_limit(const AccelerationFunction& accel, long ndof,
                                           const StabilityOptions& options = {});

/// First-order systems y' = F(y) (the rate form) from the eigenvalues lambda of J = dF/dy.
///
/// Staggered leap-frog [Powell2012, (1.40)] on y = (Q, v), Q' = P v, v' = K Q (J = [[0, P], [K, 0]], the rate form at
/// rest without viscosity: Q = (x, rho, S)): v^{n+3/2} - 2 v^{n+1/2} + v^{n-1/2} = dt^2 B v^{n+1/2}, B = K P. A mode
/// B w = mu w multiplies by z with z + 1/z = 2 + dt^2 mu; the roots have product 1, so |z| = 1 (stable, undamped)
/// iff mu is real and -4 <= dt^2 mu <= 0. The eigenvalues of J are lambda = +-sqrt(mu), so for oscillatory modes
/// (lambda = +-i omega) the limit is
///     dt_max = 2 / max |Im lambda|.
/// Modes with Re lambda != 0 grow (or, for mu > 0, track the physical growth) at any dt, as they should.
///
/// Heun / the predictor-corrector (rate_form_run.hpp) multiplies by R(z) = 1 + z + z^2/2, z = dt lambda, and
///     |R(z)|^2 - 1 = t [2a + 2a^2 t + a |lambda|^2 t^2 + |lambda|^4 t^3 / 4],   lambda = a + ib, t = dt.
/// For a = 0 (every mode of the conservative rate form at rest) this is t^4 |lambda|^4 / 4 > 0: there is NO stable
/// dt; the growth per unit time is ln|R| / dt ~ dt^3 |lambda|^4 / 8. Only damping (a < 0, e.g. the always-on
/// viscosity) gives a finite limit: the first positive root of the cubic bracket.

/// dt_max = 2 / max |Im lambda| (infinity when every lambda is real or there are none).
double leapfrog_time_step_limit(const Eigen::VectorXcd& eigenvalues);

/// |R(z)| = |1 + z + z^2/2|, Heun's amplification factor.
double heun_amplification(std::complex<double> z);

/// Largest dt with |R(t lambda)| <= 1 for every eigenvalue and every t in (0, dt]: 0 when some lambda != 0 has
/// Re lambda >= -1e-12 |lambda| (undamped or growing: unstable at every dt), infinity for no non-zero eigenvalue.
double heun_time_step_limit(const Eigen::VectorXcd& eigenvalues);

/// Growth rate of Heun's one-step map y1 = (I + dt J + dt^2 J^2 / 2) y0 on the eigenvalues of J: max over lambda of
/// ln|R(dt lambda)| / dt (on the imaginary axis |R|^2 = 1 + (omega dt)^4 / 4 > 1: Heun amplifies undamped
/// oscillations). Throws std::invalid_argument unless dt is finite and > 0; 0 for no eigenvalues.
double heun_growth_rate(const Eigen::VectorXcd& eigenvalues, double dt);

/// Spurious growth rate of Heun at dt: max over lambda of ln|R(dt lambda)| / dt - Re lambda (the numerical excess
/// over the exact growth; dt^3 max|lambda|^4 / 8 to leading order for imaginary lambda). Throws
/// std::invalid_argument unless dt is finite and > 0.
double heun_excess_growth_rate(const Eigen::VectorXcd& eigenvalues, double dt);

/// Growth rate of leap-frog (kick-drift-kick, equivalently the central difference u_{n+1} = 2 u_n - u_{n-1} -
/// dt^2 A u_n [Ismail2009, (4.46)]) for u'' = -A u, from the eigenvalues mu of A: a mode multiplies u by z per step
/// with z^2 - (2 - dt^2 mu) z + 1 = 0, so the rate is max over mu of ln max|z| / dt. It is 0 when every mu is real
/// in [0, 4 / dt^2] (|z| = 1); a real mu > 4 / dt^2 is the time-step instability, a complex or negative mu grows at
/// every dt. The same number as leapfrog_map_growth's gamma (growth/linear_growth.hpp: the dense 2n x 2n map) without
/// forming the map. Throws std::invalid_argument unless dt is finite and > 0; 0 for no eigenvalues.
double leapfrog_growth_rate(const Eigen::VectorXcd& mu, double dt);

}  // namespace sphstab
