#pragma once
/// \file pair_viscosity.hpp
/// Internal to src/forms: Monaghan's artificial viscosity of a particle pair [Monaghan1992] as the rate form uses it
/// (rate_form.hpp: it enters the momentum equation as -Pi_ij / rhobar_ij I, with the sign of docs/conventions.md).

#include "always_inline.hpp"

namespace sphstab::rate_form_detail {

/// mu_ij = h v_ij . r_ij / (r_ij^2 + eta^2), eta^2 = 0.01 h^2.
template <class Scalar>
SPHSTAB_ALWAYS_INLINE inline Scalar viscosity_mu(double h, const Scalar& v_dot_r, const Scalar& r2, double eta2) {
  return h * v_dot_r / (r2 + eta2);
}

/// Pi_ij = -alpha c0 mu_ij (+ beta mu_ij^2 with `quadratic`, the Compression switch), from alpha_c0 = -alpha c0.
template <class Scalar>
SPHSTAB_ALWAYS_INLINE inline Scalar viscosity_pi(const Scalar& mu_ij, double alpha_c0, double beta, bool quadratic) {
  Scalar pi = alpha_c0 * mu_ij;
  if (quadratic) pi += beta * mu_ij * mu_ij;
  return pi;
}

}  // namespace sphstab::rate_form_detail
