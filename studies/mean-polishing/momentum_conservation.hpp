#pragma once
// Momentum conservation of the corrected forms ([Powell2012, ch. 4 §2.3]: C_ij has "no guarantee that the method will
// conserve linear momentum"; [Powell2012, (3.62)] item 2): on a periodic lattice of 31 particles, h = 1.3 dx, with a
// random displacement in [-0.1, 0.1] dx and T = 0.1, the total force |sum V a| / sum V |a| of every correction and
// form x corrected operator, and the largest row and column sums of Ghat (relative to max |Ghat|); momentum.csv.
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "correction_cases.hpp"
#include "csv_cells.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/particles/lattice_presets.hpp"

namespace mean_polishing {

using namespace sphstab;
using study::random_vector;

/// One row of momentum.csv: a kernel, correction and form x corrected operator.
struct MomentumRow {
  std::string kernel, correction, form, target;
  double total, rowsum, colsum;

  static constexpr const char* kCsvHeader =
      "kernel,correction,form,corrected_operator,total_force_relative,max_row_sum_relative,"
      "max_column_sum_relative";
  void csv(std::ostream& o) const { csv_line(o, kernel, correction, form, target, total, rowsum, colsum); }
};

/// Momentum conservation on a periodic displaced lattice, row and column sums of Ghat there, for every kernel.
inline std::vector<MomentumRow> momentum_conservation(const std::vector<KernelType>& kernels) {
  std::vector<MomentumRow> momentum;
  for (KernelType type : kernels) {
    Kernel<1> kernel(type);
    const double h = 1.3;
    auto disc = make_discretisation(tension_lattice_1d(kernel, h, 31, true), kernel, h);
    const Eigen::VectorXd u = random_vector(disc->dofs(), 0.1, 7);
    const Eigen::VectorXd mass = WaveForm1D(disc, MomentumForm::Plus, 0.0).dof_mass();
    for (const Variant& v : variants()) {
      const auto p = provider(v);
      const Eigen::MatrixXd gh = corrected_gradient_at(*disc, *p, u);
      const double scale = gh.cwiseAbs().maxCoeff();
      const double rowsum = gh.rowwise().sum().cwiseAbs().maxCoeff() / scale;
      const double colsum = gh.colwise().sum().cwiseAbs().maxCoeff() / scale;
      for (const FormCase& fc : form_cases()) {
        if (v.correction == Correction::None && fc.target == CorrectedOperator::Both) continue;
        WaveForm1D force(disc, fc.form, 0.1, p, {.corrected = fc.target});
        Eigen::VectorXd a;
        force.acceleration(u, a);
        const double total = std::abs(mass.dot(a)) / mass.dot(a.cwiseAbs());
        momentum.push_back({kernel_name(type), v.name, momentum_form_name(fc.form),
                            v.correction == Correction::None ? "-" : corrected_operator_name(fc.target), total, rowsum,
                            colsum});
      }
    }
  }
  return momentum;
}

}  // namespace mean_polishing
