#pragma once
// cases.csv of the plate-with-hole study (issue 11, [Ismail2009, §5.4.4]): one row per static run (static_solution.hpp)
// with its case, the Newton solve, the ring and edge measures against Kirsch and Heywood's strip factor.
#include <string>

#include "plate_cases.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/plate_with_hole.hpp"
#include "static_solution.hpp"

namespace plate_hole {

using namespace sphstab;

/// Opens <out>/cases.csv and writes its header.
inline CsvWriter cases_csv(const std::string& out) {
  return CsvWriter(out + "/cases.csv", {"tag",
                                        "model",
                                        "a_over_dx",
                                        "w_over_a",
                                        "nu",
                                        "youngs_mpa",
                                        "traction_mpa",
                                        "real_particles",
                                        "all_particles",
                                        "dofs",
                                        "newton_iterations",
                                        "relative_residual",
                                        "total_force_over_SW",
                                        "peak_hoop_over_S",
                                        "peak_theta_deg",
                                        "peak_r_over_a",
                                        "kirsch_at_peak",
                                        "edge_over_S",
                                        "heywood_over_S",
                                        "peak_principal_mpa",
                                        "peak_principal_r_over_a",
                                        "max_abs_F_minus_I",
                                        "net_section_over_SW",
                                        "load_column_max_dev",
                                        "seconds"});
}

/// The row of one static run.
inline void write_case(CsvWriter& csv, const Run& run, const Outcome& o) {
  const double hw = heywood_gross_concentration(kA, run.w_over_a * kA);
  csv.row({run.tag,
           run.model,
           run.a_over_dx,
           run.w_over_a,
           run.nu,
           run.youngs,
           run.traction,
           o.real,
           o.particles,
           o.dofs,
           o.iterations,
           o.residual,
           o.total_force,
           o.peak_hoop,
           o.peak_theta,
           o.peak_r,
           o.kirsch_at_peak,
           o.edge,
           hw,
           o.peak_principal,
           o.peak_principal_r / kA,
           o.max_strain,
           o.net_section,
           o.load_column,
           o.seconds});
}

}  // namespace plate_hole
