#pragma once
/// \file dominant_wavevector.hpp
/// Dominant wavevector (kx dx / pi, ky dx / pi) of a vector-valued mode on a 2D lattice, FFT-free, by a peak search
/// of the structure factor over the reciprocal cell:
///
///   S(k) = sum_{a = x, y} | sum_i u_i^a exp(-i k . x_i) |^2,
///
/// i.e. the power of the mode in the plane wave exp(i k . x) (per component). S is periodic in the reciprocal
/// lattice and S(k) = S(-k) for real modes, so k is searched as k = u1 b1 + u2 b2 with (u1, u2) in [0, 1)^2 and the
/// maximiser is folded into the first Brillouin zone and into kx, ky >= 0 (BravaisLattice2D::fold; every lattice here
/// is mirror symmetric). A standing wave sin(k . x) or sin(kx x) sin(ky y) on a box with fixed layers has equal peaks
/// at
/// +-k, all folding to the same (|kx|, |ky|).
///
/// Method: (1) coarse grid of G x G points, G = min(1024, 4 x the lattice extent in cells) (peak width ~ 1 / extent),
/// evaluated separably when the positions are lattice sites x_i = x_ref + p_i a1 + q_i a2 (integer p, q; O(G N + G^2
/// n_rows) work), else directly on a 64 x 64 grid; (2) nine levels of local 9 x 9 patch refinement (step / 4 each) by
/// direct O(N) sums around the best coarse point. peak_fraction = S(k*) / (N sum_i |u_i|^2) is 1 for a pure plane
/// wave and 1/4 per peak for a pure sin(kx x) sin(ky y): a measure of how "single-k" the mode is.
#include <Eigen/Core>
#include <limits>

#include "sphstab/spectral/fourier_symbol_2d.hpp"

namespace sphstab {

struct WavevectorEstimate {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double kx_over_pi = nan;     ///< |kx| dx / pi of the peak (first Brillouin zone)
  double ky_over_pi = nan;     ///< |ky| dx / pi
  double peak_fraction = nan;  ///< S(k*) / (N sum |u|^2), in (0, 1]
};

/// @param[in] mode     2N values, interleaved (u_0^x, u_0^y, u_1^x, ...), real or complex
/// @param[in] x        N x 2 positions
/// @param[in] lattice  the Bravais lattice (reciprocal cell, folding, spacing)
/// Throws std::invalid_argument on size mismatch or an empty mode. A zero mode gives NaNs.
WavevectorEstimate dominant_wavevector(const Eigen::VectorXcd& mode, const Eigen::MatrixX2d& x,
                                       const BravaisLattice2D& lattice);
WavevectorEstimate dominant_wavevector(const Eigen::VectorXd& mode, const Eigen::MatrixX2d& x,
                                       const BravaisLattice2D& lattice);

}  // namespace sphstab
