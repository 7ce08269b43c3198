#pragma once
/// \file bravais_lattice.hpp
/// The 2D lattices of make_lattice as Bravais lattices: primitive and reciprocal vectors, Brillouin-zone folding,
/// and recognition of the lattice from particle positions (the geometry the Fourier symbols and the dominant
/// wavevector of a mode need).
#include <Eigen/Core>

#include "sphstab/particles/lattice.hpp"

namespace sphstab {

/// Primitive vectors (units of length) of the 2D lattices of make_lattice: square a1 = (dx, 0), a2 = (0, dx);
/// hexagonal a2 = (dx/2, dx sqrt(3)/2); face-centred a2 = (dx/2, dx). Row step dy = a2.y.
struct BravaisLattice2D {
  LatticeType type = LatticeType::Square;
  Eigen::Vector2d a1, a2;
  double dx = 1;
  double cell_area() const { return std::abs(a1.x() * a2.y() - a1.y() * a2.x()); }
  /// Reciprocal vectors b1, b2 (columns) with a_i . b_j = 2 pi delta_ij.
  Eigen::Matrix2d reciprocal() const;
  /// k folded into the first Brillouin zone (shortest k + G) and then into kx, ky >= 0 (every lattice here is
  /// symmetric under x -> -x and y -> -y).
  Eigen::Vector2d fold(const Eigen::Vector2d& k) const;
};

/// Throws std::invalid_argument for a lattice type that is not 2D or dx <= 0.
BravaisLattice2D bravais_lattice_2d(LatticeType type, double dx = 1.0);

/// The lattice of a set of 2D positions at spacing dx: square (rows dx apart, unshifted), hexagonal (rows dx sqrt(3)/2
/// apart, alternate rows shifted by dx/2) or face-centred (rows dx apart, shifted).
BravaisLattice2D detect_bravais_lattice_2d(const Eigen::MatrixX2d& x, double dx);

}  // namespace sphstab
