#pragma once
/// \file cholmod_definiteness.hpp
/// Positive-definiteness test by attempted sparse Cholesky factorisation (Powell ch. 3 footnote g: the factorisation
/// succeeds if and only if the symmetric matrix is positive definite). CHOLMOD LL^T, symbolic analysis once per
/// pattern, one numeric factorisation per test (e.g. per tension T in a bisection).
///
/// \note "Numerically positive definite": CHOLMOD stops at the first pivot <= 0 (or NaN). A matrix whose smallest
///       eigenvalue is below about eps * ||A|| in magnitude may be classified either way.
#include "sphstab/linalg/cholmod_factor.hpp"

namespace sphstab {

/// \code{.cpp}
/// sphstab::CholmodDefiniteness check;
/// check.analyze_pattern(a0);                 // symmetric, lower triangle read
/// bool pd = check.is_positive_definite(a1);  // same pattern as a0, any values
/// if (!pd) int column = check.failed_column();
/// \endcode
class CholmodDefiniteness {
 public:
  explicit CholmodDefiniteness(CholmodVariant variant = CholmodVariant::Simplicial) : m_factor(variant) {}

  /// Symbolic analysis of a symmetric n x n pattern (lower triangle read).
  void analyze_pattern(const ColSparseMatrix& a) { m_factor.analyze_pattern(a); }
  /// Numeric LL^T factorisation attempt; true iff `a` (with the analysed pattern) is positive definite.
  bool is_positive_definite(const ColSparseMatrix& a) { return m_factor.factorize(a); }
  /// Successful after a positive-definite test, NumericalIssue after a failed one, NotComputed before any.
  Status info() const { return m_factor.info(); }
  /// Column (in CHOLMOD's permuted order) at which the last factorisation stopped; rows() when it succeeded.
  int failed_column() const { return m_factor.failed_column(); }
  Eigen::Index rows() const { return m_factor.rows(); }
  /// The factor of the last successful test (e.g. for solves).
  const CholmodFactor& factor() const { return m_factor; }

 private:
  CholmodFactor m_factor;
};

/// One-shot test: analysis and factorisation of a symmetric matrix (lower triangle read).
/// Throws std::invalid_argument for a non-square or empty matrix.
bool is_positive_definite(const ColSparseMatrix& a, CholmodVariant variant = CholmodVariant::Simplicial);

}  // namespace sphstab
