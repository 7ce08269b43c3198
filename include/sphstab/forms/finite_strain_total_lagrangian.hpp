#pragma once
/// \file finite_strain_total_lagrangian.hpp
/// Finite-strain total-Lagrangian SPH [Ismail2009, ch. 5] for a hyperelastic material (models/hyperelastic_model.hpp)
/// in 1D or 2D (plane strain), as a ForceFunction. Every operator is assembled ONCE at the reference positions X
/// (Ismail's SPH matrices X, Y [Ismail2009, §2.6] are G^0, G^1 of docs/conventions.md §3, kernel gradient with
/// respect to the first index, each column scaled by V_j); an evaluation is one strain pass, the constitutive law
/// per particle and one divergence pass, with no kernel evaluation.
///
///   F_i = I + (Grad u)_i,  (Grad u)_i^{ab} = sum_j (u_j^a - u_i^a) K^b_ij     (StrainSum::Difference), or
///                                          = sum_j u_j^a K^b_ij                (StrainSum::Direct: [Ismail2009,
///                                          (5.7)],
///                                                                               algorithm 5.1 line 11: F = X u + 1)
///   P_i = P(F_i)                                                               ([Ismail2009, (3.64)] for Neo-Hookean)
///   a_i^a = (1/rho0_i) sum_j (P_j^{ab} + alpha P_i^{ab}) G^b_ij                ([Ismail2009, (5.6), (5.8)]: alpha = 0,
///                                                                               a = X P / rho, algorithm 5.1 l. 16-17)
///           + a_i^HG                                                            (hourglass control, off by default)
/// with K = G (plain reference gradient) or the reference gradient of a GradientProvider (e.g. the first-order
/// corrected NCSPH gradient [Powell2012, (1.19)]) applied ONCE at X, and alpha = 0 (Plain, Ismail), +1 (Plus) or
/// -1 (Minus).
///
/// \note Linear momentum: with the Plus divergence, sum_i m_i a_i = sum_i sum_j V_i V_j (P_i + P_j) grad_i W_ij = 0
///       for any strain operator (grad_i W_ij = -grad_j W_ji, m_i = rho0_i V_i), when every particle is free.
///       Ismail's plain divergence does not conserve it (sum_j V_j P_j grad W_ij is not antisymmetric in i, j).
/// \note Variational pair: the plain reference gradient with StrainSum::Difference and the Plus divergence give
///       M a = -dU/du with U = sum_i V_i Psi(F_i), M = diag(rho0_i V_i), for ANY volumes (V_i G_ik = -V_k G_ki); then
///       conservative() is true and the Jacobian M A is symmetric.
/// \note With Hooke's law (models/hooke.hpp), the minus gradient and the Plus divergence this is exactly the
///       small-strain TotalLagrangianForm2D (without pre-stress), at any displacement.
/// \note Fixed particles are Dirichlet particles: their displacement is prescribed (set_fixed_displacement, default 0)
///       and they are never unknowns; their F and P enter the free rows. Only the particles that are free or within
///       the neighbour list of a free particle ("active") are evaluated; an active particle with det F <= 0 throws.
/// \note Hourglass control (FiniteStrainOptions::hourglass = c_HG > 0), the pair term of [Ganzenmueller2015] as
///       sphstab implements it (forms/hourglass_control.hpp, shared with VariationalTotalLagrangian): with X_ij = X_j -
///       X_i (reference, minimum image), x_ij = X_ij + u_j - u_i (current), x^_ij = x_ij / |x_ij| and W_ij = W(|X_ij|,
///       h) at the reference,
///         delta_ij = 1/2 (F_i X_ij - x_ij + F_j X_ij - x_ij) . x^_ij       (the pair's mean prediction error along
///                                                                          the bond: eps^i_ij = F_i X_ij - x_ij and
///                                                                          eps^j_ji = F_j X_ji - x_ji = -(F_j X_ij -
///                                                                          x_ij))
///         a_i^HG = -(c_HG E / (rho0_i V_i)) sum_{j != i} V_i V_j W_ij / |X_ij|^2 delta_ij x^_ij,
///       E = material().young() (Young's modulus in every dimension and uniaxial state). The pair force is
///       central and antisymmetric (delta_ij = delta_ji, x^_ji = -x^_ij), so with every particle free it conserves
///       linear and angular momentum exactly; it vanishes for any affine field x = A X + b whenever the strain
///       operator reproduces it (F_i = A at every active particle: a first-order corrected gradient such as NCSPH
///       with the difference sum); with the plain gradient F_i = I + (A - I) S, S = sum_j X_ij (x) G_ij != I, so an
///       affine field leaves a residual wherever S differs between i and j or the neighbourhood is not symmetric.
///       The term is elastic, not dissipative: it lifts the zero-energy modes (sawtooth, checkerboard) to finite
///       frequencies, it does not damp them. It is not the gradient of a potential (F_j depends on u_k), so the
///       form is not conservative() with it. c_HG = 0 (default) evaluates exactly the code path without it.
///       HourglassProjection::Full (not the paper's) replaces delta_ij x^_ij by the whole mean error
///       1/2 (F_i X_ij - x_ij + F_j X_ij - x_ij): still antisymmetric (linear momentum) and zero for reproduced affine
///       fields, but not central, so angular momentum is not conserved; it penalises transverse pair errors too.
/// \note Not thread-safe: acceleration() and strain_energy() reuse scratch arrays owned by the object (the full
///       displacement, F and P of every particle; one set per scalar type, kept between calls), so an evaluation
///       allocates nothing once the arrays have their size. One object must not be evaluated from two threads at
///       once; give each thread its own copy (a copy starts with empty scratch arrays of its own).
/// \note The form has no affine load parameter: load() is 0 and with_load() accepts only 0 (a copy). Load it through
///       the prescribed displacements; linearise at a deformed state with ComplexStepJacobian::compute(u).
///
/// \code{.cpp}
/// auto nh = std::make_shared<sphstab::NeoHookean<1>>(sphstab::ElasticMaterial::from_young_poisson(200e9, 0.3, 8000));
/// sphstab::FiniteStrainTotalLagrangian<1> tl(disc, nh, 8000.0);   // Plus divergence, difference strain
/// tl.set_fixed_displacement(d);                                   // Dirichlet data of the fixed particles
/// Eigen::VectorXd a;
/// tl.acceleration(u, a);
/// sphstab::SparseMatrix<> A = sphstab::ComplexStepJacobian(tl).compute(u);   // A = -da/du at u
/// \endcode
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/elastic_bar.hpp"
#include "sphstab/forms/gradient_provider.hpp"
#include "sphstab/forms/hourglass_control.hpp"
#include "sphstab/forms/hyperelastic_body.hpp"
#include "sphstab/models/hyperelastic_model.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

