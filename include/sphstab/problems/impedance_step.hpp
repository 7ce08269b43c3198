#pragma once
/// \file impedance_step.hpp
/// Reflection and transmission of a 1D elastic wave at a step of acoustic impedance Z = rho c (medium 1 -> medium 2,
/// normal incidence), from continuity of stress and particle velocity at the interface and the characteristic
/// relations sigma = -Z v (right-going) and sigma = +Z v (left-going) of rho v_t = sigma_x, sigma_t = E v_x:
///
///   stress:    R_sigma = (Z2 - Z1) / (Z2 + Z1),   T_sigma = 2 Z2 / (Z1 + Z2)
///   velocity:  R_v = -R_sigma = (Z1 - Z2) / (Z1 + Z2),   T_v = 2 Z1 / (Z1 + Z2)
///
/// ([Ismail2009, §4.6.3] prints C_r = (z - 1)/(z + 1), C_t = 2z/(z + 1) with z = Z2/Z1: the stress coefficients).
/// Checks: 1 + R = T for both (continuity), R_sigma^2 + T_sigma^2 Z1/Z2 = 1 (energy flux sigma^2 / Z conserved).
/// Limits: Z2 -> inf (rigid) R_sigma = +1 (same-sign stress, velocity inverted); Z2 -> 0 (free) R_sigma = -1.
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphstab {

struct ImpedanceStep {
  double stress_reflection = 0, stress_transmission = 0, velocity_reflection = 0, velocity_transmission = 0;
};

/// Coefficients for impedances z1 (incident side) and z2, both finite and > 0; throws std::invalid_argument otherwise.
inline ImpedanceStep impedance_step(double z1, double z2) {
  if (!(z1 > 0) || !(z2 > 0) || !std::isfinite(z1) || !std::isfinite(z2))
    throw std::invalid_argument("impedance_step: impedances must be finite and > 0 (got " + std::to_string(z1) + ", " +
                                std::to_string(z2) + ")");
  const double s = z1 + z2;
  return {.stress_reflection = (z2 - z1) / s,
          .stress_transmission = 2 * z2 / s,
          .velocity_reflection = (z1 - z2) / s,
          .velocity_transmission = 2 * z1 / s};
}

}  // namespace sphstab
