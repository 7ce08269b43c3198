#pragma once
/// \file complex_step_product.hpp
/// The Jacobian-vector product J x = dF/dy(y0) x of any SemiDiscreteSystem (e.g. the rate-form scheme,
/// forms/rate_form.hpp) without forming J: one complex evaluation F(y0 + i h x) per product,
/// J x = Im F(y0 + i h x) / h, exact to round-off for h = 1e-30 / max_k (|x_k| / c_k) (no subtractive cancellation, as
/// complex_step_jacobian.hpp, whose assembled J it reproduces column by column; c_k = complex_step_size(1, s_k) of the
/// system's variable_scale() s, 1 for variables of magnitude 1e-12 to 1e12, so that a lattice at dx = 1e-40 gets a
/// step that is tiny against its positions). Memory O(N): the complex state and
/// rate vectors; no pattern and no colouring (the assembled J takes one complex evaluation per colour, 81-130 in
/// 2D for the rate form). Implements Spectra's matrix operation concept (Scalar, rows(), cols(), perform_op), so
/// Spectra's GenEigsSolver finds the leading eigenvalues of J (growth rates) matrix-free.
///
/// Like the assembled complex step, branches of F follow the real part of the state (e.g. the tensile/compressive
/// switch of the artificial stress, the von Mises return): J is the derivative of the branch that y0 takes.
///
/// \code{.cpp}
/// sphstab::RateFormScheme<2> scheme(disc, material, options, rho0);
/// const Eigen::VectorXd y0 = scheme.uniform_state();
/// sphstab::ComplexStepProduct jv(scheme, y0);       // keeps references to scheme and y0's copy
/// Eigen::VectorXd x = Eigen::VectorXd::Random(scheme.size()), y(scheme.size());
/// jv.apply(x, y);                                   // y = J x
/// Spectra::GenEigsSolver<sphstab::ComplexStepProduct> eigs(jv, 4, 30);   // largest-real-part eigenvalues of J
/// \endcode
#include <Eigen/Core>

#include "sphstab/system/semi_discrete_system.hpp"

namespace sphstab {

class ComplexStepProduct {
 public:
  using Scalar = double;
  static constexpr double default_step = 1e-30;

  /// J = dF/dy at y0 (copied; size system.size()). Keeps a reference to `system`. Throws std::invalid_argument for
  /// a state of the wrong size or a non-finite state, a step that is not finite and > 0, or a variable_scale() that
  /// is not finite and > 0.
  ComplexStepProduct(const SemiDiscreteSystem& system, const Eigen::VectorXd& y0, double step = default_step);

  Eigen::Index rows() const { return m_y0.size(); }
  Eigen::Index cols() const { return m_y0.size(); }
  /// y = J x (x and y of rows() entries; y may not alias x). Throws std::invalid_argument on sizes, std::runtime_error
  /// when F is not finite at y0 + i h x.
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const;
  /// Spectra's concept: y_out = J x_in (rows() doubles each).
  void perform_op(const double* x_in, double* y_out) const {
    apply(Eigen::Map<const Eigen::VectorXd>(x_in, rows()), Eigen::Map<Eigen::VectorXd>(y_out, rows()));
  }
  long products() const { return m_products; }  ///< complex evaluations so far

 private:
  const SemiDiscreteSystem& m_system;
  Eigen::VectorXd m_y0;
  double m_step;
  Eigen::VectorXd m_inverse_band;  // 1 / complex_step_size(1, variable_scale()_k)
  mutable Eigen::VectorXcd m_y, m_f;
  mutable long m_products = 0;
};

}  // namespace sphstab
