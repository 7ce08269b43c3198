#pragma once
/// \file cholmod_shift_invert.hpp
/// Spectra shift-and-invert operator over CHOLMOD: y = (A - sigma B)^{-1} x for symmetric sparse A, B (B = I when
/// omitted). Implements Spectra's operator concept exactly (Scalar, rows, cols, set_shift, perform_op), so it drops
/// into Spectra::SymEigsShiftSolver (B = I), Spectra::SymGEigsShiftSolver<CholmodShiftInvert, BOp,
/// GEigsMode::ShiftInvert> and GEigsMode::Buckling. Spectra's own SparseSymShiftSolve uses SparseLU; this uses
/// CHOLMOD's symmetric factorisation with the pattern analysed once and one numeric factorisation per shift.
///
/// \note With CholmodFactorKind::LLT (default) set_shift() factorises A - sigma B if it is positive definite, else
///       -(A - sigma B) if that is positive definite (a shift above the whole spectrum), and throws
///       std::invalid_argument if neither (shift inside the spectrum: use CholmodFactorKind::LDLT, an unpivoted
///       LDL^T that only fails at an exactly zero pivot, or choose another shift). This throw mirrors Spectra's
///       SymShiftInvert::set_shift on a singular matrix.
#include "sphstab/linalg/cholmod_factor.hpp"
#include "sphstab/linalg/symmetric_pencil.hpp"

namespace sphstab {

/// \code{.cpp}
/// #include <Spectra/SymEigsShiftSolver.h>
/// sphstab::CholmodShiftInvert op(a);   // symmetric a, B = I
/// Spectra::SymEigsShiftSolver<sphstab::CholmodShiftInvert> eigs(op, 3, 20, 0.0);   // 3 eigenvalues nearest 0
/// eigs.init();
/// eigs.compute(Spectra::SortRule::LargestMagn);
/// if (eigs.info() == Spectra::CompInfo::Successful) Eigen::VectorXd values = eigs.eigenvalues();
/// \endcode
class CholmodShiftInvert {
 public:
  using Scalar = double;

  /// @param[in] a  symmetric n x n (lower triangle read; row-major input converts)
  /// @param[in] b  symmetric n x n, or empty for the identity
  explicit CholmodShiftInvert(const ColSparseMatrix& a, const ColSparseMatrix& b = ColSparseMatrix(),
                              CholmodFactorKind kind = CholmodFactorKind::LLT,
                              CholmodVariant variant = CholmodVariant::Simplicial);

  Eigen::Index rows() const { return m_pencil.rows(); }
  Eigen::Index cols() const { return m_pencil.rows(); }

  /// Factorises A - sigma B (see the class note). Throws std::invalid_argument if it cannot.
  void set_shift(double sigma);
  /// y = (A - sigma B)^{-1} x, x and y of rows() entries.
  void perform_op(const double* x_in, double* y_out) const;

  double shift() const { return m_sigma; }
  /// +1 when A - sigma B was factorised directly, -1 when -(A - sigma B) was (LLT only).
  double sign() const { return m_sign; }
  /// Numeric factorisations performed so far.
  int factorizations() const { return m_count; }

 private:
  SymmetricPencil m_pencil;
  CholmodFactor m_factor;
  ColSparseMatrix m_work;
  double m_sigma = 0;
  double m_sign = 1;
  int m_count = 0;
  bool m_analysed = false;
};

}  // namespace sphstab
