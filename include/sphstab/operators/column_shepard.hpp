#pragma once
/// \file column_shepard.hpp
/// "Column" Shepard gradient, Powell (3.62), exactly as printed:
///   G~_ij = (G_ij sum_l W_lj - W_ij sum_l G_lj) / (sum_l W_jl)^2
/// i.e. the Shepard gradient (3.61) with the row sums over i's neighbourhood replaced by COLUMN sums of column j;
/// note that the denominator is printed as the ROW sum of W at j (on equal-volume sets W is symmetric and the two
/// coincide). Whatever the denominator, summing over i gives
///   sum_i G~_ij = (c^G_j c^W_j - c^W_j c^G_j) / (r^W_j)^2 = 0        (c = column sums, r = row sums),
/// so the COLUMNS sum to zero (the property Powell uses for stability with alpha = 0), while the rows in general do
/// not: sum_j G~_ij != 0 wherever the neighbourhood is irregular, so a rigid translation produces a non-zero
/// gradient and linear momentum is not conserved (Powell ch. 3 §4.1.1 item 2).
#include <complex>

#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// Column Shepard gradient of one axis, Powell (3.62) as printed (see the file comment).
/// @param[in] W  N x N kernel matrix, every row sum with a non-zero real part.
/// @param[in] G  N x N gradient matrix of one axis.
/// @return N x N, union of the patterns of W and G; its columns sum to 0.
/// Throws std::invalid_argument for size mismatch, non-finite entries or a zero row sum of W.
template <class Scalar>
SparseMatrix<Scalar> column_shepard_gradient(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G);

}  // namespace sphstab
