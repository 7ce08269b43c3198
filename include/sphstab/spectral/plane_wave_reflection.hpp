#pragma once
/// \file plane_wave_reflection.hpp
/// Reflection of plane waves at an absorbing (non-reflecting) boundary condition, the analytic side of Powell's
/// ch. 2: the boundary x = 0 of the half-space x < 0, outward normal +x, a wave of angular frequency 1 hitting it at
/// angle theta from the normal. A condition B(d/dt, d/dx, d/dy) u = 0 holds at x = 0 for the sum of the incident and
/// the reflected waves; with d/dt -> -i, d/dx -> i k_x / c, d/dy -> i k_y / c per wave (k unit, c its speed) it is a
/// linear system for the reflected amplitudes: [Powell2012, (2.49)].
///
/// Elastic (plane strain, u_tt = c_s^2 Lap u + (c_p^2 - c_s^2) grad div u, (2.38)): an incident P wave along
/// k = (cos theta, sin theta) (polarisation k) reflects as P along (-cos theta, sin theta) and S along (-zeta, eta),
/// eta = (c_s / c_p) sin theta (polarisation (-k_y, k_x)); an incident S wave as S along (-cos theta, sin theta) and P
/// along (-nu, xi), xi = (c_p / c_s) sin theta, evanescent beyond the critical angle asin(c_s / c_p) (nu imaginary,
/// decaying into the body) [Powell2012, (2.46)-(2.47)]. Amplitudes are for unit polarisation vectors.
///
/// \code{.cpp}
/// auto r = sphstab::elastic_reflection(sphstab::AbsorbingCondition::Sochaki, 1.8708, 1.0, M_PI / 4,
///                                      sphstab::WaveKind::P);  // |r.to_p|, |r.to_s|
/// double cr = sphstab::rayleigh_speed(1.8708, 1.0);            // 0.92741 c_s at nu = 0.3
/// \endcode
#include <complex>
#include <vector>

#include "sphstab/forms/absorbing_boundary.hpp"  // AbsorbingCondition

namespace sphstab {

enum class WaveKind { P, S };

/// Reflected amplitudes per unit incident amplitude (complex: phase included).
struct Reflection {
  std::complex<double> to_p;  ///< reflected P (for S incidence beyond the critical angle: the evanescent P)
  std::complex<double> to_s;  ///< reflected S
  bool p_evanescent = false;  ///< the reflected P does not propagate (S incidence beyond asin(c_s / c_p))
};

/// The reflection of an incident P or S wave at angle theta in [0, pi/2) from the normal. speed_scale multiplies the
/// condition's c_p and c_s (not the waves'): Powell's "H" is ClaytonEngquist with k.n = cos theta, Higdon's first-order
/// factor the same with 1 / cos theta (AbsorbingParticles::speed_scale). Throws std::invalid_argument unless
/// 0 < c_s < c_p (finite), theta is in [0, pi/2) and speed_scale is finite and > 0, and std::domain_error when the
/// 2 x 2 system is singular (the condition admits a free boundary wave at this angle).
Reflection elastic_reflection(AbsorbingCondition condition, double c_p, double c_s, double theta, WaveKind incident,
                              double speed_scale = 1.0);

/// The fraction of the incident wave's energy flux through the boundary that the reflected waves carry back:
/// |A_P|^2 (c_P cos theta_P) / (c_in cos theta) + |A_S|^2 (c_S cos theta_S) / (c_in cos theta) over the propagating
/// reflected waves (an evanescent P carries none), for unit-polarisation amplitudes (energy flux of a plane wave:
/// rho omega^2 |A|^2 c / 2 along its direction). Same arguments and errors as elastic_reflection.
double reflected_energy(AbsorbingCondition condition, double c_p, double c_s, double theta, WaveKind incident,
                        double speed_scale = 1.0);

/// |R| of a scalar wave (u_tt = c^2 Lap u) at Higdon's condition prod_i (cos a_i d_t + c d_x) u = 0 [Powell2012,
/// (2.32), with the factor corrected (cos a_i d_t)]: prod_i |cos theta - cos a_i| / (cos theta + cos a_i). One a = 0
/// is the first-order Engquist-Majda condition, |R| = tan^2(theta / 2). Throws std::invalid_argument for theta outside
/// [0, pi/2) or an angle outside [0, pi/2).
double scalar_reflection(double theta, const std::vector<double>& absorbing_angles = {0.0});

/// The Rayleigh surface-wave speed: the root c_r in (0, c_s) of (2 - c_r^2 / c_s^2)^2 = 4 sqrt(1 - c_r^2 / c_p^2)
/// sqrt(1 - c_r^2 / c_s^2) [Powell2012, (A.35)], to machine precision. Throws std::invalid_argument unless
/// 0 < c_s < c_p.
double rayleigh_speed(double c_p, double c_s);

}  // namespace sphstab
