#pragma once
// Boundary sensitivity of the critical loads: every correction x form with the corrected divergence (the strain for
// the conservative form) at N = n, cubic, h = 1.3 dx, with fixed layers only ONE support thick (the plain
// `sphstab tcrit` lattice), where the corrections' neighbours of neighbours reach incomplete neighbourhoods and u = 0
// need not be an equilibrium; thin_layers.csv.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "correction_cases.hpp"
#include "csv_cells.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace mean_polishing {

using namespace sphstab;

/// One row of thin_layers.csv: a correction and form.
struct ThinRow {
  std::string correction, form, target;
  double residual, asymmetry, t_first, t_second, t_compression;
  std::string first, second;

  static constexpr const char* kCsvHeader =
      "correction,form,corrected_operator,equilibrium_residual,asymmetry,criterion,tcrit,second_criterion,"
      "tcrit_second,tcrit_compression";
  void csv(std::ostream& o) const {
    csv_line(o, correction, form, target, residual, asymmetry, first, t_first, second, t_second, t_compression);
  }
};

/// Boundary sensitivity: the critical loads at N = n, cubic, h = 1.3, with fixed layers only ONE support thick.
inline std::vector<ThinRow> thin_layers(int n) {
  std::vector<ThinRow> thin;
  Kernel<1> kernel(KernelType::CubicSpline);
  const double h = 1.3;
  auto disc = make_discretisation(tension_lattice_1d(kernel, h, n), kernel, h);
  const Eigen::MatrixXd x = disc->free_positions();
  for (const Variant& v : variants())
    for (const FormCase& fc : form_cases()) {
      if (fc.target == CorrectedOperator::Both) continue;
      WaveForm1D force(disc, fc.form, 0.0, provider(v), {.corrected = fc.target});
      const ForceCriticalLoad t = force_critical_loads(force, LoadDirection::Tension, x);
      const auto c = critical_loads(t.jacobian, LoadDirection::Compression);
      const CriticalLoad& r0 = t.results.front();
      thin.push_back({v.name, momentum_form_name(fc.form),
                      v.correction == Correction::None ? "-" : corrected_operator_name(fc.target), t.residual_relative,
                      std::max(r0.asymmetry0, r0.asymmetry1), r0.load, t.results.size() > 1 ? t.results[1].load : NAN,
                      c.front().load, criterion_name(r0.criterion),
                      t.results.size() > 1 ? criterion_name(t.results[1].criterion) : "-"});
    }
  return thin;
}

}  // namespace mean_polishing
