#pragma once
/// \file artificial_stress.hpp
/// Internal to src/forms: the rate form's artificial stress [GMS2001, (6.1)-(6.9)]: R_i of each particle (the tensile
/// principal part of sigma_i, models/artificial_stress_particle.hpp: one copy with models/) and the pair factor f_ij^n,
/// f = W_ij / W(dp).
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "always_inline.hpp"
#include "sphstab/kernel/kernel_shapes.hpp"
#include "sphstab/models/artificial_stress_particle.hpp"
#include "sphstab/numerics/real_part.hpp"

namespace sphstab::rate_form_detail {

/// R_i = -eps_a sigma_i^+ / rho_i^2: 1D the tensile sigma_xx; 2D the tensile principal part (GMS (6.4)-(6.7)).
/// Throws std::invalid_argument for a density that is not finite and > 0 (2D; the run reports it).
template <int Dim, class Scalar>
SPHSTAB_ALWAYS_INLINE inline Eigen::Matrix<Scalar, Dim, Dim> particle_artificial_stress(
    const Eigen::Matrix<Scalar, Dim, Dim>& sigma, const Scalar& rho, double epsilon) {
  Eigen::Matrix<Scalar, Dim, Dim> R = Eigen::Matrix<Scalar, Dim, Dim>::Zero();
  if constexpr (Dim == 1) {
    if (detail::re(sigma(0, 0)) > 0) R(0, 0) = -epsilon * sigma(0, 0) / (rho * rho);
  } else {
    using artificial_stress_detail::Frame;
    const SymmetricTensor2<Scalar> t{sigma(0, 0), sigma(1, 1), sigma(0, 1)};
    const SymmetricTensor2<Scalar> r =
        artificial_stress_detail::particle_artificial_stress<Frame::Read>(t, rho, epsilon);
    R << r.xx, r.xy, r.xy, r.yy;
  }
  return R;
}

/// artificial_stress_pair_factor(w, w_dp, n) (models/artificial_stress.hpp/.cpp: f^n by repeated multiplication for
/// integer n <= 1024, exp(n log f) otherwise, 0 for f <= 0) with the exponent's test done once; n >= 0 finite is
/// checked by the constructor.
class PairFactor {
 public:
  PairFactor(double w_dp, double n)
      : m_w_dp(w_dp), m_n(n), m_integer(n == std::floor(n) && n <= 1024), m_int(m_integer ? static_cast<int>(n) : 0) {}
  /// f[q] = (w[q] / W(dp))^n for q < len.
  template <class Scalar>
  void row(std::size_t len, const Scalar* __restrict w, Scalar* __restrict f) const {
    if (m_int == 4) {
      for (std::size_t q = 0; q < len; ++q) {
        const Scalar x = Scalar(w[q] / m_w_dp);
        if constexpr (std::is_same_v<Scalar, double>)
          f[q] = (x * x) * (x * x);  // ipow(x, 4) = 1 * ((x * x) * (x * x)), and 1 * y = y for a real y
        else
          f[q] = detail::ipow(x, 4);
      }
    } else {
      for (std::size_t q = 0; q < len; ++q) f[q] = (*this)(w[q]);
    }
  }
  /// row() for the pair loop: f[q] = (w[q] (1 / W(dp)))^4 for GMS's n = 4 (within rounding of row()), row() otherwise.
  void row_by_reciprocal(std::size_t len, const double* __restrict w, double* __restrict f) const {
    if (m_int != 4) return row(len, w, f);
    const double inv = reciprocal_w_dp();
    for (std::size_t q = 0; q < len; ++q) {
      const double x = w[q] * inv;
      f[q] = (x * x) * (x * x);
    }
  }
  /// row_by_reciprocal() is (w (1 / W(dp)))^4 (pair_lanes.hpp computes it by lanes).
  bool fourth_power() const { return m_int == 4; }
  double reciprocal_w_dp() const { return 1.0 / m_w_dp; }
  template <class Scalar>
  Scalar operator()(const Scalar& w) const {
    const Scalar x = Scalar(w / m_w_dp);
    if (m_int == 4) return detail::ipow(x, 4);  // GMS's n = 4, unrolled
    if (m_integer) return detail::ipow(x, m_int);
    if (detail::re(x) <= 0) return Scalar(0);
    using std::exp;
    using std::log;
    return exp(m_n * log(x));
  }

 private:
  double m_w_dp, m_n;
  bool m_integer;
  int m_int;
};

}  // namespace sphstab::rate_form_detail
