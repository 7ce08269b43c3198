#pragma once
/// \file artificial_stress_particle.hpp
/// The artificial stress of one particle written once, inline, for every caller: models/artificial_stress.cpp
/// (principal_frame(), artificial_stress()) and the rate form's per-particle pass (src/forms/rate_form/), which reads
/// less of the frame. `Frame::Full` computes every field of PrincipalFrame; `Frame::Read` skips the angle theta (an
/// atan2 that artificial_stress() does not read) and the rotation c^2, s^2, sc where artificial_stress() does not read
/// it (unless exactly one principal stress is tensile). The operations that are done are the same in both, so both
/// give the same bits for every value artificial_stress() returns.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/models/artificial_stress.hpp"
#include "sphstab/numerics/real_part.hpp"

namespace sphstab::artificial_stress_detail {

enum class Frame { Full, Read };

/// Principal values and rotation of a symmetric tensor (GMS (6.1)-(6.3)), analytic in the entries.
template <Frame kFrame, class Scalar>
inline PrincipalFrame<Scalar> principal_frame(const SymmetricTensor2<Scalar>& sigma) {
  using detail::re;
  using std::sqrt;
  PrincipalFrame<Scalar> f;
  const Scalar mean = 0.5 * (sigma.xx + sigma.yy);
  const Scalar half_diff = 0.5 * (sigma.xx - sigma.yy);
  // radius = sqrt(half_diff^2 + sxy^2): the analytic square (not |.|^2) so that complex steps pass through,
  // scaled by the larger real magnitude against underflow and overflow.
  const double scale = std::max(std::abs(re(half_diff)), std::abs(re(sigma.xy)));
  if (!(scale > 0)) {  // isotropic (real parts): every direction is principal, take theta = 0
    f.major = mean;
    f.minor = mean;
    return f;
  }
  const Scalar a = half_diff / scale, b = sigma.xy / scale;
  const Scalar rho = sqrt(a * a + b * b);  // in [1, sqrt 2] (real part)
  const Scalar radius = scale * rho;
  f.major = mean + radius;
  f.minor = mean - radius;
  if constexpr (kFrame == Frame::Read)
    if (re(f.minor) > 0 || !(re(f.major) > 0)) return f;  // artificial_stress() reads no rotation
  // c^2 = (r + d)/(2r), s^2 = (r - d)/(2r) with d = half_diff; r^2 - d^2 = sxy^2 removes the cancellation.
  // Scaled quantities (a, b, rho = radius / scale) keep every product representable.
  if (re(a) >= 0) {
    f.cc = (rho + a) / (2.0 * rho);
    f.ss = b * b / (2.0 * rho * (rho + a));
  } else {
    f.ss = (rho - a) / (2.0 * rho);
    f.cc = b * b / (2.0 * rho * (rho - a));
  }
  f.sc = b / (2.0 * rho);  // sin(2 theta)/2
  if constexpr (kFrame == Frame::Full) f.theta = 0.5 * std::atan2(2.0 * re(sigma.xy), re(sigma.xx - sigma.yy));
  return f;
}

/// Back-rotation (GMS (6.5)-(6.7)).
template <class Scalar>
inline SymmetricTensor2<Scalar> back_rotate(const PrincipalFrame<Scalar>& f, const Scalar& rbar_xx,
                                            const Scalar& rbar_yy) {
  return {f.cc * rbar_xx + f.ss * rbar_yy, f.ss * rbar_xx + f.cc * rbar_yy, f.sc * (rbar_xx - rbar_yy)};
}

/// R of one particle (GMS (6.4)-(6.7)): Rbar = -epsilon sigmabar / rho^2 on each tensile principal stress. epsilon >= 0
/// is the caller's to check; throws std::invalid_argument for a density whose real part is not finite and > 0.
template <Frame kFrame, class Scalar>
inline SymmetricTensor2<Scalar> particle_artificial_stress(const SymmetricTensor2<Scalar>& sigma, const Scalar& density,
                                                           double epsilon) {
  using detail::re;
  if (!(re(density) > 0) || !std::isfinite(re(density)))
    throw std::invalid_argument("artificial_stress: density must be finite and > 0 (got " + format_number(re(density)) +
                                ")");
  const PrincipalFrame<Scalar> f = principal_frame<kFrame>(sigma);
  const bool major_tensile = re(f.major) > 0, minor_tensile = re(f.minor) > 0;  // minor tensile => major tensile
  const Scalar k = -epsilon / (density * density);
  if (minor_tensile) return {k * sigma.xx, k * sigma.yy, k * sigma.xy};  // back-rotation of the full tensor
  if (!major_tensile) return {};                                         // both compressive (or zero)
  return back_rotate(f, Scalar(k * f.major), Scalar(0));                 // GMS (6.4)-(6.7), radius > 0 here
}

}  // namespace sphstab::artificial_stress_detail
