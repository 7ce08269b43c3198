#pragma once
// The linear stability limit of the semi-discrete bar operators of the speed-vs-error study
// (include/sphstab/integrate/time_step.hpp): λ_max of A = -da/du, the leap-frog limit dt < 2 / sqrt(λ_max) and the
// Courant number C_max = dt_limit c / h it allows, the smallest real eigenvalue, the CFL step of the runs and the
// discrete first moment m1 of the strain operator at mid-bar (the SPH wave speed is m1 c), for the total-Lagrangian
// forms at n = 200 and the largest n; the rows of stability.csv.
#include <string>
#include <vector>

#include "bar_formulations.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"

namespace speed_error {

/// One case of stability.csv, as the summary uses it.
struct StabRow {
  std::string key;  // kernel | h/dx | boundary | formulation, as in stability.csv
  int n;
  double lambda_max, min_re, courant_max, m1;
};

inline CsvWriter stability_table(const std::string& out) {
  return CsvWriter(out + "/stability.csv",
                   {"kernel", "h_over_dx", "boundary", "formulation", "n", "method", "lambda_max", "dominant_re",
                    "dominant_im", "min_re", "dt_limit", "courant_max", "dt_cfl", "m1_interior"});
}

/// The stability limits of one configuration at n = 200 and n = ns.back() (once if that is 200), written to
/// stability.csv and appended to `rows`.
inline void stability_limits(CsvWriter& csv, std::vector<StabRow>& rows, KernelType kt, double hr, BarBoundary bnd,
                             const Formulation& form, const std::vector<int>& ns, double courant, double c) {
  // Linear stability limit of the semi-discrete operator (TL forms; UL linearised at u = 0 and XSPH share
  // tl-plain's operator).
  std::vector<int> n_stab = {200};
  if (ns.back() != 200) n_stab.push_back(ns.back());
  for (int n_st : n_stab) {
    if (form.frame != LagrangianFrame::Total || form.xsph_eps > 0) break;
    ElasticBar1D sb({.particles = n_st,
                     .kernel = kt,
                     .h_over_dx = hr,
                     .gradient = form.gradient,
                     .divergence = form.divergence,
                     .boundary = bnd});
    auto est = estimate_stability_limit(sb.system().acceleration, sb.size());
    const double m1 = (sb.strain_matrix() * sb.positions())[n_st / 2];
    csv.row({kernel_name(kt), hr, bar_boundary_name(bnd), form.name, static_cast<long>(n_st), est.method,
             est.lambda_max, est.dominant.real(), est.dominant.imag(), est.min_real, est.dt_limit,
             est.dt_limit * c / sb.h(), cfl_time_step(courant, sb.h(), c), m1});
    rows.push_back({kernel_name(kt) + " | " + format_csv_cell(hr) + " | " + bar_boundary_name(bnd) + " | " + form.name,
                    n_st, est.lambda_max, est.min_real, est.dt_limit * c / sb.h(), m1});
  }
}

}  // namespace speed_error
