#pragma once
/// \file semi_discrete_system.hpp
/// A semi-discrete SPH scheme as a first-order system y' = F(y; p) (docs/conventions.md §7): the state y of the
/// free particles (rate forms: x, v, rho, S[, e]; the total-strain forms: u, v) and its rate F. The linearisation
/// J = dF/dy (jacobian/complex_step_jacobian.hpp, coloured complex step) and its spectrum (growth/system_spectrum.hpp)
/// answer "does a perturbation of this state grow, and how fast": growth rate = max Re lambda(J).
///
/// The second-order systems u'' = a(u) of the force functions are the case y = (u, v), F = (v, a(u)): SecondOrderForm
/// wraps any ForceFunction, so every existing form plugs into the first-order tools unchanged.
#include <Eigen/Core>
#include <complex>
#include <memory>
#include <string>

#include "sphstab/neighbours/sparsity.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

/// y' = F(y). Implementations must make rate() a pure function of y, and the complex overload the same arithmetic on
/// complex numbers (analytic in y), so that Im F(y + i h e_k) / h = dF/dy_k exactly.
class SemiDiscreteSystem {
 public:
  virtual ~SemiDiscreteSystem() = default;
  /// Length of the state vector y.
  virtual int size() const = 0;
  /// A short description, e.g. "second-order(wave1d/plus/T=0.001)".
  virtual std::string name() const = 0;
  /// @param[in]  y     state, size()
  /// @param[out] dydt  F(y), resized to size()
  virtual void rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) const = 0;
  virtual void rate(const Eigen::VectorXcd& y, Eigen::VectorXcd& dydt) const = 0;
  /// A superset of the nonzero pattern of dF/dy (size() x size()).
  virtual SparsityPattern pattern() const = 0;
  /// Per entry of y, a magnitude it varies on (a position: a length of the discretisation; a density: rho0; ...).
  /// Derivative steps scale with it (jacobian/complex_step_jacobian.hpp), so that a Jacobian is exact at any length
  /// scale the toolkit supports (core/length_scale.hpp). Default: 1 for every entry.
  virtual Eigen::VectorXd variable_scale() const { return Eigen::VectorXd::Ones(size()); }
};

/// u'' = a(u) of a force function as y = (u, v), F(y) = (v, a(u)); J = [[0, I], [-A, 0]] with A = -da/du, so the
/// eigenvalues of J are +-sqrt(-mu), mu in eig(A), and max Re lambda(J) = max Re sqrt(-mu) = the growth rate of
/// growth_rate.hpp.
class SecondOrderForm final : public SemiDiscreteSystem {
 public:
  /// Throws std::invalid_argument for a null force.
  explicit SecondOrderForm(std::shared_ptr<const ForceFunction> force);

  int size() const override { return 2 * m_force->dofs(); }
  std::string name() const override { return "second-order(" + m_force->name() + ")"; }
  void rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) const override;
  void rate(const Eigen::VectorXcd& y, Eigen::VectorXcd& dydt) const override;
  SparsityPattern pattern() const override;
  const ForceFunction& force() const { return *m_force; }

 private:
  std::shared_ptr<const ForceFunction> m_force;
};

}  // namespace sphstab
