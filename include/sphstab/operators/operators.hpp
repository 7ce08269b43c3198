#pragma once
/// \file operators.hpp
/// Sparse SPH operator matrices assembled from a neighbour list (docs/conventions.md §3):
///   W_ij    = W(|x_i - x_j|, h) V_j                              (kernel / interpolation matrix)
///   G^a_ij  = dW(|x_i - x_j|, h)/dx_i^a V_j, G^a_ii = 0            (gradient w.r.t. the FIRST index)
///   H^ab_ij = d^2W(|x_i - x_j|, h)/dx_i^a dx_i^b V_j for i != j, H_ii = 0 (stored as explicit zeros)
/// With e = (x_i - x_j)/r: dW/dx_i = W'(r) e and d^2W/dx_i dx_i = W'' e e^T + (W'/r)(I - e e^T).
/// SPH gradient: <d_a f>_i = (G^a f)_i; zeroth-order ("minus") gradient: (G^a - diag(G^a 1)) f (Powell 1.15).
///
/// All matrices are row-major with the neighbour-list pattern (diagonal included), so they share one index
/// structure. Assembly is templated on the scalar so that displaced positions with complex (complex-step)
/// coordinates produce the exact derivative of every operator entry.
///
/// \code{.cpp}
/// auto set = sphstab::make_lattice<1>(sphstab::LatticeType::Line, 30, {.spacing = 1.0, .support_radius = 2.6});
/// sphstab::Kernel<1> w(sphstab::KernelType::CubicSpline);
/// auto nl = sphstab::find_neighbours(set, w.support_radius(1.3));
/// auto ops = sphstab::assemble_operators(set, nl, w, 1.3, {.kernel = true, .gradient = true});
/// Eigen::VectorXd dfdx = ops.G[0] * f;
/// \endcode
#include <Eigen/Sparse>
#include <array>
#include <complex>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

template <class Scalar = double>
using SparseMatrix = Eigen::SparseMatrix<Scalar, Eigen::RowMajor, int>;

template <int Dim, class Scalar = double>
using Positions = Eigen::Matrix<Scalar, Eigen::Dynamic, Dim>;

/// Which operators to assemble in one pass over the pairs.
struct OperatorRequest {
  bool kernel = true;
  bool gradient = true;
  bool hessian = false;
};

template <int Dim, class Scalar = double>
struct Operators {
  SparseMatrix<Scalar> W;                                    ///< N x N, empty unless requested
  std::array<SparseMatrix<Scalar>, Dim> G;                   ///< G[a], N x N
  std::array<std::array<SparseMatrix<Scalar>, Dim>, Dim> H;  ///< H[a][b] = H[b][a], N x N
};

/// Assembles the requested operators at the particles' positions, or at `positions` (N x Dim) when given
/// (e.g. x0 + u during time stepping or complex-step differentiation). The neighbour list fixes the pattern.
/// Throws std::invalid_argument for h <= 0, size mismatches, or an invalid particle set.
template <int Dim, class Scalar = double>
Operators<Dim, Scalar> assemble_operators(const ParticleSet<Dim>& particles, const NeighbourList& neighbours,
                                          const Kernel<Dim>& kernel, double h, OperatorRequest request = {},
                                          const Positions<Dim, Scalar>* positions = nullptr);

/// As assemble_operators, but reuses the storage of `ops` (no allocation, no page faults) when its matrices
/// already have the neighbour-list pattern, as in updated-Lagrangian re-assembly at new positions.
template <int Dim, class Scalar = double>
void assemble_operators_into(Operators<Dim, Scalar>& ops, const ParticleSet<Dim>& particles,
                             const NeighbourList& neighbours, const Kernel<Dim>& kernel, double h,
                             OperatorRequest request = {}, const Positions<Dim, Scalar>* positions = nullptr);

/// W alone (see assemble_operators).
template <int Dim>
SparseMatrix<> kernel_matrix(const ParticleSet<Dim>& particles, const NeighbourList& neighbours,
                             const Kernel<Dim>& kernel, double h);
/// G^a alone (see assemble_operators).
template <int Dim>
SparseMatrix<> gradient_matrix(const ParticleSet<Dim>& particles, const NeighbourList& neighbours,
                               const Kernel<Dim>& kernel, double h, int axis);

/// A sparse matrix with the neighbour-list pattern and zero values (for callers that fill values directly).
template <class Scalar = double>
SparseMatrix<Scalar> pattern_matrix(const NeighbourList& neighbours);

}  // namespace sphstab
