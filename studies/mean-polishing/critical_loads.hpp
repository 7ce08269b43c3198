#pragma once
// The critical loads of the mean-polishing study: for one kernel, h/dx, correction and form x corrected operator on
// the 1D pre-tensioned bar u_tt = (u_x + T)_x at u = 0, the exact A(T) = A0 + T A1 by complex step through the
// correction ([SquireTrapp1998]) and its critical loads in tension and compression by every criterion that applies
// (stability/critical_load.hpp: definiteness for a symmetric A, else the spectrum and symmetric-part criteria,
// [Powell2012, Theorem 3.1]); the sweep over N = n (h/dx grid) and the size check N = n_check (h/dx = 1.3, 2.0), and
// tcrit.csv.
#include <Eigen/Core>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "correction_cases.hpp"
#include "csv_cells.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace mean_polishing {

using namespace sphstab;
using study::Clock;
using study::seconds_since;
using study::sig;

/// One row of tcrit.csv: a case x direction x criterion.
struct Row {
  int n;
  std::string kernel;
  double h;
  std::string correction, form, target, strain_sum, direction, criterion;
  double tcrit, growth, mode_k, a1_rel, asym0, asym1, residual;
  std::string status, reason;
  double seconds;

  static constexpr const char* kCsvHeader =
      "N,kernel,h_over_dx,correction,form,corrected_operator,strain_sum,direction,criterion,tcrit,growth_2tcrit,"
      "mode_k_over_pi,a1_relative,asymmetry_T0,asymmetry_T1,equilibrium_residual,status,seconds,reason";
  void csv(std::ostream& o) const {
    csv_line(o, n, kernel, h, correction, form, target, strain_sum, direction, criterion, tcrit, growth, mode_k, a1_rel,
             asym0, asym1, residual, status, seconds, "\"" + reason + "\"");
  }
};

/// The critical loads of one case, appended to rows (one row per direction and criterion).
inline void run_case(int n, KernelType type, double h, const Variant& v, const FormCase& fc, std::vector<Row>& rows) {
  Kernel<1> kernel(type);
  auto disc = make_discretisation(tension_lattice_1d(kernel, h, n, false, kLayerSupports), kernel, h);
  const auto t0 = Clock::now();
  WaveForm1D force(disc, fc.form, 0.0, provider(v), {.corrected = fc.target});
  const ForceCriticalLoad tension = force_critical_loads(force, LoadDirection::Tension, disc->free_positions());
  const std::vector<CriticalLoad> compression = critical_loads(tension.jacobian, LoadDirection::Compression);
  const double seconds = seconds_since(t0);
  const std::string target = v.correction == Correction::None                           ? "-"
                             : force.strain_corrected() && force.divergence_corrected() ? "both"
                             : force.strain_corrected()                                 ? "strain"
                                                                                        : "divergence";
  const std::string strain_sum =
      force.strain_corrected() ? (force.strain_sum() == StrainSum::Direct ? "direct" : "difference") : "plain";
  for (const auto* list : {&tension.results, &compression})
    for (const CriticalLoad& r : *list)
      rows.push_back({n, kernel_name(type), h, v.name, momentum_form_name(fc.form), target, strain_sum,
                      load_direction_name(r.direction), criterion_name(r.criterion), r.load, r.growth_rate,
                      r.reported_wavenumber().k_projection, r.a1_relative, r.asymmetry0, r.asymmetry1,
                      tension.residual_relative, status_name(r.status), r.reason, seconds});
}

/// The rows of tcrit.csv and the time spent in the dense corrected conservative cases of the size check.
struct CriticalLoadSweep {
  std::vector<Row> rows;
  double dense_conservative_seconds = 0;
};

/// Critical loads, N = n sweep over hs and N = n_check check at h/dx = 1.3 and 2.0, for every kernel, correction and
/// form x corrected operator; prints a progress line per kernel and h.
inline CriticalLoadSweep critical_load_sweep(int n, int n_check, const std::vector<double>& hs,
                                             const std::vector<KernelType>& kernels) {
  std::vector<Row> rows;
  double dense_conservative_seconds = 0;
  for (const auto& [size, h_list] : {std::pair{n, hs}, std::pair{n_check, std::vector<double>{1.3, 2.0}}})
    for (KernelType type : kernels)
      for (double h : h_list) {
        const auto t0 = Clock::now();
        for (const Variant& v : variants())
          for (const FormCase& fc : form_cases()) {
            if (v.correction == Correction::None && fc.target == CorrectedOperator::Both) continue;
            // The dense corrected conservative forms cost O(N^4) through the nested derivatives (dual passes inside
            // complex steps): about 10-30 s each at N = 120.
            const bool dense_cons = correction_is_dense(v.correction) && fc.form == MomentumForm::Conservative;
            const auto tc = Clock::now();
            run_case(size, type, h, v, fc, rows);
            if (size == n_check && dense_cons) dense_conservative_seconds += seconds_since(tc);
          }
        std::cout << "N=" << size << " " << kernel_name(type) << " h=" << h << " (" << sig(seconds_since(t0), 2)
                  << " s)" << std::endl;
      }
  return {std::move(rows), dense_conservative_seconds};
}

}  // namespace mean_polishing
