#pragma once
/// \file cholmod_cholesky_op.hpp
/// Spectra "B operator" for the Cholesky mode of the generalised symmetric eigensolver
/// (Spectra::SymGEigsSolver<OpType, CholmodCholeskyOp, GEigsMode::Cholesky>): B = F F^T with F = P^T L from
/// CHOLMOD's P B P^T = L L^T. lower_triangular_solve applies F^{-1} = L^{-1} P, upper_triangular_solve applies
/// F^{-T} = P^T L^{-T} (Spectra only needs B = F F^T, not a triangular F). Like Spectra::SparseCholesky, but
/// CHOLMOD-backed, with the definiteness failure reported through info().
#include "sphstab/linalg/cholmod_factor.hpp"

namespace sphstab {

/// \code{.cpp}
/// #include <Spectra/SymGEigsSolver.h>
/// #include <Spectra/MatOp/SparseSymMatProd.h>
/// sphstab::CholmodCholeskyOp bop(k);                 // k symmetric positive definite
/// if (bop.info() != sphstab::Status::Successful) { /* k not positive definite */ }
/// Spectra::SparseSymMatProd<double> op(l_lower);     // L x = lambda K x
/// Spectra::SymGEigsSolver<decltype(op), sphstab::CholmodCholeskyOp, Spectra::GEigsMode::Cholesky>
///     eigs(op, bop, 1, 20);
/// eigs.init();
/// eigs.compute(Spectra::SortRule::LargestAlge);
/// \endcode
class CholmodCholeskyOp {
 public:
  using Scalar = double;

  /// Factorises symmetric b (lower triangle read). Check info(): NumericalIssue if b is not positive definite.
  explicit CholmodCholeskyOp(const ColSparseMatrix& b, CholmodVariant variant = CholmodVariant::Simplicial);

  Eigen::Index rows() const { return m_factor.rows(); }
  Eigen::Index cols() const { return m_factor.rows(); }
  Status info() const { return m_factor.info(); }
  const CholmodFactor& factor() const { return m_factor; }

  /// y = F^{-1} x = L^{-1} P x.
  void lower_triangular_solve(const double* x_in, double* y_out) const;
  /// y = F^{-T} x = P^T L^{-T} x.
  void upper_triangular_solve(const double* x_in, double* y_out) const;

 private:
  CholmodFactor m_factor;
  mutable Eigen::VectorXd m_tmp;
};

}  // namespace sphstab
