#pragma once
/// \file xsph.hpp
/// Internal to src/forms: the XSPH velocity [GMS2001, (3.6)], vhat_i = v_i + eps_x sum_j (m_j / rhobar_ij)
/// (v_j - v_i) W_ij, by which the rate form moves its particles and takes its velocity gradient.

#include "always_inline.hpp"

namespace sphstab::rate_form_detail {

/// The weight of neighbour j: eps_x m_j W_ij / rhobar_ij, rhobar_ij = (rho_i + rho_j) / 2.
template <class Scalar>
SPHSTAB_ALWAYS_INLINE inline Scalar xsph_weight(double eps, double m_j, const Scalar& w, const Scalar& rho_i,
                                                const Scalar& rho_j) {
  return eps * m_j * w / (0.5 * (rho_i + rho_j));
}

}  // namespace sphstab::rate_form_detail
