#pragma once
/// \file bulk_viscosity.hpp
/// Internal to src/forms: MCM's bulk viscosity (RateFormOptions::bulk_viscosity_*; [Powell2012, appendix, MCM input
/// deck, material card QBVC / LBVC]), the von Neumann-Richtmyer / DYNA form on the velocity divergence of a particle.
#include "always_inline.hpp"
#include "sphstab/numerics/real_part.hpp"

namespace sphstab::rate_form_detail {

/// q_i = rho_i h (Q1 h d_i^2 - Q2 c0 d_i) where d_i < 0 (compression; the real part decides), 0 otherwise.
/// @param q1_h Q1 h   @param q2_c0 Q2 c0   @param div d_i = sum_j (v_j - v_i) . Ghat_ij
template <class Scalar>
SPHSTAB_ALWAYS_INLINE inline Scalar bulk_viscosity_pressure(const Scalar& rho, double h, double q1_h, double q2_c0,
                                                            const Scalar& div) {
  if (detail::re(div) < 0) return rho * h * (q1_h * div * div - q2_c0 * div);
  return Scalar(0);
}

}  // namespace sphstab::rate_form_detail
