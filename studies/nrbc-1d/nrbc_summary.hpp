#pragma once
// The key numbers of the 1D non-reflecting boundary study for summary.md.in: Powell's Table 2.1 (x 10^2, X for
// unstable) [Powell2012, ch. 2 §3.1] beside ours for every variant with the agreement of the X pattern, the references
// without viscosity, the step limits and the spectral radius at the table's CFL (step_limits.hpp), and the h-study of
// Fig. 2.12, as Markdown rows.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "bar_problem.hpp"
#include "bar_run.hpp"
#include "common/study.hpp"
#include "step_limits.hpp"
#include "study_cases.hpp"

namespace nrbc1d {

// Powell's Table 2.1 (x 10^2); NaN: X (unstable).
constexpr double kPaper[7][4] = {{0.3474, 0.0300, 0.2243, 0.0056}, {5.9729, 1.3790, 3.2605, 0.8531},
                                 {1.5015, 0.1808, 1.3068, 0.0867}, {1.7273, 0.0763, 1.5451, 0.0726},
                                 {NAN, 0.1401, 7.5314, 0.0733},    {NAN, NAN, NAN, 13.7708},
                                 {30.9198, 3.0328, 1.2380, 0.1078}};

/// The run of the case among runs (the reference's timing flag is moot).
inline const BarRun& find_run(const std::vector<BarRun>& runs, Form f, int particles, int layers, bool upwind,
                              bool half, double c, bool mirror = true,
                              ViscositySwitch viscosity = ViscositySwitch::Compression) {
  for (const BarRun& r : runs)
    if (r.c.form == f && r.c.particles == particles && r.c.layers == layers && r.c.upwind == upwind &&
        (particles == 800 || r.c.half_step == half) && r.c.mirror == mirror && r.c.viscosity == viscosity &&
        r.c.cfl == c)
      return r;
  throw std::logic_error("missing case");
}

inline std::string cell(const BarRun& r) { return r.stable ? study::sig(100 * r.error, 3) : std::string("X"); }
inline std::string paper_cell(double v) { return std::isnan(v) ? std::string("X") : study::sig(v, 5); }

/// Table 2.1 of every variant beside Powell's (key, key_x_agree) and the references without viscosity
/// (table_inviscid).
inline void summarise_table(study::Summary& sum, const std::vector<BarRun>& runs, const std::vector<Variant>& variants,
                            double cfl) {
  const auto row_run = [&](int row, int k, const Variant& v) -> const BarRun& {
    return row == 0   ? find_run(runs, kForms[k], 800, 0, false, v.half, v.cfl, v.mirror)
           : row == 6 ? find_run(runs, kForms[k], 100, 8, true, v.half, v.cfl, v.mirror)
                      : find_run(runs, kForms[k], 100, row, false, v.half, v.cfl, v.mirror);
  };
  for (const Variant& v : variants) {
    std::string md;
    int agree = 0;  // the X pattern of the truncated rows against Powell's, cell by cell
    for (int row = 0; row < 7; ++row) {
      std::vector<std::string> cells = {row == 0 ? "Reference" : row == 6 ? "Upwind (8)" : std::to_string(row)};
      for (int k = 0; k < 4; ++k) {
        const BarRun& r = row_run(row, k, v);
        cells.push_back(cell(r) + " (" + paper_cell(kPaper[row][k]) + ")");
        if (row > 0) agree += r.stable == !std::isnan(kPaper[row][k]);
      }
      study::md_row(md, cells);
    }
    sum.set(v.key, md);
    sum.set(std::string(v.key) + "_x_agree", agree);
  }
  {
    std::string md;
    std::vector<std::string> cells = {"Reference without viscosity"};
    for (int k = 0; k < 4; ++k)
      cells.push_back(cell(find_run(runs, kForms[k], 800, 0, false, true, cfl, true, ViscositySwitch::Off)) + " (" +
                      paper_cell(kPaper[0][k]) + ")");
    study::md_row(md, cells);
    sum.set("table_inviscid", md);
  }
}

/// The step limits (runs / undamped / damped linearisation, dt_limit) and the spectral radius - 1 at the table's CFL
/// (step_radius), per timing and row of Table 2.1.
inline void summarise_step_limits(study::Summary& sum, const StepLimits& s) {
  const std::vector<BarCase>& limit_cases = s.cases;
  const std::size_t nl = limit_cases.size();
  std::string md;
  for (bool half : {true, false}) {
    for (int row = 0; row < 7; ++row) {
      std::vector<std::string> cells = {std::string(half ? "half" : "whole"), row == 0   ? "Reference"
                                                                              : row == 6 ? "Upwind (8)"
                                                                                         : std::to_string(row)};
      for (Form f : kForms)
        for (std::size_t k = 0; k < limit_cases.size(); ++k) {
          const BarCase& c = limit_cases[k];
          const bool match = c.form == f && c.half_step == half &&
                             (row == 0   ? c.particles == 800
                              : row == 6 ? c.upwind
                                         : c.particles == 100 && !c.upwind && c.layers == row);
          if (match)
            cells.push_back(study::sig(s.limits[k], 3) + " / " + study::sig(s.linear_off[k], 3) + " / " +
                            study::sig(s.linear_on[k], 3));
        }
      study::md_row(md, cells);
    }
  }
  sum.set("dt_limit", md);
  std::string rmd;  // spectral radius - 1 at the table's CFL, undamped / damped
  for (bool half : {true, false})
    for (int layers : {1, 2, 3, 4, 5, 8}) {
      std::vector<std::string> cells = {half ? "half" : "whole", layers == 8 ? "Upwind (8)" : std::to_string(layers)};
      for (Form f : kForms)
        for (std::size_t k = 0; k < nl; ++k) {
          const BarCase& c = limit_cases[k];
          if (c.form == f && c.half_step == half && c.particles == 100 && c.layers == layers)
            cells.push_back(study::sig(s.radius_off[k] - 1, 2) + " / " + study::sig(s.radius_on[k] - 1, 2));
        }
      study::md_row(rmd, cells);
    }
  sum.set("step_radius", rmd);
}

/// Fig. 2.12 (h_study): per h / dx the layers and the errors of the reference and the half and whole timings.
inline void summarise_h_study(study::Summary& sum, const std::vector<BarRun>& hruns) {
  std::string md;
  for (std::size_t k = 0; k < hruns.size(); k += 3) {
    const BarRun &ref = hruns[k], &half = hruns[k + 1], &whole = hruns[k + 2];
    study::md_row(md,
                  {study::sig(ref.c.h_over_dx, 3), std::to_string(half.c.layers), cell(ref), cell(half), cell(whole)});
  }
  sum.set("h_study", md);
}

}  // namespace nrbc1d
