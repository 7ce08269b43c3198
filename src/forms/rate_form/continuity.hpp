#pragma once
/// \file continuity.hpp
/// Internal to src/forms: the kinematic sums of the rate form (rate_form.hpp), the velocity gradient and the density
/// rate, pair by pair (d = vhat_j - vhat_i, g = grad_i W_ij or Ghat_ij).
#include <Eigen/Core>

#include "always_inline.hpp"

namespace sphstab::rate_form_detail {

/// [GMS2001, (3.10)] L^ab += V_j d^a g^b: the velocity gradient dv^a/dx^b (Powell (1.33) prints v_i - v_j, a sign
/// typo: docs/conventions.md). `weighted_d` is V_j d (plain gradient) or d (Ghat_ij already holds V_j).
template <class Mat, class Vec, class G>
SPHSTAB_ALWAYS_INLINE inline void add_velocity_gradient(Mat& L, const Vec& weighted_d, const G& g) {
  L += weighted_d * g.transpose();
}

/// [GMS2001, (3.8)] summation: drho_i/dt = sum_j m_j (vhat_i - vhat_j) . G_ij, one pair's term m_j d . g (subtracted
/// by the caller). Not dot(): it conjugates complex steps.
template <class M, class Vec, class G>
SPHSTAB_ALWAYS_INLINE inline auto continuity_term(const M& m_j, const Vec& d, const G& g) {
  return m_j * d.cwiseProduct(g).sum();
}

/// [GMS2001, (3.9)] divergence: drho_i/dt = -rho_i tr L_i (Powell (1.32) lacks the factor rho_i).
template <class Scalar, class Mat>
SPHSTAB_ALWAYS_INLINE inline Scalar continuity_divergence(const Scalar& rho, const Mat& L) {
  return -rho * L.trace();
}

}  // namespace sphstab::rate_form_detail
