#pragma once
/// \file dual.hpp
/// Forward-mode dual numbers x = v + d eps (eps^2 = 0) over a base scalar S (double or std::complex<double>).
///
/// sphstab uses them where one exact derivative must be nested inside another: the conservative SPH forms with a
/// corrected kernel in the strain (Powell 3.55) need the force a = -M^{-1} dU/du, a first derivative of the energy
/// that involves derivatives of the corrected kernel (Shepard, polishes, ...) with respect to the positions. With
/// S = double a Dual pass gives that force exactly; with S = std::complex<double> the complex-step Jacobian of the
/// force (complex_step_jacobian.hpp) differentiates through it, exact to round-off (no truncation error anywhere).
///
/// \note Branches in sphstab look at detail::re(x), the real part of the value, so a Dual takes the same branch as
///       its value (like the complex step). Comparisons == and != compare value and derivative.
/// \note Only the operations the SPH operators, kernels and corrections use are provided: + - * /, unary -, sqrt,
///       exp, and the Eigen NumTraits needed for Eigen dense/sparse storage and arithmetic.
///
/// \code{.cpp}
/// sphstab::Dual<double> x(2.0, 1.0);  // x = 2 with dx = 1
/// auto y = x * x + 3.0 * x;           // y.v = 10, y.d = 2 x + 3 = 7
/// \endcode
#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <type_traits>

#include "sphstab/numerics/real_part.hpp"

namespace sphstab {

template <class S>
struct Dual {
  S v{};  ///< value
  S d{};  ///< derivative (coefficient of eps)

  Dual() = default;
  Dual(const S& value, const S& derivative) : v(value), d(derivative) {}
  /// A constant (zero derivative) from anything the base scalar is constructible from (int, double, S).
  template <class T, std::enable_if_t<std::is_constructible_v<S, T> && !std::is_same_v<std::decay_t<T>, Dual>, int> = 0>
  Dual(const T& value) : v(S(value)), d(S(0)) {}  // NOLINT(google-explicit-constructor): scalars convert implicitly

  Dual& operator+=(const Dual& o) {
    v += o.v;
    d += o.d;
    return *this;
  }
  Dual& operator-=(const Dual& o) {
    v -= o.v;
    d -= o.d;
    return *this;
  }
  Dual& operator*=(const Dual& o) {
    d = d * o.v + v * o.d;
    v *= o.v;
    return *this;
  }
  Dual& operator/=(const Dual& o) {
    const S inv = S(1) / o.v;
    v *= inv;
    d = (d - v * o.d) * inv;
    return *this;
  }
};

template <class S>
inline Dual<S> operator-(const Dual<S>& a) {
  return {-a.v, -a.d};
}
template <class S>
inline Dual<S> operator+(const Dual<S>& a) {
  return a;
}
template <class S>
inline Dual<S> operator+(Dual<S> a, const Dual<S>& b) {
  return a += b;
}
template <class S>
inline Dual<S> operator-(Dual<S> a, const Dual<S>& b) {
  return a -= b;
}
template <class S>
inline Dual<S> operator*(Dual<S> a, const Dual<S>& b) {
  return a *= b;
}
template <class S>
inline Dual<S> operator/(Dual<S> a, const Dual<S>& b) {
  return a /= b;
}

namespace detail {
/// Plain scalars that mix with Dual<S>: arithmetic types and S itself.
template <class S, class T>
inline constexpr bool dual_mixable_v = std::is_arithmetic_v<T> || std::is_same_v<T, S>;
}  // namespace detail

// Mixed operations with a constant c (no derivative).
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S> operator+(const Dual<S>& a, const T& c) {
  return {a.v + S(c), a.d};
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S> operator+(const T& c, const Dual<S>& a) {
  return {S(c) + a.v, a.d};
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S> operator-(const Dual<S>& a, const T& c) {
  return {a.v - S(c), a.d};
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S> operator-(const T& c, const Dual<S>& a) {
  return {S(c) - a.v, -a.d};
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S> operator*(const Dual<S>& a, const T& c) {
  return {a.v * S(c), a.d * S(c)};
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S> operator*(const T& c, const Dual<S>& a) {
  return {S(c) * a.v, S(c) * a.d};
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S> operator/(const Dual<S>& a, const T& c) {
  const S inv = S(1) / S(c);
  return {a.v * inv, a.d * inv};
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S> operator/(const T& c, const Dual<S>& a) {
  const S inv = S(1) / a.v;
  const S q = S(c) * inv;
  return {q, -q * inv * a.d};
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S>& operator+=(Dual<S>& a, const T& c) {
  a.v += S(c);
  return a;
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S>& operator-=(Dual<S>& a, const T& c) {
  a.v -= S(c);
  return a;
}
template <class S, class T, std::enable_if_t<detail::dual_mixable_v<S, T>, int> = 0>
inline Dual<S>& operator*=(Dual<S>& a, const T& c) {
  a.v *= S(c);
  a.d *= S(c);
  return a;
}

template <class S>
inline bool operator==(const Dual<S>& a, const Dual<S>& b) {
  return a.v == b.v && a.d == b.d;
}
template <class S>
inline bool operator!=(const Dual<S>& a, const Dual<S>& b) {
  return !(a == b);
}

/// sqrt(v + d eps) = sqrt(v) + d / (2 sqrt(v)) eps (principal root of the value).
template <class S>
inline Dual<S> sqrt(const Dual<S>& a) {
  using std::sqrt;
  const S r = sqrt(a.v);
  return {r, a.d / (S(2) * r)};
}
template <class S>
inline Dual<S> exp(const Dual<S>& a) {
  using std::exp;
  const S e = exp(a.v);
  return {e, e * a.d};
}

}  // namespace sphstab

namespace Eigen {
/// Eigen needs NumTraits for storage, setZero and arithmetic of matrices of duals (no norms or decompositions).
template <class S>
struct NumTraits<sphstab::Dual<S>> : NumTraits<double> {
  using Real = sphstab::Dual<S>;
  using NonInteger = sphstab::Dual<S>;
  using Nested = sphstab::Dual<S>;
  using Literal = sphstab::Dual<S>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 2 * NumTraits<S>::ReadCost,
    AddCost = 2 * NumTraits<S>::AddCost,
    MulCost = 3 * NumTraits<S>::MulCost + NumTraits<S>::AddCost
  };
};
}  // namespace Eigen
