#pragma once
/// \file cholmod_factor.hpp
/// A quiet sparse Cholesky factorisation through CHOLMOD (Eigen's <Eigen/CholmodSupport>), split into
/// analyze_pattern() (once per sparsity pattern) and factorize() (once per numerical value set, e.g. per tension T
/// or per shift sigma), with access to the triangular and permutation solves that Spectra's Cholesky mode needs.
///
/// \note Input matrices are symmetric and given by their LOWER triangle in column-major storage (entries above the
///       diagonal are ignored). CHOLMOD computes P A P^T = L L^T (LLT) or P A P^T = L D L^T (LDLT, no pivoting).
/// \note CHOLMOD's own printing (e.g. "CHOLMOD warning: not positive definite") is switched off; failure is reported
///       by factorize() returning false, info() == Status::NumericalIssue and failed_column() < rows().
#include <Eigen/Sparse>
#include <memory>

#include "sphstab/core/status.hpp"

namespace sphstab {

/// Column-major sparse matrix, the storage CHOLMOD works in.
using ColSparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// CHOLMOD's two LL^T algorithms. Simplicial is faster for the narrow-band 1D matrices of sphstab (measured in
/// benchmarks/critical_tension_benchmark.cpp with the reference BLAS); supernodal wins for wide fronts (2D, 3D).
enum class CholmodVariant { Simplicial, Supernodal };

/// The factorisation computed: LLT (only for positive definite input; failure is the definiteness test) or
/// simplicial LDLT without pivoting (indefinite input allowed, fails only at an exactly zero pivot; no stability
/// guarantee for indefinite matrices).
enum class CholmodFactorKind { LLT, LDLT };

/// Systems that solve() can apply: A^-1, L^-1, L^-T, P, P^T (CHOLMOD_A, CHOLMOD_L, CHOLMOD_Lt, CHOLMOD_P,
/// CHOLMOD_Pt). L and Lt are the triangular factor of an LLT factorisation; for LDLT use A.
enum class CholmodSystem { A, L, Lt, P, Pt };  // keep the order: CholmodFactor::solve indexes a table by it

/// \code{.cpp}
/// sphstab::CholmodFactor chol(sphstab::CholmodVariant::Simplicial);
/// chol.analyze_pattern(lower);            // once per pattern
/// bool pd = chol.factorize(lower);        // per value set; pd == positive definite (LLT)
/// Eigen::VectorXd x(lower.rows());
/// if (pd) chol.solve(sphstab::CholmodSystem::A, b.data(), x.data());
/// \endcode
class CholmodFactor {
 public:
  explicit CholmodFactor(CholmodVariant variant = CholmodVariant::Simplicial,
                         CholmodFactorKind kind = CholmodFactorKind::LLT);
  ~CholmodFactor();
  CholmodFactor(CholmodFactor&&) noexcept;
  CholmodFactor& operator=(CholmodFactor&&) noexcept;
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  /// Symbolic analysis (fill-reducing ordering) of the pattern of `lower` (n x n, lower triangle used).
  /// Throws std::invalid_argument if the matrix is not square or empty.
  void analyze_pattern(const ColSparseMatrix& lower);
  /// Numerical factorisation of `lower`, which must have the analysed pattern (same outer/inner index arrays).
  /// Returns true on success. For LLT, success <=> the matrix is (numerically) positive definite.
  bool factorize(const ColSparseMatrix& lower);
  /// analyze_pattern() then factorize().
  bool compute(const ColSparseMatrix& lower);

  Status info() const { return m_info; }
  /// CHOLMOD's "minor": the column at which the factorisation stopped, rows() on success.
  int failed_column() const;
  Eigen::Index rows() const { return m_n; }
  Eigen::Index cols() const { return m_n; }
  CholmodVariant variant() const { return m_variant; }
  CholmodFactorKind kind() const { return m_kind; }
  /// CHOLMOD's cheap reciprocal-condition estimate (min diag L / max diag L)^2 for LLT (cholmod_rcond);
  /// a lower bound on 1/cond is NOT guaranteed. 0 before a successful factorisation.
  double rcond_estimate() const;

  /// y = op(x) with op the inverse (or permutation) named by `sys`; x and y have rows() entries and may not alias.
  /// Requires a successful factorisation (throws std::logic_error otherwise).
  void solve(CholmodSystem sys, const double* x, double* y) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
  CholmodVariant m_variant;
  CholmodFactorKind m_kind;
  Eigen::Index m_n = 0;
  Status m_info = Status::NotComputed;
};

/// The lower triangle (diagonal included) of a symmetric sparse matrix in any storage order, column-major.
template <class Derived>
ColSparseMatrix lower_triangle(const Eigen::SparseMatrixBase<Derived>& a) {
  ColSparseMatrix m = a.derived();
  return m.template triangularView<Eigen::Lower>();
}

}  // namespace sphstab
