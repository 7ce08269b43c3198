#pragma once
// The cases of the mean-polishing study: the kernel corrections (gradient providers, correction_gradient.hpp) none,
// minus [Powell2012, (1.15)], Shepard (3.61), column Shepard (3.62), NCSPH (1.19), the local polish C_ij (4.9,
// algorithm 4.1; with the Fig. 4.3 counting and the (4.18) first-step Shepard means), the mean polish (3.64,
// algorithm 3.1) and the Shepard column polish (ch. 3 §4.1.1 item 4); the momentum forms x corrected operator
// (divergence (3.28), both, strain (3.55)); the fixed layers, and the corrected gradient Ghat at a displaced state.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/wave_1d.hpp"

namespace mean_polishing {

using namespace sphstab;

constexpr int kLayerSupports = 3;  // fixed layers: see tension_lattice_1d

/// One kernel correction of the study: its name in the CSV files and the summary, the gradient provider's options.
struct Variant {
  std::string name;
  Correction correction;
  CorrectionGradientOptions options;
};

inline const std::vector<Variant>& variants() {
  static const std::vector<Variant> v{
      {"none", Correction::None, {}},
      {"minus", Correction::Minus, {}},
      {"shepard", Correction::Shepard, {}},
      {"column-shepard", Correction::ColumnShepard, {}},
      {"ncsph", Correction::Ncsph, {}},
      {"local-polish", Correction::LocalPolish, {}},
      {"local-polish+fig4.3", Correction::LocalPolish, {.counting = NeighbourCounting::BoundaryLevel}},
      {"local-polish+eq4.18", Correction::LocalPolish, {.first_step_shepard = true}},
      {"mean-polish", Correction::MeanPolish, {}},
      {"shepard-column-polish", Correction::ShepardColumnPolish, {}},
  };
  return v;
}

/// A momentum form and the operator the correction is applied to.
struct FormCase {
  MomentumForm form;
  CorrectedOperator target;
};

/// Forms x corrected operator: the divergence (Powell 3.28) and both operators for the non-conservative forms, the
/// strain (3.55) for the conservative one. For "none" only the first of each form is run.
inline const std::vector<FormCase>& form_cases() {
  static const std::vector<FormCase> v{
      {MomentumForm::Uncorrected, CorrectedOperator::Divergence}, {MomentumForm::Uncorrected, CorrectedOperator::Both},
      {MomentumForm::Plus, CorrectedOperator::Divergence},        {MomentumForm::Plus, CorrectedOperator::Both},
      {MomentumForm::Minus, CorrectedOperator::Divergence},       {MomentumForm::Minus, CorrectedOperator::Both},
      {MomentumForm::Conservative, CorrectedOperator::Strain},
  };
  return v;
}

/// The gradient provider of a correction (correction_gradient.hpp).
inline std::shared_ptr<const GradientProvider<1>> provider(const Variant& v) {
  return make_gradient_provider<1>(v.correction, v.options);
}

/// Ghat of a provider at the displaced positions x0 + u (u on the free particles).
inline Eigen::MatrixXd corrected_gradient_at(const Discretisation<1>& d, const GradientProvider<1>& p,
                                             const Eigen::VectorXd& u) {
  Positions<1> x = d.particles.x;
  for (int f = 0; f < d.free_count(); ++f) x(d.free[f], 0) += u[f];
  const Operators<1> ops =
      assemble_operators<1, double>(d.particles, d.neighbours, d.kernel, d.h, p.requirements(), &x);
  std::array<SparseMatrix<>, 1> g{ops.G[0]};
  p.correct(GradientContext<1, double>{d, x, ops}, g);
  return Eigen::MatrixXd(g[0]);
}

}  // namespace mean_polishing
