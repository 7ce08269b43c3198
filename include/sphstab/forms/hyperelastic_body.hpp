#pragma once
/// \file hyperelastic_body.hpp
/// What the two finite-strain total-Lagrangian forms share (FiniteStrainTotalLagrangian, [Ismail2009, (5.6)-(5.8)];
/// VariationalTotalLagrangian, the exact gradient of the discrete strain energy): the reference configuration of a
/// hyperelastic body — particles, material, density, the reference strain gradient K (assembled once at X), the
/// active particles (the free ones and their neighbours, whose F and P are evaluated), the prescribed displacements of
/// the fixed particles and the hourglass control — and what follows from it alone: F_i = I + sum_j (u_j - u_i) x K_ij
/// (or sum_j u_j x K_ij for the direct sum), the strain energy U = sum_i V_i Psi(F_i), P_i, lumped masses, and the
/// ForceFunction members that follow from these. The forms add their momentum equation (acceleration,
/// conservativeness, pattern, name, with_load).
#include <Eigen/Core>
#include <array>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/core/scratch.hpp"
#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/hourglass_control.hpp"
#include "sphstab/models/hyperelastic_model.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

template <int Dim>
class HyperelasticBody : public ForceFunction {
 public:
  int dofs() const override { return m_disc->dofs(); }
  int dim() const override { return Dim; }
  /// 0: the finite-strain forms have no affine load (the body is loaded through set_fixed_displacement).
  double load() const override { return 0; }
  /// U = sum_{active i} V_i Psi(F_i) (the potential of the conservative configurations).
  double strain_energy(const Eigen::VectorXd& u) const override { return energy(u); }
  std::complex<double> strain_energy(const Eigen::VectorXcd& u) const override { return energy(u); }
  /// rho0_i V_i per DOF.
  Eigen::VectorXd dof_mass() const override { return lumped_mass(); }

  /// Prescribed displacements of the fixed particles, interleaved (Dim per fixed particle, ascending particle
  /// index; default zero). Throws std::invalid_argument for a wrong size or non-finite entries.
  void set_fixed_displacement(const Eigen::VectorXd& d);
  const Eigen::VectorXd& fixed_displacement() const { return m_fixed_u; }
  /// Deformation gradient F_i (row-major, Dim^2 entries per row) of every particle (N rows; rows of inactive
  /// particles are NaN). Throws std::invalid_argument where det F <= 0 at an active particle.
  Eigen::MatrixXd deformation_gradients(const Eigen::VectorXd& u) const;
  /// First Piola-Kirchhoff stress, as deformation_gradients.
  Eigen::MatrixXd stresses(const Eigen::VectorXd& u) const;

  const HyperelasticModel<Dim>& material() const { return *m_material; }
  const Discretisation<Dim>& discretisation() const { return *m_disc; }
  const Eigen::VectorXd& density() const { return m_rho; }
  /// Particles whose F and P are evaluated: the free ones and their neighbours (ascending).
  const std::vector<int>& active() const { return m_active; }

 protected:
  /// Checks the inputs (one-line errors naming `who`), sets the density (N entries or one), the active set and zero
  /// Dirichlet data. The form sets m_K (and m_difference, m_hg) in its own constructor.
  HyperelasticBody(std::shared_ptr<const Discretisation<Dim>> discretisation,
                   std::shared_ptr<const HyperelasticModel<Dim>> material, const Eigen::VectorXd& density,
                   std::string who);

  /// rho0_i V_i per DOF.
  Eigen::VectorXd lumped_mass() const;
  /// with_load's check: throws std::invalid_argument (one line) unless load == 0.
  void check_no_load(double load) const;

  /// evaluate()'s and energy()'s scratch arrays, kept between calls (resized, not reallocated, while N is unchanged;
  /// core/scratch.hpp: a copied form starts with empty ones).
  template <class Scalar>
  struct Workspace {
    Positions<Dim, Scalar> u;                          ///< displacement of every particle, N x Dim
    std::vector<Deformation<Scalar, Dim>> F, P;        ///< per particle (NaN / zero outside the active set)
    Eigen::Matrix<Scalar, Eigen::Dynamic, Dim> force;  ///< per particle, N x Dim (the variational form's sums)
  };
  template <class Scalar>
  Workspace<Scalar>& workspace() const;

  /// Fills uall (N x Dim, the full displacement) and F (N entries, NaN for inactive particles) from K.
  template <class Scalar>
  void deformation(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Positions<Dim, Scalar>& uall,
                   std::vector<Deformation<Scalar, Dim>>& F) const;
  /// U = sum_{active i} V_i Psi(F_i).
  template <class Scalar>
  Scalar energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const;

  std::string m_who;  ///< the form's class name, for error messages
  std::shared_ptr<const Discretisation<Dim>> m_disc;
  std::shared_ptr<const HyperelasticModel<Dim>> m_material;
  Eigen::VectorXd m_rho;                                       ///< N entries
  std::shared_ptr<const std::array<SparseMatrix<>, Dim>> m_K;  ///< reference strain gradient K^b, N x N
  bool m_difference = true;  ///< F from sum_j (u_j - u_i) K_ij (zeroth-order consistent) or sum_j u_j K_ij
  std::vector<int> m_active;
  Eigen::VectorXd m_fixed_u;
  HourglassControl<Dim> m_hg;  ///< [Ganzenmueller2015] pair term (forms/hourglass_control.hpp); inactive when off
  mutable Scratch<Workspace> m_work;
};

extern template class HyperelasticBody<1>;
extern template class HyperelasticBody<2>;

}  // namespace sphstab
