#pragma once
/// \file total_lagrangian.hpp
/// Total-Lagrangian SPH for 2D small-strain elasticity with a uniform pre-stress, as a ForceFunction: every
/// operator is assembled ONCE at the reference positions x0 and an evaluation is pure sparse matrix-vector products
/// (LinearElasticSph<2>, frame Total, zeroth-order strain gradient and Plus divergence):
///   (grad u)_i^{ab} = sum_j (u_j^a - u_i^a) G0^b_ij,   sigma_i = lambda tr(eps_i) I + 2 mu eps_i + sigma0,
///   a_i^a = (1/rho) sum_j (sigma_j^{ab} + sigma_i^{ab}) G0^b_ij,   G0 = G(x0) fixed.
/// This is the basic SPH (ElasticForm2D Plus) momentum equation with the kernel frozen at x0 (Powell ch. 4 §2.2 and
/// §4 compare it as "TL-SPH"). It is linear in u: a(u) = -A u + a0 with a0 = (2/rho) sigma0 . (G0 1)_i, which
/// vanishes for complete neighbourhoods. The pre-stress therefore has no stiffness (no initial-stress term, unlike
/// the updated-Lagrangian forms): A = K, the material stiffness, for every pre-strain, and A equals the Jacobian of
/// ElasticForm2D(Plus) at u = 0 without pre-stress.
///
/// The form is conservative for equal volumes (minus gradient and plus divergence are adjoint):
///   U(u) = 1/2 sum_i V_i sigma^e_i : eps_i + sum_i V_i sigma0 : (grad u)_i,  sigma^e = sigma - sigma0,
/// and M a = -dU/du with M = diag(rho V_i). Fixed particles are clamped (u = 0).
///
/// \code{.cpp}
/// auto tl = std::make_shared<sphstab::TotalLagrangianForm2D>(disc, material,
/// sphstab::PreStrain::from_area_ratio(1.02)); Eigen::VectorXd a; tl->acceleration(Eigen::VectorXd::Zero(tl->dofs()),
/// a);  // a0 \endcode
#include <memory>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/linear_elastic.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

class TotalLagrangianForm2D final : public ForceFunction {
 public:
  /// Throws std::invalid_argument for a null discretisation, an invalid material, a non-finite pre-strain, or a
  /// particle set whose free particles do not come first (lattice ordering).
  TotalLagrangianForm2D(std::shared_ptr<const Discretisation<2>> discretisation, const ElasticMaterial& material,
                        const PreStrain& prestrain = {});

  int dofs() const override { return m_disc->dofs(); }
  int dim() const override { return 2; }
  std::string name() const override;
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const override;
  /// Linear: a(x + i y) = a(x) + i (a(y) - a0).
  void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const override;
  double load() const override { return m_prestrain.strain; }
  std::unique_ptr<ForceFunction> with_load(double load) const override;
  SparsityPattern dof_pattern() const override;
  bool conservative() const override { return true; }
  double strain_energy(const Eigen::VectorXd& u) const override;
  std::complex<double> strain_energy(const Eigen::VectorXcd& u) const override;
  Eigen::VectorXd dof_mass() const override;

  /// a0 = a(0), size dofs().
  const Eigen::VectorXd& offset() const { return m_a0; }
  const PreStrain& prestrain() const { return m_prestrain; }

 private:
  void compute_offset();
  std::shared_ptr<const Discretisation<2>> m_disc;
  ElasticMaterial m_material;
  PreStrain m_prestrain;
  std::shared_ptr<const LinearElasticSph<2>> m_sph;  ///< TL operators (shared by with_load copies)
  Eigen::VectorXd m_a0;
};

}  // namespace sphstab
