#pragma once
/// \file instantiation.hpp
/// The one list of the scalars and dimensions for which sphstab's templates are explicitly instantiated, as X-macros:
/// a source defines its own SPHSTAB_INSTANTIATE(...) for one case and applies it with these.
///   - double: time stepping and the analytic routes;
///   - std::complex<double>: complex-step Jacobians;
///   - Dual<double>, Dual<std::complex<double>>: derivatives of corrected kernels inside an energy (numerics/dual.hpp).
#include <complex>

#include "sphstab/numerics/dual.hpp"

/// M(S) for every operator scalar.
#define SPHSTAB_FOR_EACH_SCALAR(M) \
  M(double)                        \
  M(std::complex<double>)          \
  M(Dual<double>)                  \
  M(Dual<std::complex<double>>)

/// M(D) for the dimensions 1, 2, 3.
#define SPHSTAB_FOR_EACH_DIM(M) M(1) M(2) M(3)

/// M(D, S) for every dimension and operator scalar.
#define SPHSTAB_FOR_EACH_DIM_AND_SCALAR(M) \
  M(1, double)                             \
  M(2, double)                             \
  M(3, double)                             \
  M(1, std::complex<double>)               \
  M(2, std::complex<double>)               \
  M(3, std::complex<double>)               \
  M(1, Dual<double>)                       \
  M(2, Dual<double>)                       \
  M(3, Dual<double>)                       \
  M(1, Dual<std::complex<double>>)         \
  M(2, Dual<std::complex<double>>)         \
  M(3, Dual<std::complex<double>>)