template <int Dim>
struct FiniteStrainOptions {
  /// Strain sum: Difference (zeroth-order consistent, the variational partner of Plus) or Direct ([Ismail2009, (5.7)]).
  StrainSum strain_sum = StrainSum::Difference;
  /// Reference gradient of the strain (applied once at X); nullptr or plain: G itself.
  std::shared_ptr<const GradientProvider<Dim>> gradient;
  /// Plain ([Ismail2009, (5.8)]), Plus (momentum conserving) or Minus; Adjoint is rejected.
  StressDivergence divergence = StressDivergence::Plus;
  /// Hourglass control coefficient c_HG >= 0 (finite) of the [Ganzenmueller2015] pair term (file comment); 0 = off.
  double hourglass = 0;
  /// Direction of the hourglass pair force: Bond (the paper's) or Full.
  HourglassProjection hourglass_projection = HourglassProjection::Bond;
};

template <int Dim>
class FiniteStrainTotalLagrangian final : public HyperelasticBody<Dim> {
 public:
  /// @param[in] discretisation  reference set X, kernel, h, neighbours (shared)
  /// @param[in] material        hyperelastic model (shared)
  /// @param[in] density         rho0 per particle (N entries, > 0), or size 1 for a uniform rho0
  /// @param[in] options         strain and divergence operators
  /// Throws std::invalid_argument (one line) for a null discretisation or material, h <= 0, a density of the wrong
  /// size or not > 0, the Adjoint divergence, an hourglass coefficient that is negative or not finite.
  FiniteStrainTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                              std::shared_ptr<const HyperelasticModel<Dim>> material, const Eigen::VectorXd& density,
                              FiniteStrainOptions<Dim> options = {});
  FiniteStrainTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                              std::shared_ptr<const HyperelasticModel<Dim>> material, double density,
                              FiniteStrainOptions<Dim> options = {})
      : FiniteStrainTotalLagrangian(std::move(discretisation), std::move(material),
                                    Eigen::VectorXd::Constant(1, density), std::move(options)) {}

  std::string name() const override;
  /// [Ismail2009, (5.6), (5.8)] with the chosen divergence (file comment).
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const override;
  void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const override;
  /// A copy for load == 0; throws std::invalid_argument otherwise (no affine load; see the file comment).
  std::unique_ptr<ForceFunction> with_load(double load) const override;
  SparsityPattern dof_pattern() const override;
  /// Plain reference gradient, StrainSum::Difference and the Plus divergence (the variational pair), without
  /// hourglass control.
  bool conservative() const override;
  // dofs, load, strain_energy, dof_mass, set_fixed_displacement, deformation_gradients, stresses, material, density,
  // active: the body's (forms/hyperelastic_body.hpp).

 private:
  using Body = HyperelasticBody<Dim>;
  using Body::m_active, Body::m_disc, Body::m_hg, Body::m_K, Body::m_material, Body::m_rho;
  using Body::deformation, Body::energy, Body::workspace;
  template <class Scalar>
  using Workspace = typename Body::template Workspace<Scalar>;

  template <class Scalar>
  void evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;

  FiniteStrainOptions<Dim> m_options;
  bool m_plain_strain = true;                                  ///< K = G
  std::shared_ptr<const std::array<SparseMatrix<>, Dim>> m_G;  ///< reference G^b (divergence), N x N
};

extern template class FiniteStrainTotalLagrangian<1>;
extern template class FiniteStrainTotalLagrangian<2>;

}  // namespace sphstab
