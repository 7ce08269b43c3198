#pragma once
/// \file dense_general_eigen.hpp
/// Eigenvalues and right eigenvectors of a dense real nonsymmetric matrix (LAPACK dgeev), e.g. a linearised
/// Jacobian A = -df/du of a non-conservative SPH form, whose eigenvalues may be complex.
#include <Eigen/Dense>

#include "sphstab/core/status.hpp"

namespace sphstab {

struct DenseGeneralEigen {
  Eigen::VectorXcd values;   ///< n eigenvalues in LAPACK's order (complex pairs adjacent, positive imaginary first)
  Eigen::MatrixXcd vectors;  ///< n x n right eigenvectors (unit 2-norm columns), empty unless requested
  Status status = Status::NotComputed;
  int lapack_info = 0;  ///< LAPACK's INFO: > 0 the QR algorithm failed to converge
};

/// Eigen-decomposition of a (n x n, n >= 1). Throws std::invalid_argument for a non-square or empty matrix, or
/// non-finite entries.
DenseGeneralEigen general_eigen(const Eigen::MatrixXd& a, bool vectors = false);

}  // namespace sphstab
