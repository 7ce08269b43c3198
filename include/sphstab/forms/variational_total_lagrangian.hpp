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
///       modes of the corrected K) are not controlled here: they are neutrally stable, not damped.
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
#include "sphstab/models/hyperelastic_model.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

template <int Dim>
class VariationalTotalLagrangian final : public ForceFunction {
 public:
  /// @param[in] discretisation  reference set X, kernel, h, neighbours (shared, not null)
  /// @param[in] material        hyperelastic model (shared, not null)
  /// @param[in] density         rho0 per particle (N entries) or 1 entry; finite and > 0
  /// @param[in] gradient        reference strain gradient K (nullptr or plain: G); must keep the neighbour pattern
  /// Throws std::invalid_argument (one line) for a null input, a density of the wrong size or not > 0, or a
  /// non-local (dense) gradient provider.
  VariationalTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                             std::shared_ptr<const HyperelasticModel<Dim>> material, const Eigen::VectorXd& density,
                             std::shared_ptr<const GradientProvider<Dim>> gradient = nullptr);
  VariationalTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                             std::shared_ptr<const HyperelasticModel<Dim>> material, double density,
                             std::shared_ptr<const GradientProvider<Dim>> gradient = nullptr)
      : VariationalTotalLagrangian(std::move(discretisation), std::move(material),
                                   Eigen::VectorXd::Constant(1, density), std::move(gradient)) {}

  int dofs() const override { return m_disc->dofs(); }
  int dim() const override { return Dim; }
  std::string name() const override;
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const override { evaluate(u, a); }
  void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const override { evaluate(u, a); }
  double load() const override { return 0; }
  /// A copy for load == 0; throws std::invalid_argument otherwise (no affine load).
  std::unique_ptr<ForceFunction> with_load(double load) const override;
  SparsityPattern dof_pattern() const override;
  bool conservative() const override { return true; }
  double strain_energy(const Eigen::VectorXd& u) const override { return energy(u); }
  std::complex<double> strain_energy(const Eigen::VectorXcd& u) const override { return energy(u); }
  Eigen::VectorXd dof_mass() const override;

  /// Prescribed displacements of the fixed particles, interleaved (Dim per fixed particle, ascending index).
  /// Throws std::invalid_argument for a wrong size or non-finite entries.
  void set_fixed_displacement(const Eigen::VectorXd& d);
  /// F_i (row-major, Dim^2 per row; NaN rows for inactive particles) and P_i, as FiniteStrainTotalLagrangian.
  Eigen::MatrixXd deformation_gradients(const Eigen::VectorXd& u) const;
  Eigen::MatrixXd stresses(const Eigen::VectorXd& u) const;
  const std::vector<int>& active() const { return m_active; }

 private:
  /// evaluate()'s and energy()'s scratch arrays, kept between calls; every entry read is written earlier in the same
  /// call. Copying a form does not copy them: the copy starts empty.
  template <class Scalar>
  struct Workspace {
    Workspace() = default;
    Workspace(const Workspace&) {}
    Workspace(Workspace&&) = default;
    Workspace& operator=(const Workspace&) { return *this; }
    Workspace& operator=(Workspace&&) = default;
    Positions<Dim, Scalar> u;                          ///< displacement of every particle, N x Dim
    std::vector<Deformation<Scalar, Dim>> F;           ///< per particle (NaN outside the active set)
    Eigen::Matrix<Scalar, Eigen::Dynamic, Dim> force;  ///< -dU/du per particle, N x Dim
  };
  template <class Scalar>
  Workspace<Scalar>& workspace() const;

  /// Fills uall (N x Dim, the full displacement) and F (N entries, NaN for inactive particles).
  template <class Scalar>
  void deformation(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Positions<Dim, Scalar>& uall,
                   std::vector<Deformation<Scalar, Dim>>& F) const;
  template <class Scalar>
  void evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;
  template <class Scalar>
  Scalar energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const;

  std::shared_ptr<const Discretisation<Dim>> m_disc;
  std::shared_ptr<const HyperelasticModel<Dim>> m_material;
  std::shared_ptr<const GradientProvider<Dim>> m_gradient;
  Eigen::VectorXd m_rho;                                       ///< N entries
  std::shared_ptr<const std::array<SparseMatrix<>, Dim>> m_K;  ///< reference strain gradient, N x N
  Eigen::Matrix<double, Eigen::Dynamic, Dim> m_rowsum;         ///< sum_j K^b_ij, N x Dim
  std::vector<int> m_active;
  Eigen::VectorXd m_fixed_u;
  mutable Workspace<double> m_work_real;                   ///< acceleration(VectorXd), strain_energy(VectorXd)
  mutable Workspace<std::complex<double>> m_work_complex;  ///< the complex overloads (complex-step Jacobians)
};

extern template class VariationalTotalLagrangian<1>;
extern template class VariationalTotalLagrangian<2>;

}  // namespace sphstab
