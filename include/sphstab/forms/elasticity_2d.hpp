#pragma once
/// \file elasticity_2d.hpp
/// 2D small-strain linear elasticity (plane strain, Lame lambda, mu, density rho) with a uniform pre-stress, in
/// the four SPH momentum forms, kernel at the CURRENT positions x = x0 + u.
///
/// Displacement gradient and stress (all particles, free and fixed):
///   (grad u)_i^{ab} = sum_j (u_j^a - u_i^a) G^b_ij(x),  eps = sym grad u   (Ghat with set_corrected_strain),
///   sigma_i = lambda tr(eps_i) I + 2 mu eps_i + sigma0
/// Momentum (free particles i; Powell 4.13 with sigma / rho^2 and constant rho for alpha = 1):
///   a_i^a = (1/rho) sum_j (sigma_j^{ab} + alpha sigma_i^{ab}) Ghat^b_ij(x),  alpha = 0, 1, -1
/// Conservative: a = -M^{-1} dU/du, M = diag(rho V_i), U = sum_i V_i [1/2 eps_i : C : eps_i + sigma0 : (grad u)_i]
/// (sum over all particles). Differentiating (derivation in elasticity_2d.cpp) gives the explicit formula
///   a_i^c = (1/rho) sum_j (sigma_j + sigma_i)^{ab} [delta_ac G^b_ij + (u_i^a - u_j^a) H^{bc}_ij],
/// the 2D analogue of Powell (3.27).
///
/// Pre-stress from a pre-strain e (the load parameter; every form is affine in e):
///   Isotropic (area ratio xi = V/V0, e = sqrt(xi) - 1 per axis): sigma0 = 2 (lambda + mu) e I
///   UniaxialX (e along x, plane strain):                          sigma0 = lambda e I + 2 mu e e_x (x) e_x
/// The Jacobian is therefore A(e) = A0 + e A1 (affine_jacobian); in terms of the area ratio xi = (1 + e)^2,
/// dA/dxi = A1 / (2 sqrt(xi)). The positions are NOT stretched by the pre-strain (as in Powell §3.3, the pre-stress
/// is an additive constant); stretch the lattice (LatticeOptions::stretch) separately if wanted.
/// Additional momentum terms (elastic_term.hpp: GMS artificial stress, the S-SPH correction of Powell ch. 4) can be
/// added with add_term(); they see the same state (positions, displacements, stresses, operators) and their free
/// rows are added to the acceleration.
/// At a complete lattice equilibrium the initial-stress blocks are sigma0 H_ij (uncorrected), 2 sigma0 H_ij (plus),
/// 0 (minus) and 2 (sigma0 H_ij + H_ij sigma0) (conservative): the 1D ratios 1 : 2 : 4 hold for isotropic sigma0 only.
///
/// \code{.cpp}
/// auto set = sphstab::make_lattice<2>(sphstab::LatticeType::Square, 20, {.spacing = 1.0, .periodic = true});
/// auto disc = sphstab::make_discretisation(set, sphstab::Kernel<2>(sphstab::KernelType::WendlandC2), 1.3);
/// const auto mat = sphstab::ElasticMaterial::from_lame(1.0, 0.5, 1.0);  // lambda, mu, rho
/// auto prestrain = sphstab::PreStrain::from_area_ratio(1.001);
/// sphstab::ElasticForm2D force(disc, mat, sphstab::MomentumForm::Conservative, prestrain);
/// \endcode
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/elastic_term.hpp"
#include "sphstab/forms/gradient_provider.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/models/elastic_material.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

enum class PreStrainKind { Isotropic, UniaxialX };
/// "isotropic" / "iso" or "uniaxial" / "uniaxial-x"; throws std::invalid_argument naming the valid names.
PreStrainKind parse_prestrain_kind(const std::string& name);
/// The canonical name accepted by parse_prestrain_kind: "isotropic" or "uniaxial".
std::string prestrain_kind_name(PreStrainKind kind);

/// A uniform pre-strain: kind and linear strain e (the load parameter).
struct PreStrain {
  PreStrainKind kind = PreStrainKind::Isotropic;
  double strain = 0;  ///< e (finite)
  /// Isotropic pre-strain from the area ratio xi = V/V0 > 0: e = sqrt(xi) - 1.
  static PreStrain from_area_ratio(double xi);
  static PreStrain uniaxial_x(double e) { return {PreStrainKind::UniaxialX, e}; }
  /// sigma0 for this pre-strain in `material` (plane strain).
  Eigen::Matrix2d stress(const ElasticMaterial& material) const;
};

