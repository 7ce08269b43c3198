#pragma once
/// \file gradient_provider.hpp
/// Pluggable "kernel-gradient provider" for the momentum equation: given the operators at the CURRENT positions,
/// it supplies a corrected gradient matrix Ghat^a (Powell's H_ij of (3.28) or W~'_ij of (3.55)). Which SPH operator
/// uses Ghat (the divergence of the stress, the strain, or both) is chosen by the force function (wave_1d.hpp); by
/// default the strain uses the plain G (Powell 3.26, 4.12) and only the divergence of the stress uses Ghat.
///
/// Provided here: PlainGradient (Ghat = G) and MinusGradient (Ghat = G - diag(G 1), zeroth-order consistent,
/// Powell 1.15); every named kernel correction of operators/correction.hpp is a CorrectionGradient
/// (forms/correction_gradient.hpp). New providers derive from GradientProviderT and implement one
/// `template <class Scalar> void correct_impl(const GradientContext<Dim, Scalar>&, std::array<SparseMatrix<Scalar>,
/// Dim>& g) const`; the scalar is double, std::complex<double> (complex step) or a Dual of either (numerics/dual.hpp,
/// nested derivatives of the conservative corrected forms).
#include <array>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/numerics/dual.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// Everything a provider may read, all at the current positions x = x0 + u.
template <int Dim, class Scalar>
struct GradientContext {
  const Discretisation<Dim>& discretisation;  ///< reference set, neighbour list (the pattern), volumes
  const Positions<Dim, Scalar>& positions;    ///< current positions, N x Dim
  const Operators<Dim, Scalar>& operators;    ///< current W (if requested), G, H (if requested)
};

/// How a corrected gradient K forms the strain <u_x>_i (Powell 3.55, alpha there):
///   Difference: sum_j (u_j - u_i) K_ij  (alpha = 1; exact for a translation, so momentum-conserving energies)
///   Direct:     sum_j u_j K_ij          (alpha = 0; what Powell ch. 3 §4.1.1 item 2 needs for the column Shepard
///                                        kernel (3.62), whose COLUMNS sum to zero)
/// For a kernel whose rows sum to zero (Shepard, NCSPH, the polishes, C_ij) both coincide.
enum class StrainSum { Difference, Direct };

/// Graph distance used for "reaches every particle" (dense, non-local corrections such as the mean polish).
inline constexpr int kFullReach = std::numeric_limits<int>::max() / 4;

/// Base class of gradient providers. Implementations transform g in place; on entry g = operators.G. On exit g
/// keeps the neighbour-list pattern (values change, structure not), unless keeps_pattern() is false: then g may
/// have any N x N pattern (the dense polishes store all N^2 entries).
///
/// \note dependence_radius(): how many neighbour-graph hops from particle i the VALUES of row i of Ghat may read
///       positions (plain, minus, Shepard, NCSPH: 1; column Shepard and C_ij of Powell 4.9: 2; global polishes:
///       kFullReach). The Jacobian sparsity pattern is built from it and from keeps_pattern().
template <int Dim>
class GradientProvider {
 public:
  virtual ~GradientProvider() = default;
  virtual std::string name() const = 0;
  /// Operators the provider needs besides G (e.g. W for a Shepard correction).
  virtual OperatorRequest requirements() const { return {.kernel = false, .gradient = true, .hessian = false}; }
  virtual int dependence_radius() const { return 1; }
  /// False for providers whose Ghat has entries outside the neighbour list (dense, non-local polishes).
  virtual bool keeps_pattern() const { return true; }
  /// The strain sum this correction is meant for (Powell 3.55); the force function may override it.
  virtual StrainSum preferred_strain_sum() const { return StrainSum::Difference; }
  /// True if Ghat == G (no correction).
  virtual bool is_plain() const { return false; }
  virtual void correct(const GradientContext<Dim, double>& context, std::array<SparseMatrix<double>, Dim>& g) const = 0;
  virtual void correct(const GradientContext<Dim, std::complex<double>>& context,
                       std::array<SparseMatrix<std::complex<double>>, Dim>& g) const = 0;
  /// Dual-number overloads (nested derivatives); GradientProviderT implements them, others may not.
  virtual void correct(const GradientContext<Dim, Dual<double>>&, std::array<SparseMatrix<Dual<double>>, Dim>&) const {
    throw std::logic_error("gradient provider '" + name() + "' does not support dual numbers");
  }
  virtual void correct(const GradientContext<Dim, Dual<std::complex<double>>>&,
                       std::array<SparseMatrix<Dual<std::complex<double>>>, Dim>&) const {
    throw std::logic_error("gradient provider '" + name() + "' does not support dual numbers");
  }
};

/// CRTP helper: Derived implements one template `correct_impl<Scalar>(context, g)`; every overload forwards to it.
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
  void correct(const GradientContext<Dim, Dual<double>>& c,
               std::array<SparseMatrix<Dual<double>>, Dim>& g) const override {
    static_cast<const Derived&>(*this).correct_impl(c, g);
  }
  void correct(const GradientContext<Dim, Dual<std::complex<double>>>& c,
               std::array<SparseMatrix<Dual<std::complex<double>>>, Dim>& g) const override {
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
