#pragma once
/// \file bar_wave_exact.hpp
/// Exact solution of the 1D velocity-jump problem on a finite elastic bar (Powell ch. 2 §3.1, eq. 2.68, with the
/// truncating NRBC replaced by a physical end):
///   rho u_tt = E u_xx on 0 < x < L, u(x, 0) = 0, u_t(x, 0) = g(x) = v_left (x < x_jump), v_right (x > x_jump),
///   each end free (sigma = E u_x = 0) or fixed (u = 0).
///
/// Derivation (method of images). Extend g to the whole line by reflection about x = 0 and x = L: even about a
/// free end (then u_x = 0 there by symmetry), odd about a fixed end (u = 0 there). The extension ĝ satisfies
/// ĝ(-y) = s0 ĝ(y), ĝ(L + y) = sL ĝ(L - y) (s = +1 free, -1 fixed), hence ĝ(y + 2L) = s0 sL ĝ(y). d'Alembert on the
/// line (zero initial displacement):
///   u(x,t) = 1/(2c) [Ĝ(x + ct) - Ĝ(x - ct)],  Ĝ(y) = ∫_0^y ĝ,  c = sqrt(E / rho)
///   v(x,t) = u_t = ½ [ĝ(x + ct) + ĝ(x - ct)]
///   sigma(x,t) = E u_x = (rho c / 2) [ĝ(x + ct) - ĝ(x - ct)]      (E / (2c) = rho c / 2)
/// A left-going wave ĝ(x + ct) hitting a free end comes back as the right-going ĝ(x - ct) with the same
/// velocity and opposite stress: free ends invert stress (fixed ends invert velocity). Across a discontinuity
/// moving with speed s = ±c the jumps satisfy [sigma] = -rho s [v] (Rankine-Hugoniot for rho v_t = sigma_x,
/// sigma_t = E v_x). The solution is periodic in t with period 2L/c (same end types) or 4L/c (mixed).
/// At a discontinuity of ĝ the mean of the one-sided values is used.
///
/// Units as given (Powell: g, cm, µs, stress in Mbar; rho = 7.8, E = 2.1 → c = 0.518875 cm/µs).
#include <cmath>

namespace sphstab {

enum class BarEnd { Free, Fixed };

struct BarJumpProblem {
  double length = 1.0;          ///< L > 0
  double density = 7.8;         ///< rho > 0
  double youngs_modulus = 2.1;  ///< E > 0
  double jump_position = 0.35;  ///< 0 < x_jump < L
  double velocity_left = 0.01;  ///< g for x < x_jump
  double velocity_right = -0.01;
  BarEnd left = BarEnd::Free, right = BarEnd::Free;
  double wave_speed() const { return std::sqrt(youngs_modulus / density); }
};

class BarJumpExact {
 public:
  /// Throws std::invalid_argument for non-positive L, rho, E or a jump outside (0, L).
  explicit BarJumpExact(const BarJumpProblem& problem);

  const BarJumpProblem& problem() const { return m_p; }
  double wave_speed() const { return m_c; }
  /// Time period of the solution: 2L/c (both ends of one type) or 4L/c (mixed).
  double period() const;

  /// g(x) for x in [0, L] (mean value at the jump).
  double initial_velocity(double x) const;
  /// ĝ(y), the reflected extension, any real y.
  double extended_velocity(double y) const;
  /// Ĝ(y) = ∫_0^y ĝ(s) ds, any real y (closed form, no quadrature).
  double extended_integral(double y) const;

  double velocity(double x, double t) const;
  double stress(double x, double t) const;
  double displacement(double x, double t) const;
  /// ∫_0^L rho v dx (closed form via Ĝ); constant for free-free ends.
  double momentum(double t) const;

 private:
  /// ∫_0^r g(s) ds for r in [0, L].
  double base_integral(double r) const;
  BarJumpProblem m_p;
  double m_c;
  double m_s0, m_sL;
};

}  // namespace sphstab
