#pragma once
/// \file dominant_wavenumber.hpp
/// Dominant wavenumber k dx / pi in [0, 1] of a mode shape on a 1D lattice, FFT-free, by two methods:
///
/// 1. Projection: with the N values ordered by position, fixed ends (non-periodic) use the discrete sine basis
///    phi_m(i) = sin(m pi (i + 1) / (N + 1)), m = 1..N (orthogonal on N points, zero at the first fixed particle on
///    each side), k dx / pi = m* / (N + 1); periodic lattices use the Fourier basis exp(2 pi i m i / N),
///    m = 0..N/2, k dx / pi = 2 m* / N. m* maximises the squared coefficient (direct O(N^2) sums; skipped above
///    `projection_limit` values).
/// 2. Sign changes: z sign changes of the ordered values (exact zeros skipped; cyclic when periodic) give
///    k dx / pi ~ (z + 1) / (N + 1) (fixed ends: sin(m pi (i+1)/(N+1)) has m - 1 sign changes) or z / N (periodic).
///    O(N), exact for pure modes, only indicative for mixtures.
/// The sawtooth (-1)^i has k dx / pi = N / (N + 1) -> 1 (fixed ends) or 1 (periodic, N even).
#include <Eigen/Core>
#include <limits>

namespace sphstab {

struct WavenumberEstimate {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double k_projection = nan;         ///< k dx / pi from the projection (NaN when skipped or not computed)
  double projection_fraction = nan;  ///< share of the squared norm in the dominant basis function (NaN if skipped)
  double k_sign_changes = nan;       ///< k dx / pi from the sign-change count (NaN if not computed)
  int sign_changes = 0;              ///< z
};

/// @param[in] mode      N values (N >= 1), one per free particle
/// @param[in] x         N positions (any order; values are ordered by x)
/// @param[in] periodic  periodic lattice (Fourier basis, cyclic sign count) or fixed ends (sine basis)
/// @param[in] projection_limit  largest N for the O(N^2) projection
/// Throws std::invalid_argument on size mismatch or empty input.
WavenumberEstimate dominant_wavenumber(const Eigen::VectorXd& mode, const Eigen::VectorXd& x, bool periodic,
                                       int projection_limit = 6000);

}  // namespace sphstab
