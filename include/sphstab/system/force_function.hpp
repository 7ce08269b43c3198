#pragma once
/// \file force_function.hpp
/// The interface shared by every SPH force function (momentum form): the time integrator calls it with real
/// displacements, the generic Jacobian with complex ones (complex-step differentiation). One implementation per
/// formulation serves both, so the Jacobian is exactly the derivative of what is time-stepped.
#include <Eigen/Core>
#include <complex>
#include <functional>
#include <memory>
#include <string>

#include "sphstab/neighbours/sparsity.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

/// Accelerations of the free DOFs as a function of their displacements, a = f(u) (the right-hand side of
/// u'' = f(u)). DOFs: free particles only, interleaved dof = f * Dim + a (see Discretisation).
///
/// \note Sign convention: the Jacobian reported by sphstab is A = -da/du (docs/conventions.md §6), positive definite at
/// a
///       stable equilibrium; the load parameter (1D tension T, 2D pre-strain e) enters a affinely, so
///       A(load) = A0 + load * A1 exactly.
/// \note acceleration() must be a pure function of u (no state); the complex overload must be the same
///       arithmetic on complex numbers (analytic in u), so that Im a(u + i h e_k) / h = da/du_k exactly.
class ForceFunction {
 public:
  virtual ~ForceFunction() = default;

  /// Number of DOFs (Dim * number of free particles).
  virtual int dofs() const = 0;
  /// Spatial dimension (components per particle).
  virtual int dim() const = 0;
  /// A short description, e.g. "wave1d/plus/T=0.001".
  virtual std::string name() const = 0;

  /// @param[in]  u  displacements of the free DOFs, size dofs()
  /// @param[out] a  accelerations of the free DOFs, resized to dofs()
  virtual void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const = 0;
  /// Complex-step overload (same formula, complex arithmetic).
  virtual void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const = 0;

  /// The load parameter in which a is affine (1D: T; 2D: pre-strain e).
  virtual double load() const = 0;
  /// A copy of this force function with another load.
  virtual std::unique_ptr<ForceFunction> with_load(double load) const = 0;

  /// A superset of the nonzero pattern of da/du (dofs x dofs).
  virtual SparsityPattern dof_pattern() const = 0;

  /// True when a = -M^{-1} dU/du for the strain_energy U (then M A is symmetric: Powell Thm 3.8).
  virtual bool conservative() const = 0;
  /// Strain energy U(u) of the body (defined for every form; the force derives from it only when conservative()).
  virtual double strain_energy(const Eigen::VectorXd& u) const = 0;
  virtual std::complex<double> strain_energy(const Eigen::VectorXcd& u) const = 0;
  /// Mass of each DOF, m = rho V_i, size dofs(); kinetic energy = 1/2 sum m v^2.
  virtual Eigen::VectorXd dof_mass() const = 0;
};

/// Adapter from a force function to the integrator's callable (shares ownership of `force`).
AccelerationFunction acceleration_function(std::shared_ptr<const ForceFunction> force);

/// Total energy 1/2 sum m v^2 + U(u) (a conserved quantity of the semi-discrete system for conservative forms).
double total_energy(const ForceFunction& force, const Eigen::VectorXd& u, const Eigen::VectorXd& v);

}  // namespace sphstab
