#pragma once
/// \file symmetric_pencil.hpp
/// A symmetric matrix pencil A - sigma B stored on one merged sparsity pattern (lower triangle, column-major), so
/// that evaluating it for many sigma only rewrites the value array: the pattern and CHOLMOD's symbolic analysis are
/// reused. Used by the Cholesky bisection on the tension (A(T) = K - n T L, Powell (3.40)) and by the shift-invert
/// operator.
#include "sphstab/linalg/cholmod_factor.hpp"

namespace sphstab {

/// \code{.cpp}
/// sphstab::SymmetricPencil pencil(K, L);          // any storage order, symmetric, same size
/// const sphstab::ColSparseMatrix& a = pencil.evaluate(0.25);   // lower triangle of K - 0.25 L
/// \endcode
class SymmetricPencil {
 public:
  /// @param[in] a, b  symmetric n x n matrices (only the lower triangles are read; row-major input converts).
  ///                  b may be empty (0 x 0), meaning the identity. Throws std::invalid_argument on size mismatch.
  SymmetricPencil(const ColSparseMatrix& a, const ColSparseMatrix& b);

  Eigen::Index rows() const { return m_matrix.rows(); }
  /// Lower triangle of A - sigma B on the merged pattern (a reference to an internal matrix, overwritten by the
  /// next call).
  const ColSparseMatrix& evaluate(double sigma);
  /// The merged pattern with zero values (for CholmodFactor::analyze_pattern).
  const ColSparseMatrix& pattern() const { return m_matrix; }
  const Eigen::VectorXd& a_values() const { return m_a; }
  const Eigen::VectorXd& b_values() const { return m_b; }

 private:
  ColSparseMatrix m_matrix;  // merged pattern, values = last evaluation
  Eigen::VectorXd m_a, m_b;  // values of A and B on the merged pattern
};

}  // namespace sphstab
