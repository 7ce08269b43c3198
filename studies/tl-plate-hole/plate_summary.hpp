#pragma once
// The key numbers of the plate-with-hole study for summary.md.in (issue 11, [Ismail2009, §5.4.4]), assembled from the
// static runs (static_solution.hpp) and the suddenly loaded ones (dynamic_load.hpp): the Markdown tables of the
// resolution study, the width study (with the lumped load), Ismail's case and the dynamic runs; the observed order of
// the edge value and the log-log slope of the first-ring peak's error against Kirsch.
#include <cmath>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "dynamic_load.hpp"
#include "plate_cases.hpp"
#include "sphstab/problems/plate_with_hole.hpp"
#include "static_solution.hpp"

namespace plate_hole {

using namespace sphstab;

struct PlateSummary {
  std::string md_lin, md_w, md_is, md_dyn;
  std::vector<double> res_dx, res_edge, res_peak_err;  ///< the resolution study (W/a = 5, consistent load)

  /// The row of a static run: resolution or width table (linear runs), or Ismail's case.
  void add_static(const Run& run, const Outcome& o) {
    const double hw = heywood_gross_concentration(kA, run.w_over_a * kA);
    const std::vector<std::string> common{study::sig(run.a_over_dx), study::sig(run.w_over_a), std::to_string(o.real),
                                          std::to_string(o.iterations), study::sig(o.residual, 2)};
    if (run.tag.rfind("linear", 0) == 0) {
      std::vector<std::string> row = common;
      for (const std::string& c :
           {study::fixed(o.total_force, 4), study::fixed(o.peak_hoop, 3), study::fixed(o.peak_r, 3),
            study::fixed(o.peak_theta, 1), study::fixed(o.kirsch_at_peak, 3), study::fixed(o.edge, 3),
            study::fixed(hw, 3), study::fixed(o.net_section, 4), std::string(run.lumped ? "lumped" : "consistent"),
            study::fixed(o.load_column, 4), study::fixed(o.seconds, 1)})
        row.push_back(c);
      const bool resolution = run.w_over_a == 5 && !run.lumped;
      study::md_row(resolution ? md_lin : md_w, row);
      if (resolution) {
        res_dx.push_back(kA / run.a_over_dx);
        res_edge.push_back(o.edge);
        res_peak_err.push_back(o.peak_hoop - o.kirsch_at_peak);
      }
    } else {
      std::vector<std::string> row{run.model,
                                   study::sig(run.a_over_dx),
                                   std::to_string(run.steps),
                                   std::to_string(o.iterations),
                                   study::sig(o.residual, 2),
                                   study::fixed(o.max_strain, 3),
                                   study::fixed(o.peak_hoop * run.traction, 2),
                                   study::fixed(o.peak_hoop, 3),
                                   study::fixed(o.peak_principal, 2),
                                   study::fixed(o.peak_principal / run.traction, 3),
                                   study::fixed(o.seconds, 1)};
      study::md_row(md_is, row);
    }
  }

  /// The row of a suddenly loaded run; dt in units of the transit time W / c_s (c_s = sqrt(mu / rho), rho = 1, W = 5).
  void add_dynamic(const Run& run, const DynamicOutcome& d) {
    study::md_row(md_dyn, {study::sig(run.a_over_dx),
                           study::sig(d.dt * std::sqrt(ElasticMaterial::from_young_poisson(70, 0.49, 1.0).mu()) / 5, 3),
                           std::to_string(d.steps), d.end, study::fixed(d.peak_hole, 2), study::fixed(d.peak_time, 2),
                           study::fixed(d.peak_all, 2)});
  }

  /// Observed order of the edge value: successive differences of the W/a = 5 sequence (dx halves); "-" without three.
  std::string edge_orders() const {
    std::string orders;
    for (std::size_t k = 0; k + 2 < res_edge.size(); ++k) {
      const double p = std::log(std::abs(res_edge[k] - res_edge[k + 1]) / std::abs(res_edge[k + 1] - res_edge[k + 2])) /
                       std::log(2.0);
      orders += (orders.empty() ? "" : ", ") + study::sig(p, 3);
    }
    return orders.empty() ? "-" : orders;
  }

  /// The tables and the convergence numbers into `summary`.
  void put(study::Summary& summary) const {
    summary.set("dynamic", md_dyn);
    summary.set("orders_edge", edge_orders());
    summary.set("slope_peak_error", study::loglog_slope(res_dx, res_peak_err), 3);
    summary.set("linear", md_lin);
    summary.set("width", md_w);
    summary.set("ismail", md_is);
  }
};

}  // namespace plate_hole
