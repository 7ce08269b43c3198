#pragma once
/// \file correction_gradient.hpp
/// Every kernel correction of operators/correction.hpp as a GradientProvider, so that each SPH momentum form
/// (wave_1d.hpp: uncorrected, plus, minus, conservative) can be combined with each correction. The correction is
/// evaluated at the CURRENT positions x0 + u from the operators assembled there, so the complex-step Jacobian (and
/// the dual-number force of the corrected conservative form) differentiates through the correction exactly.
///
/// | correction            | Ghat (per axis), Powell                                  | reach | pattern | strain sum |
/// |-----------------------|----------------------------------------------------------|-------|---------|------------|
/// | none                  | G                                                        | 1     | local   | difference |
/// | minus                 | G - diag(G 1) (1.15)                                     | 1     | local   | difference |
/// | shepard               | (G_ij S_i - W_ij g_i) / S_i^2 (3.61)                     | 1     | local   | difference |
/// | column-shepard        | (G_ij c^W_j - W_ij c^G_j) / (S_j)^2 (3.62)               | 2     | local   | direct     |
/// | ncsph                 | Shepard gradient times M_i^{-1} (1.19)                   | 1     | local   | difference |
/// | local-polish          | C_ij = G_ij - r_i - c_j + m_i (4.9, algorithm 4.1)       | 2     | local   | difference |
/// | mean-polish           | row then column mean polish (3.64, algorithm 3.1)        | all   | dense   | difference |
/// | shepard-column-polish | Shepard gradient, then column mean polish (§4.1.1 item 4) | all   | dense   | difference |
///
/// "reach" is dependence_radius(): the neighbour-graph distance over which row i of Ghat reads positions. The
/// strain sum is preferred_strain_sum() (Powell 3.55 alpha): column-shepard needs the direct sum sum_j u_j Ghat_ij
/// (alpha = 0, Powell's item 2), for the row-normalised kernels both sums coincide.
///
/// \note The hat kernel (Powell 3.60) is not a correction: use KernelType::Hat with any provider.
/// \note Dense providers (mean-polish, shepard-column-polish) cost O(N^2) per evaluation and make every force
///       depend on every particle; fine for N up to a few hundred (1D studies), not for production runs.
/// \note local-polish options: NeighbourCounting::BoundaryLevel (Powell Fig. 4.3) and first_step_shepard (Powell
///       4.18: the means r, c, m are taken of the Shepard gradient with the kernel sums frozen at the reference
///       positions x0; recomputed from the discretisation at every call, a real assembly of W and G at x0).
///
/// \code{.cpp}
/// auto shepard = sphstab::make_gradient_provider<1>(sphstab::Correction::Shepard);
/// sphstab::WaveForm1D force(disc, sphstab::MomentumForm::Plus, 1e-2, shepard);  // corrected divergence
/// auto split = sphstab::affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
/// \endcode
#include <memory>
#include <string>

#include "sphstab/forms/gradient_provider.hpp"
#include "sphstab/operators/correction.hpp"
#include "sphstab/operators/local_polish.hpp"

namespace sphstab {

/// Options of CorrectionGradient (each applies to one correction only; others are rejected).
struct CorrectionGradientOptions {
  NeighbourCounting counting = NeighbourCounting::Actual;  ///< local-polish: n_i (BoundaryLevel = Powell Fig. 4.3)
  bool first_step_shepard = false;                         ///< local-polish: means of the (4.18) Shepard gradient
  bool polish_free_only = false;                           ///< mean-polish: N = free particles (default: all N)
  double min_rcond = 1e-12;                                ///< ncsph: smallest accepted rcond of M_i
};

/// A named kernel correction as a gradient provider (see the file comment).
template <int Dim>
class CorrectionGradient final : public GradientProviderT<Dim, CorrectionGradient<Dim>> {
 public:
  /// Throws std::invalid_argument for an option that does not apply to `correction`, or min_rcond outside [0, 1).
  explicit CorrectionGradient(Correction correction, CorrectionGradientOptions options = {});

  /// correction_name(), with "+fig4.3" / "+eq4.18" / "+free" for the non-default options.
  std::string name() const override;
  OperatorRequest requirements() const override;
  int dependence_radius() const override;
  bool keeps_pattern() const override { return !correction_is_dense(m_correction); }
  StrainSum preferred_strain_sum() const override {
    return m_correction == Correction::ColumnShepard ? StrainSum::Direct : StrainSum::Difference;
  }
  bool is_plain() const override { return m_correction == Correction::None; }

  Correction correction() const { return m_correction; }
  const CorrectionGradientOptions& options() const { return m_options; }

  /// g = the corrected gradients of the operators in `context` (GradientProviderT forwards every scalar here).
  template <class Scalar>
  void correct_impl(const GradientContext<Dim, Scalar>& context, std::array<SparseMatrix<Scalar>, Dim>& g) const;

 private:
  Correction m_correction;
  CorrectionGradientOptions m_options;
};

/// Convenience: a shared CorrectionGradient (what WaveForm1D takes).
template <int Dim>
std::shared_ptr<const GradientProvider<Dim>> make_gradient_provider(Correction correction,
                                                                    CorrectionGradientOptions options = {});

extern template class CorrectionGradient<1>;  // instantiated in src/forms/correction_gradient.cpp
extern template class CorrectionGradient<2>;
extern template class CorrectionGradient<3>;

}  // namespace sphstab
