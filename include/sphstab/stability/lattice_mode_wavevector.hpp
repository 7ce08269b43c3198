#pragma once
/// \file lattice_mode_wavevector.hpp
/// Dominant wavevector of a 2D vector field (a mode shape or a displacement snapshot) on the free particles of a
/// rectangular lattice block with fixed surroundings: the field of each component is expanded in the discrete
/// sine basis sin(m pi (i + 1)/(nx + 1)) sin(l pi (j + 1)/(ny + 1)) (zero on the first fixed layer; the 2D version of
/// dominant_wavenumber.hpp) and the largest squared coefficient over both components gives (kx, ky) dx / pi =
/// (m/(nx + 1), l/(ny + 1)) in (0, 1); 1 is the sawtooth (-1)^i.
#include <Eigen/Core>
#include <limits>

namespace sphstab {

struct LatticeModeEstimate {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double kx = nan;        ///< kx dx / pi
  double ky = nan;        ///< ky dy / pi
  int mx = 0, my = 0;     ///< basis indices (1-based)
  int component = -1;     ///< 0 (x) or 1 (y): the component carrying the dominant coefficient
  double fraction = nan;  ///< share of the squared norm in that basis function
  int nx = 0, ny = 0;     ///< grid size found
};

/// @param[in] field    interleaved values (2 per particle: x then y component), size 2 n
/// @param[in] x        n x 2 positions of the same particles (a full nx x ny grid, any order)
/// @param[in] spacing  lattice spacing (> 0); grid indices are round((x - min x) / spacing)
/// Throws std::invalid_argument for size mismatches, spacing <= 0, or positions that do not fill an nx x ny grid
/// exactly once.
LatticeModeEstimate dominant_wavevector_2d(const Eigen::VectorXd& field, const Eigen::MatrixX2d& x, double spacing);

}  // namespace sphstab
