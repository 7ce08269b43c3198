#pragma once
/// \file kernel_shapes.hpp
/// Native shape functions f(s) and their first two derivatives (included by kernel.hpp).
#include <cmath>

#include "sphstab/kernel/kernel.hpp"

namespace sphstab {
namespace detail {

/// a^n for small n >= 0 by repeated multiplication (std::pow(double, int) goes through pow(double, double)).
template <class Scalar>
Scalar ipow(const Scalar& a, int n) {
  Scalar result(1.0), base = a;
  for (; n > 0; n >>= 1) {
    if (n & 1) result *= base;
    base *= base;
  }
  return result;
}

/// (a)^n and its derivatives with respect to s when a = c - s, for a > 0 (caller checks the support).
template <class Scalar>
Scalar power_term(const Scalar& a, int n, int order) {
  switch (order) {
    case 0:
      return ipow(a, n);
    case 1:
      return -double(n) * ipow(a, n - 1);
    default:
      return double(n) * double(n - 1) * ipow(a, n - 2);
  }
}

/// f = (1-s)^m p(s) with polynomial p given by coefficients c[0..k]; derivatives by the product rule.
template <class Scalar, int K>
Scalar wendland_like(const Scalar& s, int m, const double (&c)[K], int order) {
  Scalar a = 1.0 - s;
  Scalar p = 0.0, dp = 0.0, ddp = 0.0;
  for (int k = K - 1; k >= 0; --k) p = p * s + c[k];
  for (int k = K - 1; k >= 1; --k) dp = dp * s + double(k) * c[k];
  for (int k = K - 1; k >= 2; --k) ddp = ddp * s + double(k) * double(k - 1) * c[k];
  Scalar g = power_term(a, m, 0), dg = power_term(a, m, 1), ddg = power_term(a, m, 2);
  if (order == 0) return g * p;
  if (order == 1) return dg * p + g * dp;
  return ddg * p + 2.0 * dg * dp + g * ddp;
}

}  // namespace detail

template <int Dim>
template <class Scalar>
Scalar Kernel<Dim>::shape(const Scalar& s_in, int order) const {
  using detail::power_term;
  using detail::re;
  // Radial functions are even: evaluate at |s| and flip odd derivatives (r >= 0 in all callers).
  const double sr = re(s_in);
  const Scalar s = sr < 0 ? Scalar(-s_in) : s_in;
  const double sign = (sr < 0 && order == 1) ? -1.0 : 1.0;
  const double x = std::abs(sr);
  if (x >= m_native_support) return Scalar(0.0);
  Scalar f = 0.0;
  switch (m_type) {
    case KernelType::CubicSpline: {  // Powell (A.1): 1 - 3/2 s^2 + 3/4 s^3 ; 1/4 (2-s)^3
      if (x < 1.0) {
        if (order == 0) f = 1.0 - 1.5 * s * s + 0.75 * s * s * s;
        if (order == 1) f = -3.0 * s + 2.25 * s * s;
        if (order == 2) f = -3.0 + 4.5 * s;
      } else {
        f = 0.25 * power_term(Scalar(2.0 - s), 3, order);
      }
      break;
    }
    case KernelType::QuarticSpline: {  // Powell (A.2), support 5/2
      f = power_term(Scalar(2.5 - s), 4, order);
      if (x < 1.5) f -= 5.0 * power_term(Scalar(1.5 - s), 4, order);
      if (x < 0.5) f += 10.0 * power_term(Scalar(0.5 - s), 4, order);
      break;
    }
    case KernelType::QuinticSpline: {  // Powell (A.3), support 3
      f = power_term(Scalar(3.0 - s), 5, order);
      if (x < 2.0) f -= 6.0 * power_term(Scalar(2.0 - s), 5, order);
      if (x < 1.0) f += 15.0 * power_term(Scalar(1.0 - s), 5, order);
      break;
    }
    case KernelType::WendlandC2: {
      if (Dim == 1) {
        static constexpr double c[] = {1.0, 3.0};
        f = detail::wendland_like(s, 3, c, order);
      } else {
        static constexpr double c[] = {1.0, 4.0};
        f = detail::wendland_like(s, 4, c, order);
      }
      break;
    }
    case KernelType::WendlandC4: {
      if (Dim == 1) {
        static constexpr double c[] = {1.0, 5.0, 8.0};
        f = detail::wendland_like(s, 5, c, order);
      } else {
        static constexpr double c[] = {1.0, 6.0, 35.0 / 3.0};
        f = detail::wendland_like(s, 6, c, order);
      }
      break;
    }
    case KernelType::WendlandC6: {
      if (Dim == 1) {
        static constexpr double c[] = {1.0, 7.0, 19.0, 21.0};
        f = detail::wendland_like(s, 7, c, order);
      } else {
        static constexpr double c[] = {1.0, 8.0, 25.0, 32.0};
        f = detail::wendland_like(s, 8, c, order);
      }
      break;
    }
    case KernelType::Lucy: {
      static constexpr double c[] = {1.0, 3.0};
      f = detail::wendland_like(s, 3, c, order);
      break;
    }
    case KernelType::Gaussian: {  // exp(-s^2) truncated at s = 3
      using std::exp;
      Scalar e = exp(-s * s);
      if (order == 0) f = e;
      if (order == 1) f = -2.0 * s * e;
      if (order == 2) f = (4.0 * s * s - 2.0) * e;
      break;
    }
    case KernelType::Hat: {  // Powell (3.60): 1 - s on s < 1
      if (order == 0) f = 1.0 - s;
      if (order == 1) f = Scalar(-1.0);
      if (order == 2) f = Scalar(0.0);
      break;
    }
    case KernelType::ModifiedMollifier: {  // Ismail (2.19): exp(-1/(1-s^2)) (1-s^2)^8
      using detail::ipow;
      using std::exp;
      Scalar t = 1.0 - s * s;  // t > 0 inside the support
      Scalar e = exp(-1.0 / t);
      // f = e t^8; df/ds = -2 s e t^6 (1 + 8 t) (derived: d/ds e = -2s e / t^2, d/ds t^8 = -16 s t^7)
      if (order == 0) f = e * ipow(t, 8);
      if (order == 1) f = -2.0 * s * e * ipow(t, 6) * (1.0 + 8.0 * t);
      if (order == 2) {
        // d/ds [-2 s e t^6 (1+8t)] with de/ds = -2 s e / t^2, dt/ds = -2 s
        Scalar g = e * ipow(t, 6) * (1.0 + 8.0 * t);
        Scalar dg = e * (-2.0 * s / (t * t)) * ipow(t, 6) * (1.0 + 8.0 * t) +
                    e * (6.0 * ipow(t, 5) * (1.0 + 8.0 * t) + ipow(t, 6) * 8.0) * (-2.0 * s);
        f = -2.0 * g - 2.0 * s * dg;
      }
      break;
    }
  }
  return sign * f;
}

}  // namespace sphstab
