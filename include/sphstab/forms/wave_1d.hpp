#pragma once
/// \file wave_1d.hpp
/// The 1D pre-stressed wave equation u_tt = (u_x + T)_x of Powell ch. 3 §3 (c = E = rho = 1) in its four SPH
/// momentum forms, evaluated with the kernel at the CURRENT positions x = x0 + u.
///
/// Stress (all particles, free and fixed; Powell 3.26 with the sign of DESIGN.md):
///   s_i = sum_j (u_j - u_i) G_ij(x) + T
/// Momentum (free particles i), Powell 3.28:
///   Uncorrected / Plus / Minus:  a_i = sum_j (s_j + alpha s_i) Ghat_ij(x),  alpha = 0, 1, -1
///   Conservative (Powell 3.27):  a_i = sum_j (s_j + s_i) [G_ij + (u_i - u_j) H_ij],  H = d^2W/dx_i^2 V_j
/// The conservative form is a = -M^{-1} dU/du with U = 1/2 sum_{all i} V_i s_i^2 and M = diag(V_i) (rho = 1);
/// for equal volumes this is -dU'/du with Powell's U' = 1/2 sum s_i^2 (3.22).
/// Ghat is G unless a GradientProvider is given (e.g. MinusGradient, or the local-polish C_ij of Powell 4.9).
///
/// Linearised at u = 0 on a lattice whose free particles have complete neighbourhoods (Powell 3.40):
///   A = -da/du = G_f G_f^T - n T L,  L = diag(sum_{j != i} H_ij) - H (free block),  n = 1, 2, 0, 4.
///
/// \code{.cpp}
/// auto set = sphstab::make_lattice<1>(sphstab::LatticeType::Line, 40, {.spacing = 1.0, .support_radius = 2.6});
/// auto disc = sphstab::make_discretisation(set, sphstab::Kernel<1>(sphstab::KernelType::CubicSpline), 1.3);
/// auto force = std::make_shared<sphstab::WaveForm1D>(disc, sphstab::MomentumForm::Plus, 1e-3);
/// Eigen::VectorXd u = Eigen::VectorXd::Zero(force->dofs()), a;
/// force->acceleration(u, a);                     // a == 0 at the equilibrium
/// auto rhs = sphstab::acceleration_function(force);  // for the leap-frog integrator
/// \endcode
#include <memory>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/force_function.hpp"
#include "sphstab/forms/gradient_provider.hpp"
#include "sphstab/forms/momentum_form.hpp"

namespace sphstab {

class WaveForm1D final : public ForceFunction {
 public:
  /// @param[in] discretisation  1D particle set, kernel, h, neighbours (shared, not copied)
  /// @param[in] form            momentum form
  /// @param[in] tension         pre-tension T (finite; T > 0 tension)
  /// @param[in] gradient        momentum gradient provider; nullptr = PlainGradient. Conservative needs plain.
  WaveForm1D(std::shared_ptr<const Discretisation<1>> discretisation, MomentumForm form, double tension,
             std::shared_ptr<const GradientProvider<1>> gradient = nullptr);

  int dofs() const override { return m_disc->dofs(); }
  int dim() const override { return 1; }
  std::string name() const override;
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const override { evaluate(u, a); }
  void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const override { evaluate(u, a); }
  double load() const override { return m_tension; }
  std::unique_ptr<ForceFunction> with_load(double load) const override;
  SparsityPattern dof_pattern() const override;
  bool conservative() const override { return m_form == MomentumForm::Conservative; }
  double strain_energy(const Eigen::VectorXd& u) const override { return energy(u); }
  std::complex<double> strain_energy(const Eigen::VectorXcd& u) const override { return energy(u); }
  Eigen::VectorXd dof_mass() const override;

  /// Stress s_i of every particle (size N), for diagnostics.
  Eigen::VectorXd stress(const Eigen::VectorXd& u) const;

  /// Prescribed displacements of the fixed particles (size = number of fixed particles, in ascending particle
  /// order; default zero).
  void set_fixed_displacement(const Eigen::VectorXd& d);
  const Eigen::VectorXd& fixed_displacement() const { return m_fixed_u; }

  MomentumForm form() const { return m_form; }
  double tension() const { return m_tension; }
  const Discretisation<1>& discretisation() const { return *m_disc; }

 private:
  template <class Scalar>
  void evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;
  template <class Scalar>
  Scalar energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const;
  /// Full displacement (N) and the stress (N) at the current positions; fills the operators.
  template <class Scalar>
  void strain_state(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& uall,
                    Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& s, Operators<1, Scalar>& ops, bool hessian) const;

  std::shared_ptr<const Discretisation<1>> m_disc;
  MomentumForm m_form;
  double m_tension;
  std::shared_ptr<const GradientProvider<1>> m_gradient;
  Eigen::VectorXd m_fixed_u;
};

}  // namespace sphstab
