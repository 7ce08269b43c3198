#pragma once
/// \file mean_polish.hpp
/// Global row/column mean polish of a square matrix, Powell ch. 3 §4.1.1 item 3, algorithm 3.1 and (3.63)-(3.64)
/// (after Tukey's median polish, Powell's ref. [76]), and the Shepard + column polish of item 4.
///
/// Row polish A1_ij = A_ij - rbar_i, then column polish A2_ij = A1_ij - cbar1_j (algorithm 3.1), i.e. (3.64)
///   A2_ij = A_ij - R_i - C_j + (1/N) sum_l R_l,    R_i = (1/N) sum_j A_ij,  C_j = (1/N) sum_l A_lj,
/// after which every row AND every column sums to zero. Applied to a gradient matrix (Powell writes W'_ij) the
/// corrected operator is stable for all T and conserves momentum in the 1D analysis, but it is DENSE: every entry
/// may be non-zero ("action at a distance"), so the results are Eigen::MatrixX and polish_fill() reports the fill.
///
/// Subset (what N is): by default N is the matrix size, as in (3.64). With a subset S of indices (e.g. the free
/// particles, `ParticleSet::indices(Role::Free)`) the polish acts on the principal block A[S, S] alone with
/// N = |S|: means are taken over S only and only entries with both indices in S change; rows/columns outside S
/// are copied unchanged. Then sum_{j in S} A2_ij = 0 for i in S and sum_{i in S} A2_ij = 0 for j in S, which is
/// what the linearised free-particle system sees (the fixed particles' displacements are prescribed), while the
/// sums over ALL columns of a free row still include the untouched free-fixed couplings.
///
/// Shepard + column polish (item 4): Ghat_ij = G~_ij - (1/N) sum_k G~_kj with G~ the Shepard gradient (3.61).
/// The thesis prints the column mean as (1/N) sum_k W'_kj (the UNcorrected kernel); its own proof that the rows
/// still sum to zero needs the mean of the Shepard gradient G~, which is what is implemented.
#include <Eigen/Core>
#include <complex>
#include <vector>

#include "sphstab/operators/operators.hpp"

namespace sphstab {

template <class Scalar>
using DenseMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// Row mean polish (first half of algorithm 3.1): A_ij - (1/N) sum_{l in S} A_il for i, j in S.
/// @param[in] A       N x N, finite.
/// @param[in] subset  distinct indices in [0, N); empty = all (see the file comment).
template <class Scalar>
DenseMatrix<Scalar> row_mean_polish(const DenseMatrix<Scalar>& A, const std::vector<int>& subset = {});

/// Column mean polish (second half of algorithm 3.1): A_ij - (1/N) sum_{l in S} A_lj for i, j in S.
template <class Scalar>
DenseMatrix<Scalar> column_mean_polish(const DenseMatrix<Scalar>& A, const std::vector<int>& subset = {});

/// Row then column mean polish, algorithm 3.1 / (3.64): rows and columns (within the subset) sum to 0.
/// @return dense N x N. Throws std::invalid_argument for a non-square/empty/non-finite A or a bad subset.
template <class Scalar>
DenseMatrix<Scalar> mean_polish(const DenseMatrix<Scalar>& A, const std::vector<int>& subset = {});
/// Sparse input (e.g. a gradient matrix); the result is dense.
template <class Scalar>
DenseMatrix<Scalar> mean_polish(const SparseMatrix<Scalar>& A, const std::vector<int>& subset = {});

/// Shepard gradient (3.61) followed by a column mean polish over all N particles (Powell ch. 3 §4.1.1 item 4):
/// rows and columns sum to 0. @param[in] W, G: N x N kernel and one-axis gradient matrices. @return dense N x N.
template <class Scalar>
DenseMatrix<Scalar> shepard_column_polish(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G);

/// Fill of a polish: how many entries the sparse operator had and how many the polished matrix has.
struct PolishFill {
  long size = 0;            ///< N (the matrix is N x N)
  long stored_before = 0;   ///< stored entries of the input (its pattern, explicit zeros included)
  long nonzero_before = 0;  ///< entries of the input that are not exactly 0
  long nonzero_after = 0;   ///< entries of the polished matrix that are not exactly 0 (at most N^2)
};

/// Counts the fill (entries compared with exact zero; counting only, nothing is differentiated).
template <class Scalar>
PolishFill polish_fill(const SparseMatrix<Scalar>& before, const DenseMatrix<Scalar>& after);

/// A dense matrix stored as a sparse one with EVERY entry kept (explicit zeros included), so that polished results
/// travel through sparse interfaces without hiding their fill.
template <class Scalar>
SparseMatrix<Scalar> dense_to_sparse_all_entries(const DenseMatrix<Scalar>& A);

}  // namespace sphstab
