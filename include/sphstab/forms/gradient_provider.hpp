#pragma once
/// \file gradient_provider.hpp
/// Pluggable "kernel-gradient provider" for the momentum equation: given the operators at the CURRENT positions,
/// it supplies the gradient matrix Ghat^a used in f_i = sum_j (s_j + alpha s_i) Ghat^a_ij. The strain is always
/// computed with the plain G (Powell 3.26, 4.12); only the divergence of the stress uses Ghat.
///
/// Provided here: PlainGradient (Ghat = G) and MinusGradient (Ghat = G - diag(G 1), zeroth-order consistent,
/// Powell 1.15). The local-polish kernel C_ij (Powell 4.9-4.11) plugs in the same way: derive from
/// GradientProviderT and implement `template <class Scalar> void correct(const GradientContext<Dim, Scalar>&,
/// std::array<SparseMatrix<Scalar>, Dim>& g) const`.
#include <array>
#include <complex>
#include <string>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// Everything a provider may read, all at the current positions x = x0 + u.
template <int Dim, class Scalar>
struct GradientContext {
  const Discretisation<Dim>& discretisation;  ///< reference set, neighbour list (the pattern), volumes
  const Positions<Dim, Scalar>& positions;    ///< current positions, N x Dim
  const Operators<Dim, Scalar>& operators;    ///< current W (if requested), G, H (if requested)
};

/// Base class of gradient providers. Implementations transform g in place; on entry g = operators.G, on exit
/// g must keep the neighbour-list pattern (values change, structure not).
///
/// \note dependence_radius(): how many neighbour-graph hops from particle i row i of Ghat may read positions
///       (plain and minus: 1; C_ij of Powell 4.9: 2). The Jacobian sparsity pattern is built from it.
template <int Dim>
class GradientProvider {
 public:
  virtual ~GradientProvider() = default;
  virtual std::string name() const = 0;
  /// Operators the provider needs besides G (e.g. W for a Shepard correction).
  virtual OperatorRequest requirements() const { return {.kernel = false, .gradient = true, .hessian = false}; }
  virtual int dependence_radius() const { return 1; }
  /// True if Ghat == G (no correction); the conservative form accepts only this.
  virtual bool is_plain() const { return false; }
  virtual void correct(const GradientContext<Dim, double>& context, std::array<SparseMatrix<double>, Dim>& g) const = 0;
  virtual void correct(const GradientContext<Dim, std::complex<double>>& context,
                       std::array<SparseMatrix<std::complex<double>>, Dim>& g) const = 0;
};

/// CRTP helper: Derived implements one template `correct_impl<Scalar>(context, g)`; both overloads forward to it.
template <int Dim, class Derived>
class GradientProviderT : public GradientProvider<Dim> {
 public:
  void correct(const GradientContext<Dim, double>& c, std::array<SparseMatrix<double>, Dim>& g) const override {
    static_cast<const Derived&>(*this).correct_impl(c, g);
  }
  void correct(const GradientContext<Dim, std::complex<double>>& c,
               std::array<SparseMatrix<std::complex<double>>, Dim>& g) const override {
    static_cast<const Derived&>(*this).correct_impl(c, g);
  }
};

/// Ghat = G (the kernel gradient itself).
template <int Dim>
class PlainGradient final : public GradientProviderT<Dim, PlainGradient<Dim>> {
 public:
  std::string name() const override { return "plain"; }
  bool is_plain() const override { return true; }
  template <class Scalar>
  void correct_impl(const GradientContext<Dim, Scalar>&, std::array<SparseMatrix<Scalar>, Dim>&) const {}
};

/// Ghat^a = G^a - diag(G^a 1): the gradient of a constant is exactly zero (Powell 1.15). With alpha = 0 this
/// gives f_i = sum_j (s_j - s_i) G_ij, i.e. the "minus" form with the plain gradient.
template <int Dim>
class MinusGradient final : public GradientProviderT<Dim, MinusGradient<Dim>> {
 public:
  std::string name() const override { return "minus-gradient"; }
  template <class Scalar>
  void correct_impl(const GradientContext<Dim, Scalar>& c, std::array<SparseMatrix<Scalar>, Dim>& g) const {
    const NeighbourList& nl = c.discretisation.neighbours;
    for (int a = 0; a < Dim; ++a) {
      Scalar* v = g[a].valuePtr();
      for (int i = 0; i < nl.size(); ++i) {
        Scalar sum(0);
        long diag = -1;
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
          sum += v[k];
          if (nl.indices[k] == i) diag = k;
        }
        v[diag] -= sum;  // the neighbour list contains i itself
      }
    }
  }
};

}  // namespace sphstab
