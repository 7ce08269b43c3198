#pragma once
/// \file zigzag_modes.hpp
/// Classification of the eigenmodes of a linearised particle system into zigzag (hourglass) and smooth modes, for
/// free particles on a regular grid (a lattice block, the Turek-Hron beam): the zigzag (hourglass) fraction of a mode
/// phi is the share of sum_c |DFT(phi_c)|^2 at wavevectors with |k_a| > pi / (2 dx) along some axis a, the DFT taken
/// over the bounding box of the free particles' grid indices (n_0 x ... x n_{Dim-1}, treated as periodic; empty grid
/// points count as 0). It is 1 for the sawtooth, for every pattern alternating along an axis and for mixtures of them
/// (degenerate modes of a symmetric block, which an eigen solver returns mixed), and ~0 for smooth modes
/// (studies/tl-hourglass, studies/tl-csm3-hourglass use 0.5 as the threshold).
///
/// \code{.cpp}
/// const auto grid = sphstab::grid_indices(*disc, dx);          // integer grid index of each free particle
/// const auto modes = sphstab::zigzag_spectrum<2>(A, grid);      // eigenpairs of A, ascending Re mu, classified
/// for (const auto& m : modes) if (m.zigzag > 0.5) ...
/// \endcode
#include <Eigen/Core>
#include <array>
#include <vector>

#include "sphstab/forms/discretisation.hpp"

namespace sphstab {

/// Integer grid index of each free particle (DOF order) and the extent of the bounding box per axis.
template <int Dim>
struct GridIndices {
  std::vector<std::array<int, Dim>> index;  ///< free_count entries, each in [0, extent[a])
  std::array<int, Dim> extent{};            ///< n_a = max index + 1 along axis a
};

/// index_a = round((X_a - min_f X_a) / dx) of the free particles. Throws std::invalid_argument for dx <= 0 or a
/// free particle off the grid by more than 1e-6 dx.
template <int Dim>
GridIndices<Dim> grid_indices(const Discretisation<Dim>& d, double dx);

/// Zigzag (hourglass) fraction of phi (Dim x free_count, interleaved) in [0, 1]; 0 for phi = 0. Throws
/// std::invalid_argument for a size mismatch.
template <int Dim>
double hourglass_fraction(const Eigen::VectorXd& phi, const GridIndices<Dim>& grid);

struct ZigzagMode {
  double mu = 0;        ///< Re of the eigenvalue
  double imag = 0;      ///< |Im| of the eigenvalue
  double zigzag = 0;    ///< hourglass_fraction of the eigenvector
  Eigen::VectorXd phi;  ///< unit real eigenvector (the real part, or the imaginary part when the real part is ~0)
};

/// Classifies given eigenpairs (values n, vectors n x n column-wise), sorted by ascending Re mu.
template <int Dim>
std::vector<ZigzagMode> classify_modes(const Eigen::VectorXcd& values, const Eigen::MatrixXcd& vectors,
                                       const GridIndices<Dim>& grid);

/// Eigenpairs of the dense, possibly non-symmetric A (Eigen's EigenSolver), classified and sorted by Re mu.
template <int Dim>
std::vector<ZigzagMode> zigzag_spectrum(const Eigen::MatrixXd& A, const GridIndices<Dim>& grid);

}  // namespace sphstab
