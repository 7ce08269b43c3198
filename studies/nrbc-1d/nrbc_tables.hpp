#pragma once
// The CSV tables of the 1D non-reflecting boundary study: table.csv and cfl_sweep.csv (one row per run: case, status,
// mean error (2.72), steps), series/<tag>.csv (v at particle 80 and the exact value), dt_limit.csv (step_limits.hpp)
// and h_study.csv (Fig. 2.12).
#include <algorithm>
#include <string>
#include <vector>

#include "bar_problem.hpp"
#include "bar_run.hpp"
#include "sphstab/io/csv.hpp"
#include "step_limits.hpp"

namespace nrbc1d {

/// table.csv or cfl_sweep.csv: one row per run.
inline void write_table(const std::string& path, const std::vector<BarRun>& runs) {
  CsvWriter w(path, {"form", "particles", "layers", "upwind", "timing", "h_over_dx", "cfl", "viscosity", "mirror",
                     "status", "mean_error", "steps"});
  for (const BarRun& r : runs)
    w.row({form_name(r.c.form), r.c.particles, r.c.layers, r.c.upwind ? 1 : 0, r.c.half_step ? "half" : "whole",
           r.c.h_over_dx, r.c.cfl, r.c.viscosity == ViscositySwitch::Compression ? 1 : 0, r.c.mirror ? 1 : 0, r.status,
           r.error, r.steps});
}

/// series/<tag>.csv of every run: t, v at particle 80 and the exact value.
inline void write_series(const std::string& out, const std::vector<BarRun>& runs) {
  for (const BarRun& r : runs) {
    CsvWriter w(out + "/series/" + tag_of(r.c) + ".csv", {"t", "v80", "exact"});
    const std::size_t every = std::max<std::size_t>(1, r.t.size() / 400);  // plots need ~400 points, not every step
    for (std::size_t k = 0; k < r.t.size(); k += every) w.row({r.t[k], r.v[k], exact_velocity(0.795, r.t[k])});
  }
}

inline void write_dt_limit(const std::string& out, const StepLimits& s) {
  CsvWriter w(out + "/dt_limit.csv",
              {"form", "particles", "layers", "upwind", "timing", "max_stable_cfl", "linear_max_cfl_undamped",
               "linear_max_cfl_damped", "step_radius_at_cfl_undamped", "step_radius_at_cfl_damped"});
  for (std::size_t k = 0; k < s.cases.size(); ++k) {
    const BarCase& c = s.cases[k];
    w.row({form_name(c.form), c.particles, c.layers, c.upwind ? 1 : 0, c.half_step ? "half" : "whole", s.limits[k],
           s.linear_off[k], s.linear_on[k], s.radius_off[k], s.radius_on[k]});
  }
}

/// h_study.csv from the runs of h_cases (study_cases.hpp): reference, half, whole per h / dx.
inline void write_h_study(const std::string& out, const std::vector<BarRun>& hruns) {
  CsvWriter w(out + "/h_study.csv",
              {"h_over_dx", "layers", "reference_error", "half_error", "half_status", "whole_error", "whole_status"});
  for (std::size_t k = 0; k < hruns.size(); k += 3) {
    const BarRun &ref = hruns[k], &half = hruns[k + 1], &whole = hruns[k + 2];
    w.row({ref.c.h_over_dx, half.c.layers, ref.error, half.error, half.status, whole.error, whole.status});
  }
}

}  // namespace nrbc1d
