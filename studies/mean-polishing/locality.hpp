#pragma once
// Locality of the corrections: the global mean polish [Powell2012, algorithm 3.1, (3.64)] and the Shepard column
// polish ([Powell2012, ch. 3 §4.1.1 item 4]) give a fully populated corrected gradient ("action at a distance"). At a
// displaced state (N = n, cubic, h = 1.3 dx, random displacement in [-0.05, 0.05] dx): stored and non-zero entries of G
// and Ghat and of the complex-step Jacobians of the plus and conservative forms, and their colour counts; locality.csv.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "correction_cases.hpp"
#include "csv_cells.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice_presets.hpp"

namespace mean_polishing {

using namespace sphstab;
using study::random_vector;

/// One row of locality.csv: a correction.
struct LocalityRow {
  std::string correction;
  long g_stored, g_nonzero, gh_stored, gh_nonzero, pattern_plus, jac_plus, pattern_cons, jac_cons;
  int colours_plus, colours_cons;

  static constexpr const char* kCsvHeader =
      "correction,G_stored,G_nonzero,Ghat_stored,Ghat_nonzero,jacobian_pattern_plus,jacobian_nonzero_plus,"
      "colours_plus,jacobian_pattern_conservative,jacobian_nonzero_conservative,colours_conservative";
  void csv(std::ostream& o) const {
    csv_line(o, correction, g_stored, g_nonzero, gh_stored, gh_nonzero, pattern_plus, jac_plus, colours_plus,
             pattern_cons, jac_cons, colours_cons);
  }
};

/// Entries of m larger than relative x max |m|.
inline long count_nonzero(const Eigen::MatrixXd& m, double relative) {
  const double tol = relative * m.cwiseAbs().maxCoeff();
  return (m.array().abs() > tol).count();
}

/// Locality: entries of Ghat and of the Jacobian at a displaced state (N = n, cubic, h = 1.3), per correction.
inline std::vector<LocalityRow> locality_counts(int n) {
  std::vector<LocalityRow> locality;
  Kernel<1> kernel(KernelType::CubicSpline);
  const double h = 1.3;
  auto disc = make_discretisation(tension_lattice_1d(kernel, h, n, false, kLayerSupports), kernel, h);
  const Eigen::VectorXd u = random_vector(disc->dofs(), 0.05, 3);
  const Eigen::MatrixXd g = corrected_gradient_at(*disc, PlainGradient<1>(), u);
  for (const Variant& v : variants()) {
    const auto p = provider(v);
    WaveForm1D plus(disc, MomentumForm::Plus, 0.1, p);
    WaveForm1D cons(disc, MomentumForm::Conservative, 0.1, p);
    const Eigen::MatrixXd gh = corrected_gradient_at(*disc, *p, u);
    Positions<1> x = disc->particles.x;
    const Operators<1> ops =
        assemble_operators<1, double>(disc->particles, disc->neighbours, disc->kernel, h, p->requirements(), &x);
    std::array<SparseMatrix<>, 1> stored{ops.G[0]};
    p->correct(GradientContext<1, double>{*disc, x, ops}, stored);
    const ComplexStepJacobian jp(plus), jc(cons);
    locality.push_back({v.name, disc->neighbours.nonzeros(), count_nonzero(g, 1e-14), stored[0].nonZeros(),
                        count_nonzero(gh, 1e-14), jp.pattern().nonzeros(),
                        count_nonzero(Eigen::MatrixXd(jp.compute(u)), 1e-14), jc.pattern().nonzeros(),
                        count_nonzero(Eigen::MatrixXd(jc.compute(u)), 1e-14), jp.colours(), jc.colours()});
  }
  return locality;
}

}  // namespace mean_polishing
