#pragma once
/// \file dense_symmetric_eigen.hpp
/// Dense symmetric (dsyev) and generalised symmetric-definite (dsygv, A x = lambda B x with B positive definite)
/// eigenproblems through LAPACK's Fortran symbols. For small systems and as the independent cross-check of the
/// sparse routes.
///
/// \note Only the LOWER triangles of A and B are read (uplo = 'L'). Eigenvalues come in ascending order.
///       Generalised eigenvectors are B-normalised: x^T B x = 1.
#include <Eigen/Dense>

#include "sphstab/core/status.hpp"

namespace sphstab {

struct DenseSymmetricEigen {
  Eigen::VectorXd values;   ///< ascending, n entries (empty on failure)
  Eigen::MatrixXd vectors;  ///< n x n, column k belongs to values[k] (empty unless requested)
  Status status = Status::NotComputed;
  /// LAPACK's INFO: 0 success; > 0 no convergence (dsyev) or, for dsygv with info > n, the leading minor of order
  /// info - n of B is not positive definite.
  int lapack_info = 0;
};

/// Eigenvalues (and optionally eigenvectors) of symmetric a (n x n, n >= 1). Throws std::invalid_argument if a is
/// not square or empty.
DenseSymmetricEigen symmetric_eigen(const Eigen::MatrixXd& a, bool vectors = false);

/// A x = lambda B x for symmetric a and symmetric positive definite b (dsygv, itype 1). status == NumericalIssue
/// when b is not positive definite (lapack_info > n). Throws std::invalid_argument on size mismatch.
DenseSymmetricEigen generalized_symmetric_eigen(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                                bool vectors = false);

}  // namespace sphstab
