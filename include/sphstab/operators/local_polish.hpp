#pragma once
/// \file local_polish.hpp
/// Local row/column mean polish of a gradient matrix: the corrected kernel C_ij of Powell ch. 4, (4.9), computed
/// as in algorithm 4.1 (the kernel of the corrected momentum equation (4.10) and of the S-SPH correction g_i
/// (4.14), algorithm 4.2). Per axis, for j in N(i) (the pattern of G, self included):
///   C_ij = G_ij - r_i - c_j + m_i,
///   r_i = (1/n_i) sum_{k in N(i)} G_ik        (row mean,              "row_mean[i]")
///   c_j = (1/n_j) sum_{k in N(j)} G_kj        (column mean of col j,  "column_mean[j]")
///   m_i = (1/n_i) sum_{j in N(i)} c_j         (mean of the column means over i's neighbours, "mean_mean[i]").
/// Then sum_{j in N(i)} C_ij = (1 - |N(i)|/n_i) (sum_j G_ij - sum_{j in N(i)} c_j), which vanishes identically
/// when n_i = |N(i)| (actual counts), Powell's property 2.
///
/// \note (4.9) as printed ends in (1/n_i) sum_{j in N(i)} (1/n_j) sum_{k in N(j)} grad W_jk V_k, i.e. the mean of
///       the ROW means r_j. With it sum_j C_ij = sum_{j in N(i)} (r_j - c_j) (actual counts), which is not zero in
///       general (for an equal-volume set c_j = -r_j and it is 2 sum_j r_j, non-zero near a boundary or on a
///       perturbed lattice; checked numerically in tests/operators/local_polish_test.cpp). The printed proof only
///       closes when that term uses column means, which is what algorithm 4.1 computes (mean_mean[i] = sum_j
///       column_mean[j] / n_i); this file implements algorithm 4.1.
/// \note On a regular lattice G is antisymmetric and every complete row sums to zero, so r_i = c_j = m_i = 0 and
///       C_ij = G_ij wherever i and all its neighbours have complete neighbourhoods (Powell property 1).
///
/// Neighbour counts n_i (neighbour_counts): NeighbourCounting::Actual, n_i = |N(i)| including i itself (the
/// diagonal is part of every operator pattern, so "self included" makes n_i the number of stored entries of the
/// row); NeighbourCounting::BoundaryLevel, Powell Fig. 4.3, see neighbour_counts().
///
/// First-step Shepard option (Powell (4.18)): the means r, c, m are taken of the first-step Shepard gradient
/// reference_shepard_gradient(W, G, reference) (shepard.hpp) while the first term stays G_ij, as in algorithm 4.2
/// (f_ij uses grad W_ij V_j, the means use (4.18)):
///   C = local_polish(G, local_means(reference_shepard_gradient(W, G, ref), counts)).
/// Then, in the reference configuration and with actual counts, sum_j C_ij = sum_j G_ij (the raw row sum, not 0):
/// the option trades property 2 for small corrections near the boundary.
///
/// \code{.cpp}
/// auto ops = sphstab::assemble_operators(set, nl, w, h);
/// Eigen::VectorXd n = sphstab::neighbour_counts(set, nl, sphstab::NeighbourCounting::Actual);
/// auto C = sphstab::local_polish(ops.G[0], n);  // rows sum to 0
/// \endcode
#include <Eigen/Core>
#include <complex>
#include <string>

#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

enum class NeighbourCounting {
  Actual,        ///< n_i = |N(i)|, self included
  BoundaryLevel  ///< Powell Fig. 4.3 (see neighbour_counts)
};

/// Parses "actual" | "boundary-level"; throws std::invalid_argument naming the valid choices otherwise.
NeighbourCounting parse_neighbour_counting(const std::string& name);

/// Neighbour counts n_i (N entries, as doubles) for the local polish.
///
/// BoundaryLevel (Powell Fig. 4.3, "to give boundary particles the correct number of neighbours"): for a particle
/// whose neighbourhood is incomplete, n_i = 1 (self) + sum over neighbours j != i of 2 if depth_j > depth_i
/// (interior side), 1 if depth_j == depth_i (same boundary level), 0 if depth_j < depth_i (exterior side). A
/// neighbourhood counts as incomplete when depth_i < max_{j in N(i)} depth_j - depth_i, i.e. the neighbourhood
/// reaches fewer levels towards the outside than towards the inside (the particle is closer to the surface than
/// the support reaches); other particles keep n_i = |N(i)|. Depth is ParticleSet::depth (lattices: the lattice
/// distance to the outside of the body, fixed layers included, so with complete fixed layers only the outer fixed
/// particles are affected). The rule mirrors a full neighbourhood exactly across a flat surface of a line or
/// square lattice, not at corners (e.g. a square-lattice corner with h = 1.3 dx gets 11 instead of 21).
/// Throws std::invalid_argument if the list and set differ in size or depth has the wrong size.
template <int Dim>
Eigen::VectorXd neighbour_counts(const ParticleSet<Dim>& particles, const NeighbourList& neighbours,
                                 NeighbourCounting counting);

/// The means of algorithm 4.1 for one axis; each has N entries.
template <class Scalar>
struct LocalMeans {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> row;              ///< r_i
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> column;           ///< c_j
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> mean_of_columns;  ///< m_i
};

/// r, c, m of algorithm 4.1 taken of G (N x N, one axis; N(i) = stored pattern of row i), counts n (N entries,
/// finite, > 0). Throws std::invalid_argument on size mismatch, non-finite entries or non-positive counts.
template <class Scalar>
LocalMeans<Scalar> local_means(const SparseMatrix<Scalar>& G, const Eigen::VectorXd& counts);

/// C_ij = G_ij - r_i - c_j + m_i on the pattern of G (means from local_means, possibly of another matrix).
template <class Scalar>
SparseMatrix<Scalar> local_polish(const SparseMatrix<Scalar>& G, const LocalMeans<Scalar>& means);

/// C = local_polish(G, local_means(G, counts)): the local polish (4.9)/algorithm 4.1 of one axis.
template <class Scalar>
SparseMatrix<Scalar> local_polish(const SparseMatrix<Scalar>& G, const Eigen::VectorXd& counts);

}  // namespace sphstab
