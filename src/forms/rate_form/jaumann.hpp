#pragma once
/// \file jaumann.hpp
/// Internal to src/forms: the hypoelastic stress rate of the rate form (rate_form.hpp) from a particle's velocity
/// gradient L and stored deviator S.
#include <Eigen/Core>

#include "always_inline.hpp"
#include "equation_of_state.hpp"

namespace sphstab::rate_form_detail {

/// dS/dt, written to out[0 .. kStress): 1D uniaxial strain (4 mu / 3) L_xx; 2D the Jaumann rate [GMS2001, (2.3)]
/// 2 mu (D - tr(D)/3 I) + Omega S - S Omega in 3 x 3 with D_zz = 0 and Omega in-plane (S_zz = -(S_xx + S_yy) is
/// carried implicitly), stored xx, yy, xy.
template <int Dim, class Scalar, class Out>
SPHSTAB_ALWAYS_INLINE inline void deviator_rate(const Eigen::Matrix<Scalar, Dim, Dim>& L,
                                                const Eigen::Matrix<Scalar, Dim == 1 ? 1 : 3, 1>& S, double mu,
                                                Out&& out) {
  using Mat = Eigen::Matrix<Scalar, Dim, Dim>;
  if constexpr (Dim == 1) {
    out[0] = (4.0 * mu / 3.0) * L(0, 0);
  } else {
    const Mat D = 0.5 * (L + L.transpose()), W = 0.5 * (L - L.transpose());
    const Mat s = deviator_matrix<Dim, Scalar>(S);
    const Scalar tr = D.trace();
    const Mat ds = 2.0 * mu * (D - (tr / 3.0) * Mat::Identity()) + W * s - s * W;
    out[0] = ds(0, 0);
    out[1] = ds(1, 1);
    out[2] = ds(0, 1);
  }
}

}  // namespace sphstab::rate_form_detail
