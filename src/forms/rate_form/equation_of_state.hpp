#pragma once
/// \file equation_of_state.hpp
/// Internal to src/forms: the rate form's stress of a particle from its density and stored deviator (rate_form.hpp).
/// Written once for real and complex (complex-step Jacobian) scalars.
#include <Eigen/Core>

#include "always_inline.hpp"

namespace sphstab::rate_form_detail {

/// [GMS2001, (2.7)] p = K (rho / rho0 - 1): the linear equation of state.
template <class Scalar>
SPHSTAB_ALWAYS_INLINE inline Scalar eos_pressure(double bulk_modulus, const Scalar& rho, double rho0) {
  return bulk_modulus * (rho / rho0 - 1.0);
}

/// The stored deviator as a Dim x Dim matrix: S_xx (1D); [S_xx S_xy; S_xy S_yy] (2D, stored xx, yy, xy).
template <int Dim, class Scalar>
SPHSTAB_ALWAYS_INLINE inline Eigen::Matrix<Scalar, Dim, Dim> deviator_matrix(
    const Eigen::Matrix<Scalar, Dim == 1 ? 1 : 3, 1>& S) {
  Eigen::Matrix<Scalar, Dim, Dim> s;
  if constexpr (Dim == 1) {
    s(0, 0) = S[0];
  } else {
    s << S[0], S[2], S[2], S[1];
  }
  return s;
}

/// sigma = S - p I (tension positive; p includes a bulk viscosity where one acts).
template <int Dim, class Scalar>
SPHSTAB_ALWAYS_INLINE inline Eigen::Matrix<Scalar, Dim, Dim> cauchy_stress(
    const Eigen::Matrix<Scalar, Dim == 1 ? 1 : 3, 1>& S, const Scalar& pressure) {
  using Mat = Eigen::Matrix<Scalar, Dim, Dim>;
  const Mat s = deviator_matrix<Dim, Scalar>(S);
  return s - pressure * Mat::Identity();
}

}  // namespace sphstab::rate_form_detail
