#pragma once
/// \file matrix_free_operator.hpp
/// Spectra's matrix operation concept (Scalar, rows(), cols(), perform_op) for y = (c0 A0 + c1 A1) x applied by a
/// MatrixFreeLinearisation (matrix_free_linearisation.hpp), so that Spectra's solvers (SymEigsSolver, the OpType of
/// SymGEigsSolver, GenEigsSolver) run on the linearisation without assembling it.
///
/// \code{.cpp}
/// #include <Spectra/SymEigsSolver.h>
/// sphstab::MatrixFreeLinearisation lin(*disc, material, sphstab::MomentumForm::Conservative,
///                                      sphstab::PreStrainKind::Isotropic);
/// sphstab::MatrixFreeOperator op(lin, 1.0, 1e-3);   // A(e = 1e-3); must not outlive lin
/// Spectra::SymEigsSolver<sphstab::MatrixFreeOperator<2>> eigs(op, 4, 30);
/// eigs.init();
/// eigs.compute(Spectra::SortRule::LargestAlge);
/// \endcode
#include <Eigen/Core>

#include "sphstab/jacobian/matrix_free_linearisation.hpp"

namespace sphstab {

template <int Dim>
class MatrixFreeOperator {
 public:
  using Scalar = double;

  /// y = (c0 A0 + c1 A1) x; keeps a reference to `lin`.
  explicit MatrixFreeOperator(const MatrixFreeLinearisation<Dim>& lin, double c0 = 1.0, double c1 = 0.0)
      : m_lin(&lin), m_c0(c0), m_c1(c1) {}

  Eigen::Index rows() const { return m_lin->dofs(); }
  Eigen::Index cols() const { return m_lin->dofs(); }
  void set_coefficients(double c0, double c1) {
    m_c0 = c0;
    m_c1 = c1;
  }

  /// y_out = (c0 A0 + c1 A1) x_in; both point to rows() doubles, not overlapping.
  void perform_op(const double* x_in, double* y_out) const {
    m_lin->apply_combination(m_c0, m_c1, Eigen::Map<const Eigen::VectorXd>(x_in, rows()),
                             Eigen::Map<Eigen::VectorXd>(y_out, rows()));
  }

 private:
  const MatrixFreeLinearisation<Dim>* m_lin;
  double m_c0, m_c1;
};

}  // namespace sphstab