class ElasticForm2D final : public ForceFunction {
 public:
  /// @param[in] discretisation  2D particle set, kernel, h, neighbours (shared, not copied)
  /// @param[in] material        lambda, mu, rho
  /// @param[in] form            momentum form
  /// @param[in] prestrain       pre-strain kind and e (the load)
  /// @param[in] gradient        momentum gradient provider; nullptr = PlainGradient. Conservative needs plain.
  ElasticForm2D(std::shared_ptr<const Discretisation<2>> discretisation, const ElasticMaterial& material,
                MomentumForm form, const PreStrain& prestrain = {},
                std::shared_ptr<const GradientProvider<2>> gradient = nullptr);

  int dofs() const override { return m_disc->dofs(); }
  int dim() const override { return 2; }
  std::string name() const override;
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const override { evaluate(u, a); }
  void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const override { evaluate(u, a); }
  double load() const override { return m_prestrain.strain; }
  std::unique_ptr<ForceFunction> with_load(double load) const override;
  SparsityPattern dof_pattern() const override;
  /// True for the conservative form without additional terms.
  bool conservative() const override { return m_form == MomentumForm::Conservative && m_terms.empty(); }
  double strain_energy(const Eigen::VectorXd& u) const override { return energy(u); }
  std::complex<double> strain_energy(const Eigen::VectorXcd& u) const override { return energy(u); }
  Eigen::VectorXd dof_mass() const override;

  /// Use the provider's Ghat for the strain too: (grad u)_i^{ab} = sum_j (u_j^a - u_i^a) Ghat^b_ij (both operators
  /// corrected, as in NCSPH, whose gradient is exact for linear fields). Default: the strain uses the plain G.
  /// Throws std::invalid_argument without a non-plain provider or for the conservative form.
  void set_corrected_strain(bool on);
  bool corrected_strain() const { return m_corrected_strain; }

  /// Adds a momentum term (artificial stress, S-SPH correction, ...; elastic_term.hpp) evaluated after the base form
  /// at the same state; its free rows are added to the acceleration. Terms are shared by copies (with_load).
  /// Throws std::invalid_argument for a null term.
  void add_term(std::shared_ptr<const ElasticTerm2D> term);
  /// Replaces all terms (e.g. by a frozen copy of one of them); throws std::invalid_argument for a null term.
  void set_terms(std::vector<std::shared_ptr<const ElasticTerm2D>> terms);
  const std::vector<std::shared_ptr<const ElasticTerm2D>>& terms() const { return m_terms; }

  /// Stress of every particle, N x 3 rows (sxx, syy, sxy), for diagnostics.
  Eigen::MatrixX3d stress(const Eigen::VectorXd& u) const;

  /// Prescribed displacements of the fixed particles, interleaved (2 per fixed particle, ascending particle
  /// order; default zero).
  void set_fixed_displacement(const Eigen::VectorXd& d);
  const Eigen::VectorXd& fixed_displacement() const { return m_fixed_u; }

  MomentumForm form() const { return m_form; }
  const ElasticMaterial& material() const { return m_material; }
  const PreStrain& prestrain() const { return m_prestrain; }
  const Discretisation<2>& discretisation() const { return *m_disc; }
  /// The momentum gradient provider (nullptr = plain kernel gradient).
  const GradientProvider<2>* gradient_provider() const { return m_gradient.get(); }

 private:
  template <class Scalar>
  void evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;
  template <class Scalar>
  Scalar energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const;
  template <class Scalar>
  void add_terms(const Discretisation<2>& d, const Positions<2, Scalar>& uall,
                 const Eigen::Matrix<Scalar, Eigen::Dynamic, 3>& sig, const Operators<2, Scalar>& ops,
                 Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;
  template <class Scalar>
  void strain_state(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Positions<2, Scalar>& uall,
                    Eigen::Matrix<Scalar, Eigen::Dynamic, 4>& grad, Operators<2, Scalar>& ops, bool hessian,
                    std::array<SparseMatrix<Scalar>, 2>* corrected = nullptr) const;

  std::shared_ptr<const Discretisation<2>> m_disc;
  ElasticMaterial m_material;
  MomentumForm m_form;
  PreStrain m_prestrain;
  std::shared_ptr<const GradientProvider<2>> m_gradient;
  Eigen::VectorXd m_fixed_u;
  std::vector<std::shared_ptr<const ElasticTerm2D>> m_terms;
  bool m_corrected_strain = false;
};

}  // namespace sphstab
