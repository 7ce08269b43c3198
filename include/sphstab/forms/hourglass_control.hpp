#pragma once
/// \file hourglass_control.hpp
/// The hourglass control pair term of [Ganzenmueller2015] as sphstab implements it, shared by the total-Lagrangian
/// forms (FiniteStrainTotalLagrangian: FiniteStrainOptions::hourglass; VariationalTotalLagrangian: its hourglass
/// argument). With X_ij = X_j - X_i (reference, minimum image), x_ij = X_ij + u_j - u_i (current),
/// x^_ij = x_ij / |x_ij| and W_ij = W(|X_ij|, h) at the reference,
///
///   delta_ij = 1/2 (F_i X_ij - x_ij + F_j X_ij - x_ij) . x^_ij   (the pair's mean prediction error along the bond)
///   a_i^HG   = -(c_HG E / (rho0_i V_i)) sum_{j != i} V_i V_j W_ij / |X_ij|^2 delta_ij x^_ij,
///
/// with F_i the form's own deformation gradient (plain or corrected reference gradient) and E Young's modulus.
/// c_HG is the alpha of TrixiParticles.jl's PenaltyForceGanzenmueller (same force; tested) and half the hourglass
/// amplitude of LAMMPS SMD's pair_smd_tlsph, whose delta carries one more factor 1/2 (studies/tl-hourglass/README.md).
/// HourglassProjection::Full (not the paper's) replaces delta_ij x^_ij by the whole mean error vector.
///
/// \note Central and antisymmetric (Bond): with every particle free it conserves linear and angular momentum; zero
///       for every affine field the strain operator reproduces. Elastic, not dissipative, and not the gradient of a
///       potential (F_j depends on u_k): a form with the term is not conservative.
///
/// \code{.cpp}
/// sphstab::HourglassControl<2> hg(disc, E, rho, {.coefficient = 0.1});   // pair coefficients at X, once
/// if (hg.active()) hg.add(uall, F, a);                                    // a += a^HG (free DOFs, interleaved)
/// \endcode
#include <Eigen/Core>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/models/hyperelastic_model.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// The direction of the hourglass pair force.
enum class HourglassProjection {
  Bond,  ///< along the current bond x^_ij ([Ganzenmueller2015]: central, conserves angular momentum)
  Full,  ///< the whole mean pair error vector (not central)
};

struct HourglassOptions {
  double coefficient = 0;  ///< c_HG >= 0 (finite); 0 = off
  HourglassProjection projection = HourglassProjection::Bond;
};

template <int Dim>
class HourglassControl {
 public:
  HourglassControl() = default;
  /// Pair coefficients c_HG E V_j W_ij / |X_ij|^2 / rho0_i of every free particle's neighbours, at the reference.
  /// @param[in] d        reference discretisation
  /// @param[in] young    Young's modulus E (> 0)
  /// @param[in] rho      rho0 per particle (N entries, > 0)
  /// @param[in] options  coefficient and projection
  /// @param[in] who      the owning form's name, for the error message
  /// Throws std::invalid_argument (one line) for a coefficient that is negative or not finite.
  HourglassControl(const Discretisation<Dim>& d, double young, const Eigen::VectorXd& rho, HourglassOptions options,
                   const char* who);

  bool active() const { return !m_offsets.empty(); }
  const HourglassOptions& options() const { return m_options; }
  /// a[Dim f + c] += a^HG of free particle f. uall: N x Dim full displacement; F: the form's deformation gradient of
  /// every particle (those of the free particles' neighbours are read). Scalar: double or std::complex<double>
  /// (complex step: the bond length uses the analytic square root, no conjugate).
  template <class Scalar>
  void add(const Discretisation<Dim>& d, const Positions<Dim, Scalar>& uall,
           const std::vector<Deformation<Scalar, Dim>>& F, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const;

 private:
  HourglassOptions m_options;
  // Pairs of each free particle (free order): m_offsets[f] .. m_offsets[f + 1] index m_j (the neighbour), m_c
  // (c_HG E V_i V_j W_ij / |X_ij|^2 / (rho0_i V_i)) and m_X (X_ij = X_j - X_i). Empty when off.
  std::vector<int> m_offsets;
  std::vector<int> m_j;
  std::vector<double> m_c;
  std::vector<Eigen::Matrix<double, Dim, 1>> m_X;
};

extern template class HourglassControl<1>;
extern template class HourglassControl<2>;

}  // namespace sphstab
