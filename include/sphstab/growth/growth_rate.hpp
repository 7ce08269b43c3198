#pragma once
/// \file growth_rate.hpp
/// Linear growth rates of u'' = -A u (A = -df/du at an equilibrium, any real square matrix, symmetric or not).
/// With u = v e^{lambda t}: lambda^2 = -mu for each eigenvalue mu of A, so the growth rate of the mode is
/// Re sqrt(-mu) (principal root, >= 0) and the system's rate is gamma = max_mu Re sqrt(-mu) (docs/conventions.md §6;
/// Powell (3.7), Theorem 3.1: unstable unless every mu is real and positive). Eigenvalues by dense LAPACK dgeev.
///
/// \note A tiny |mu| or a tiny imaginary part from rounding gives a spurious Re sqrt(-mu) of order
///       sqrt(eps ||A||); modes are listed as unstable only above `tolerance` (default 1e-6 sqrt(||A||_F)),
///       while growth_rate always reports the computed maximum.
#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "sphstab/core/status.hpp"
#include "sphstab/spectral/dominant_wavenumber.hpp"

namespace sphstab {

struct UnstableMode {
  std::complex<double> mu;        ///< eigenvalue of A
  double growth = 0;              ///< Re sqrt(-mu) > tolerance
  Eigen::VectorXd shape;          ///< real mode shape (eigenvector rotated to be as real as possible), unit 2-norm
  WavenumberEstimate wavenumber;  ///< dominant k dx / pi of shape
};

struct GrowthAnalysis {
  double growth_rate = 0;              ///< gamma = max Re sqrt(-mu) >= 0
  Eigen::VectorXcd eigenvalues;        ///< all mu
  std::vector<UnstableMode> unstable;  ///< one per real mu / conjugate pair with growth > tolerance, fastest first
  double tolerance = 0;                ///< threshold used for `unstable`
  Status status = Status::NotComputed;
};

/// @param[in] a          N x N real matrix (N >= 1)
/// @param[in] x          N positions of the degrees of freedom (for the wavenumber of unstable modes)
/// @param[in] periodic   lattice periodicity (wavenumber method, see dominant_wavenumber.hpp)
/// @param[in] tolerance  growth threshold for listing a mode; < 0 selects 1e-6 sqrt(||A||_F)
/// Throws std::invalid_argument for size mismatches, an empty or non-finite matrix.
GrowthAnalysis growth_rate(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, bool periodic = false,
                           double tolerance = -1);

/// Re sqrt(-mu), the growth rate of one eigenvalue (principal square root, always >= 0).
inline double mode_growth(std::complex<double> mu) { return std::sqrt(-mu).real(); }

}  // namespace sphstab
