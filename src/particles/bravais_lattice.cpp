#include "sphstab/particles/bravais_lattice.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

Eigen::Matrix2d BravaisLattice2D::reciprocal() const {
  Eigen::Matrix2d a;
  a.col(0) = a1;
  a.col(1) = a2;
  // b_j . a_i = 2 pi delta_ij: B^T A = 2 pi I
  return 2 * M_PI * a.inverse().transpose();
}

Eigen::Vector2d BravaisLattice2D::fold(const Eigen::Vector2d& k) const {
  const Eigen::Matrix2d b = reciprocal();
  const Eigen::Vector2d u = b.inverse() * k;
  Eigen::Vector2d best = k;
  const double f1 = std::floor(u[0]), f2 = std::floor(u[1]);
  for (int i = -2; i <= 3; ++i)
    for (int j = -2; j <= 3; ++j) {
      const Eigen::Vector2d c = k - (f1 + i) * b.col(0) - (f2 + j) * b.col(1);
      if (c.squaredNorm() < best.squaredNorm() * (1 - 1e-12)) best = c;
    }
  return best.cwiseAbs();
}

BravaisLattice2D bravais_lattice_2d(LatticeType type, double dx) {
  if (!(dx > 0) || !std::isfinite(dx))
    throw std::invalid_argument("bravais_lattice_2d: spacing dx must be finite and > 0 (got " + format_number(dx) +
                                ")");
  BravaisLattice2D l;
  l.type = type;
  l.dx = dx;
  l.a1 = {dx, 0};
  switch (type) {
    case LatticeType::Square:
      l.a2 = {0, dx};
      break;
    case LatticeType::Hexagonal:
      l.a2 = {0.5 * dx, 0.5 * std::sqrt(3.0) * dx};
      break;
    case LatticeType::FaceCentred:
      l.a2 = {0.5 * dx, dx};
      break;
    default:
      throw std::invalid_argument("bravais_lattice_2d: lattice '" + lattice_name(type) +
                                  "' is not two-dimensional (valid: square, hex, face-centred)");
  }
  return l;
}

BravaisLattice2D detect_bravais_lattice_2d(const Eigen::MatrixX2d& x, double dx) {
  double dy = std::numeric_limits<double>::infinity();
  bool shifted = false;
  for (Eigen::Index i = 1; i < x.rows(); ++i) {
    const double d = std::abs(x(i, 1) - x(0, 1));
    if (d > 1e-9 * dx) dy = std::min(dy, d);
    const double fx = (x(i, 0) - x(0, 0)) / dx;
    if (std::abs(fx - std::round(fx)) > 0.25) shifted = true;
  }
  if (!shifted) return bravais_lattice_2d(LatticeType::Square, dx);
  if (std::abs(dy - dx * std::sqrt(3.0) / 2) < 1e-6 * dx) return bravais_lattice_2d(LatticeType::Hexagonal, dx);
  return bravais_lattice_2d(LatticeType::FaceCentred, dx);
}

}  // namespace sphstab
