#pragma once
/// \file wave_1d.hpp
/// The 1D pre-stressed wave equation u_tt = (u_x + T)_x of Powell ch. 3 §3 (c = E = rho = 1) in its four SPH
/// momentum forms, evaluated with the kernel at the CURRENT positions x = x0 + u, optionally with a corrected
/// kernel gradient Ghat (a GradientProvider, e.g. make_gradient_provider<1>(Correction::MeanPolish)).
///
/// Stress (all particles, free and fixed; Powell 3.26 with the sign of docs/conventions.md §4, 3.55 when corrected):
///   s_i = sum_j (u_j - u_i) K_ij(x) + T            (K = G, or K = Ghat with StrainSum::Difference)
///   s_i = sum_j u_j K_ij(x) + T                     (K = Ghat with StrainSum::Direct, Powell 3.55 alpha = 0)
/// Momentum (free particles i), Powell 3.28, with D = G or Ghat:
///   Uncorrected / Plus / Minus:  a_i = sum_j (s_j + alpha s_i) D_ij(x),  alpha = 0, 1, -1
///   Conservative:                a = -M^{-1} dU/du,  U = 1/2 sum_{all i} V_i s_i^2,  M = diag(V_i) (rho = 1)
/// With the plain strain the conservative force is Powell (3.27): a_i = sum_j (s_j + s_i) [G_ij + (u_i - u_j) H_ij];
/// with a corrected strain (Powell 3.55-3.64) dU/du = J^T V s with J = ds/du, computed exactly by forward-mode dual
/// numbers (numerics/dual.hpp) through the correction, one pass per colour of J's sparsity pattern.
///
/// Which operator is corrected (CorrectedOperator, Powell uses both readings):
///   Divergence (default for uncorrected/plus/minus): D = Ghat, K = G. Powell (3.28) with H_ij the corrected kernel
///     and K_ij (3.31) the plain one; the C_ij form (4.11)-(4.12) and S-SPH (4.14) are of this kind.
///   Strain (default, and the only meaningful choice, for conservative): K = Ghat. Powell ch. 3 §4.1.1 (3.55): the
///     energy is built from the corrected strain, its divergence follows from the energy. For the non-conservative
///     forms D = G then.
///   Both: K = D = Ghat (non-conservative forms; for conservative it is the same as Strain).
///
/// Linearised at u = 0 on a lattice whose free particles have complete neighbourhoods, plain kernel (Powell 3.40):
///   A = -da/du = G_f G_f^T - n T L,  L = diag(sum_{j != i} H_ij) - H (free block),  n = 1, 2, 0, 4.
///
/// \code{.cpp}
/// auto set = sphstab::make_lattice<1>(sphstab::LatticeType::Line, 40, {.spacing = 1.0, .support_radius = 2.6});
/// auto disc = sphstab::make_discretisation(set, sphstab::Kernel<1>(sphstab::KernelType::CubicSpline), 1.3);
/// auto force = std::make_shared<sphstab::WaveForm1D>(disc, sphstab::MomentumForm::Plus, 1e-3);
/// Eigen::VectorXd u = Eigen::VectorXd::Zero(force->dofs()), a;
/// force->acceleration(u, a);                     // a == 0 at the equilibrium
/// auto rhs = sphstab::acceleration_function(force);  // for the leap-frog integrator
/// // Powell's polished conservative form (3.64):
/// sphstab::WaveForm1D polished(disc, sphstab::MomentumForm::Conservative, 1e-3,
///                              sphstab::make_gradient_provider<1>(sphstab::Correction::MeanPolish));
/// \endcode
#include <memory>
#include <optional>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/gradient_provider.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

/// Which operator of a 1D form uses the provider's corrected gradient (see the file comment).
enum class CorrectedOperator {
  Auto,        ///< Divergence for uncorrected/plus/minus, Strain for conservative
  Divergence,  ///< the divergence of the stress (Powell 3.28, 4.11); rejected for the conservative form
  Strain,      ///< the strain <u_x> (Powell 3.55)
  Both         ///< strain and divergence
};

/// Parses "auto", "divergence", "strain", "both"; throws std::invalid_argument otherwise.
CorrectedOperator parse_corrected_operator(const std::string& name);
std::string corrected_operator_name(CorrectedOperator target);

/// Options of WaveForm1D for a non-plain gradient provider.
struct WaveForm1DOptions {
  CorrectedOperator corrected = CorrectedOperator::Auto;
  /// Strain sum with the corrected K; default: the provider's preferred_strain_sum(). The plain strain always uses
  /// the difference sum (Powell 3.26).
  std::optional<StrainSum> strain_sum = {};
};

class WaveForm1D final : public ForceFunction {
 public:
  /// @param[in] discretisation  1D particle set, kernel, h, neighbours (shared, not copied)
  /// @param[in] form            momentum form
  /// @param[in] tension         pre-tension T (finite; T > 0 tension)
  /// @param[in] gradient        corrected-gradient provider; nullptr = PlainGradient (no correction)
  /// @param[in] options         which operator is corrected, strain sum (ignored for a plain provider)
  /// Throws std::invalid_argument for a null discretisation, a non-finite T, or CorrectedOperator::Divergence with
  /// the conservative form and a non-plain provider.
  WaveForm1D(std::shared_ptr<const Discretisation<1>> discretisation, MomentumForm form, double tension,
             std::shared_ptr<const GradientProvider<1>> gradient = nullptr, const WaveForm1DOptions& options = {});

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
  /// True when the strain (resp. the divergence) uses the corrected gradient.
  bool strain_corrected() const { return m_strain_corrected; }
  bool divergence_corrected() const { return m_divergence_corrected; }
  /// The strain sum in use (Difference for the plain strain).
  StrainSum strain_sum() const { return m_strain_sum; }
  /// Graph distance over which s_i reads displacements (1 for the plain strain).
  int strain_reach() const { return m_strain_reach; }
  double tension() const { return m_tension; }
  const Discretisation<1>& discretisation() const { return *m_disc; }

 private:
  template <class Scalar>
  void evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;
  template <class Scalar>
  Scalar energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const;
  /// Full displacement (N) and the stress (N) at the current positions; fills the operators and, when a corrected
  /// operator is in use, the corrected gradient (`corrected` true on return).
  template <class Scalar>
  void strain_state(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& uall,
                    Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& s, Operators<1, Scalar>& ops, bool hessian,
                    SparseMatrix<Scalar>& ghat, bool& corrected) const;
  /// Conservative form with a corrected strain: a = -M^{-1} J^T V s by dual-number passes.
  template <class Scalar>
  void evaluate_energy_gradient(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;

  std::shared_ptr<const Discretisation<1>> m_disc;
  MomentumForm m_form;
  double m_tension;
  std::shared_ptr<const GradientProvider<1>> m_gradient;  ///< null unless non-plain
  bool m_strain_corrected = false;
  bool m_divergence_corrected = false;
  StrainSum m_strain_sum = StrainSum::Difference;
  int m_strain_reach = 1;
  /// Corrected conservative form: colouring of J = ds/du (rows: all particles, columns: free DOFs); for each colour
  /// the (particle row, DOF column) entries it recovers.
  std::vector<std::vector<std::pair<int, int>>> m_strain_colour_entries;
  Eigen::VectorXd m_fixed_u;
};

}  // namespace sphstab
