#pragma once
/// \file real_part.hpp
/// The real part of a scalar's value, for the branches of code templated on the scalar (double, complex step,
/// dual numbers): every scalar takes the branch its real value takes, so a derivative carried along is that of
/// the branch actually evaluated.
#include <complex>

namespace sphstab {

template <class S>
struct Dual;  // numerics/dual.hpp

namespace detail {
inline double re(double x) { return x; }
inline double re(const std::complex<double>& x) { return x.real(); }
/// Real part of a dual number's value (branches follow the value).
template <class S>
double re(const Dual<S>& x) {
  return re(x.v);
}
}  // namespace detail

}  // namespace sphstab
