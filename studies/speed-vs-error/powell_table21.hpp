#pragma once
// The comparison with the "Reference" row of [Powell2012, Table 2.1]: the cases (SPH, XSPH in both hook modes
// [Powell2012, (2.71)], [Monaghan1989], the corrected gradient and corrected + XSPH, with Powell's SPH, XSPH, NCSPH
// and NCXSPH errors) and their runs on Powell's 8 cm bar, the mean relative velocity error (2.72) at particle 80;
// the rows of powell.csv.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "bar_formulations.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/bar_wave_exact.hpp"

namespace speed_error {

struct PowellCase {
  std::string name;
  Formulation form;
  double eps;
  VelocityHookMode mode;
  double powell_pct;
  std::string powell_label;
};

inline std::vector<PowellCase> powell_cases() {
  const auto& F = formulations();
  return {{"SPH (tl-plain)", F[0], 0.0, VelocityHookMode::DriftOnly, 0.3474, "SPH"},
          {"SPH (ul-plain)", F[4], 0.0, VelocityHookMode::DriftOnly, 0.3474, "SPH"},
          {"SPH (ul-minus-plus)", F[5], 0.0, VelocityHookMode::DriftOnly, 0.3474, "SPH"},
          {"XSPH drift-only (tl-plain)", F[0], 0.1, VelocityHookMode::DriftOnly, 0.0300, "XSPH"},
          {"XSPH replace (tl-plain)", F[0], 0.1, VelocityHookMode::Replace, 0.0300, "XSPH"},
          {"corrected (tl-corrected)", F[2], 0.0, VelocityHookMode::DriftOnly, 0.2243, "NCSPH"},
          {"corrected + XSPH replace", F[2], 0.1, VelocityHookMode::Replace, 0.0056, "NCXSPH"}};
}

/// Runs every Powell case, writes <out>/powell.csv and returns "case | Powell label" -> (our %, Powell's %).
inline std::vector<std::pair<std::string, std::pair<double, double>>> powell_comparison(const std::string& out,
                                                                                        const BarJumpProblem& problem,
                                                                                        double courant, double c) {
  // Powell Table 2.1 "Reference" row, qualitatively: semi-infinite bar (8 cm, 800 particles, h = 1.3 dx, cubic
  // B-spline), mean relative velocity error (2.72) at particle 80 (x = 0.795) over 3 < t < 20 µs, where the exact
  // velocity is -0.01 cm/µs.
  CsvWriter powell_csv(out + "/powell.csv", {"case", "formulation", "xsph_eps", "xsph_mode", "mean_rel_error_pct",
                                             "powell_label", "powell_pct", "status"});
  std::vector<std::pair<std::string, std::pair<double, double>>> powell_rows;
  for (const auto& pc : powell_cases()) {
    BarJumpProblem pp = problem;
    pp.length = 8.0;
    BarJumpExact pex(pp);
    ElasticBar1D bar({.particles = 800,
                      .length = 8.0,
                      .h_over_dx = 1.3,
                      .gradient = pc.form.gradient,
                      .divergence = pc.form.divergence,
                      .frame = pc.form.frame});
    auto sys = bar_system(bar, pc.eps, pc.mode);
    Eigen::VectorXd v0(bar.size());
    for (int i = 0; i < bar.size(); ++i) v0[i] = pex.initial_velocity(bar.positions()[i]);
    LeapfrogOptions opt;
    opt.dt = cfl_time_step(courant, bar.h(), c);
    opt.t_end = 20.0;
    opt.observe_every = 1;
    opt.limits.energy_growth = 10.0;
    opt.limits.check_every = 50;
    double sum = 0;
    long count = 0;
    opt.observer = [&](const StepView& s) {
      if (s.time <= 3.0) return;
      const double ve = pex.velocity(bar.positions()[79], s.time);  // particle 80 (1-based)
      sum += std::abs(s.v[79] - ve) / std::abs(ve);
      ++count;
    };
    auto res = run_leapfrog(sys, Eigen::VectorXd::Zero(bar.size()), v0, opt);
    const double pct = res.completed() ? 100.0 * sum / count : NAN;
    powell_csv.row({pc.name, pc.form.name, pc.eps,
                    pc.eps > 0 ? (pc.mode == VelocityHookMode::Replace ? "replace" : "drift-only") : "-", pct,
                    pc.powell_label, pc.powell_pct, run_status_name(res.status)});
    powell_rows.push_back({pc.name + " | " + pc.powell_label, {pct, pc.powell_pct}});
    std::fprintf(stderr, "[speed-vs-error] Powell case %s: %.4f %% (Powell %s %.4f %%)\n", pc.name.c_str(), pct,
                 pc.powell_label.c_str(), pc.powell_pct);
  }
  return powell_rows;
}

}  // namespace speed_error
