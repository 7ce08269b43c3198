#pragma once
/// \file body_force.hpp
/// A decorator adding a constant body-force acceleration b (gravity) to the free DOFs of any force function:
///
///   a_k(u) = a_inner,k(u) + b_{k mod Dim}      (free DOFs, interleaved dof = f * Dim + c)
///
/// the rho0 b term of the total-Lagrangian momentum equation rho0 v' = Div P + rho0 b [Ismail2009, ch. 3] (the TL
/// equation of motion; [Ismail2009, §3]). Fixed particles are not unknowns, so they carry no body force (their
/// displacement is prescribed).
///
/// \note Potential: with U_b(u) = -sum_k m_k b_{k mod Dim} u_k (m = dof_mass), M a = -d(U_inner + U_b)/du whenever the
///       inner form is conservative, so strain_energy() returns U_inner + U_b and conservative() is the inner one's;
///       total_energy() of a run then stays constant for a conservative inner form.
/// \note The Jacobian A = -da/du is the inner one's (b does not depend on u); load() and with_load() forward to the
///       inner form (the body force is not the load parameter).
///
/// \code{.cpp}
/// auto tl = std::make_shared<sphstab::FiniteStrainTotalLagrangian<2>>(disc, svk, 1000.0);
/// sphstab::BodyForce gravity(tl, Eigen::Vector2d(0.0, -2.0));   // 2 m/s^2 downward on every free particle
/// Eigen::VectorXd a;
/// gravity.acceleration(u, a);
/// \endcode
#include <Eigen/Core>
#include <memory>
#include <string>

#include "sphstab/system/force_function.hpp"

namespace sphstab {

class BodyForce final : public ForceFunction {
 public:
  /// @param[in] inner         the force function (shared, not null)
  /// @param[in] acceleration  body-force acceleration b, inner->dim() entries, finite (m/s^2 in SI scenes)
  /// Throws std::invalid_argument (one line) for a null inner form, a wrong size or a non-finite entry.
  BodyForce(std::shared_ptr<const ForceFunction> inner, const Eigen::VectorXd& acceleration);

  int dofs() const override { return m_inner->dofs(); }
  int dim() const override { return m_inner->dim(); }
  std::string name() const override;
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const override;
  void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const override;
  double load() const override { return m_inner->load(); }
  std::unique_ptr<ForceFunction> with_load(double load) const override;
  SparsityPattern dof_pattern() const override { return m_inner->dof_pattern(); }
  bool conservative() const override { return m_inner->conservative(); }
  /// U_inner(u) - sum_k m_k b_{k mod Dim} u_k (strain energy plus the body force's potential).
  double strain_energy(const Eigen::VectorXd& u) const override;
  std::complex<double> strain_energy(const Eigen::VectorXcd& u) const override;
  Eigen::VectorXd dof_mass() const override { return m_mass; }

  const ForceFunction& inner() const { return *m_inner; }
  const Eigen::VectorXd& body_acceleration() const { return m_b; }

 private:
  std::shared_ptr<const ForceFunction> m_inner;
  Eigen::VectorXd m_b;     ///< Dim entries
  Eigen::VectorXd m_bdof;  ///< b per DOF (dofs entries)
  Eigen::VectorXd m_mass;  ///< inner dof_mass
};

}  // namespace sphstab
