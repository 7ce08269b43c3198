#pragma once
/// \file variational_total_lagrangian.hpp
/// Finite-strain total-Lagrangian SPH whose force is EXACTLY the negative gradient of the discrete strain energy, for
/// any reference strain gradient K (plain G or a corrected one, e.g. NCSPH [Powell2012, (1.19)]), assembled once at X:
///
///   F_i = I + sum_j (u_j - u_i) (x) K_ij,   U(u) = sum_{active i} V_i Psi(F_i),   M a = -dU/du,  M = diag(rho0_k V_k)
///   f_k^a = -dU/du_k^a = -sum_i V_i P_i^{ab} K^b_ik + V_k P_k^{ab} sum_j K^b_kj          (P = dPsi/dF)
///
/// i.e. the stress divergence uses the TRANSPOSE of the strain operator (the Galerkin / Bonet-Lok pairing). With
/// K = G and equal volumes (V_i G_ik = -V_k G_ki) this is the plus divergence of FiniteStrainTotalLagrangian
/// (plain gradient, difference strain), the variational pair of that form; with a first-order corrected K (exact for
/// linear fields, hence objective: a rigid rotation gives F = R and P = 0) it is the corrected pair that
/// FiniteStrainTotalLagrangian does not offer (its divergence always uses the plain G, which with NCSPH strain has
/// growing modes at rest: studies/tl-csm3).
///
/// \note Conservative: energy and linear momentum (when every particle is free and K rows sum to 0) are conserved by
///       the semi-discrete system; M A is symmetric. Zero-energy modes of U other than rigid motions (hourglass
///       modes of the corrected K) are neutrally stable, not damped, unless the hourglass argument switches on the
///       [Ganzenmueller2015] pair term (forms/hourglass_control.hpp, with this form's F): a_i += a_i^HG. The term is
///       not the gradient of a potential, so with it the form is not conservative() (M A no longer symmetric).
/// \note Fixed particles: prescribed displacement (set_fixed_displacement, default 0), never unknowns; their F and
///       P enter the sums. An active particle with det F <= 0 throws std::invalid_argument.
/// \note Not thread-safe: acceleration() and strain_energy() reuse scratch arrays owned by the object (one set per
///       scalar type, kept between calls: no allocation once sized); give each thread its own copy (a copy starts
///       with empty scratch arrays).
///
/// \code{.cpp}
/// auto ncsph = sphstab::make_gradient_provider<2>(sphstab::Correction::Ncsph);
/// sphstab::VariationalTotalLagrangian<2> tl(disc, svk, 1000.0, ncsph);
/// Eigen::VectorXd a;
/// tl.acceleration(u, a);   // = -M^{-1} dU/du
/// \endcode
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/gradient_provider.hpp"
#include "sphstab/forms/hourglass_control.hpp"
#include "sphstab/forms/hyperelastic_body.hpp"
#include "sphstab/models/hyperelastic_model.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

template <int Dim>
class VariationalTotalLagrangian final : public HyperelasticBody<Dim> {
 public:
  /// @param[in] discretisation  reference set X, kernel, h, neighbours (shared, not null)
  /// @param[in] material        hyperelastic model (shared, not null)
  /// @param[in] density         rho0 per particle (N entries) or 1 entry; finite and > 0
  /// @param[in] gradient        reference strain gradient K (nullptr or plain: G); must keep the neighbour pattern
  /// @param[in] hourglass       [Ganzenmueller2015] hourglass control (coefficient 0 = off, the default)
  /// Throws std::invalid_argument (one line) for a null input, a density of the wrong size or not > 0, a
  /// non-local (dense) gradient provider, or an hourglass coefficient that is negative or not finite.
  VariationalTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                             std::shared_ptr<const HyperelasticModel<Dim>> material, const Eigen::VectorXd& density,
                             std::shared_ptr<const GradientProvider<Dim>> gradient = nullptr,
                             HourglassOptions hourglass = {});
  VariationalTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                             std::shared_ptr<const HyperelasticModel<Dim>> material, double density,
                             std::shared_ptr<const GradientProvider<Dim>> gradient = nullptr,
                             HourglassOptions hourglass = {})
      : VariationalTotalLagrangian(std::move(discretisation), std::move(material),
                                   Eigen::VectorXd::Constant(1, density), std::move(gradient), hourglass) {}

  std::string name() const override;
  /// -M^{-1} dU/du (file comment).
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const override;
  void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const override;
  /// A copy for load == 0; throws std::invalid_argument otherwise (no affine load).
  std::unique_ptr<ForceFunction> with_load(double load) const override;
  SparsityPattern dof_pattern() const override;
  /// True unless the hourglass term is on.
  bool conservative() const override { return !this->m_hg.active(); }
  // dofs, load, strain_energy, dof_mass, set_fixed_displacement, deformation_gradients, stresses, active, ...: the
  // body's (forms/hyperelastic_body.hpp).

 private:
  using Body = HyperelasticBody<Dim>;
  using Body::m_active, Body::m_disc, Body::m_hg, Body::m_K, Body::m_material, Body::m_rho;
  using Body::deformation, Body::energy, Body::workspace;
  template <class Scalar>
  using Workspace = typename Body::template Workspace<Scalar>;

  template <class Scalar>
  void evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;

  std::shared_ptr<const GradientProvider<Dim>> m_gradient;
  Eigen::Matrix<double, Eigen::Dynamic, Dim> m_rowsum;  ///< sum_j K^b_ij, N x Dim
};

extern template class VariationalTotalLagrangian<1>;
extern template class VariationalTotalLagrangian<2>;

}  // namespace sphstab
