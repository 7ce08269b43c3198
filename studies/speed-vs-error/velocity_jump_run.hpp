#pragma once
// One run of the speed-vs-error sweep: the velocity-jump problem [Powell2012, ch. 2 §3.1, (2.68)] on the free-free
// bar, solved by leap-frog KDK with one formulation (bar_formulations.hpp), kernel, h/dx, boundary and n, and compared
// with the exact d'Alembert solution (include/sphstab/problems/bar_wave_exact.hpp):
//   - the velocity errors L1 and L2 against the exact solution (normalised by v0 and the bar length);
//   - the run itself: wall times (best of unobserved repeats for short runs), errors at t_end and their time mean,
//     momentum drift, energy change, neighbour builds, the largest displacement;
//   - its CSV rows: runs.csv, error_history.csv (while it runs) and profiles.csv (with the exact profile).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "bar_formulations.hpp"
#include "common/study.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/bar_wave_exact.hpp"

namespace speed_error {

using study::Clock;
using study::seconds_since;

/// The problem and the settings that every run of the sweep shares.
struct SweepSettings {
  BarJumpProblem problem;  ///< L = 1 cm, rho = 7.8, E = 2.1, jump at 0.35, ±0.01 cm/µs, free ends
  double t_end;            ///< µs
  double c;                ///< bar wave speed (cm/µs)
  double courant;          ///< C in dt = C h / c
};

struct RunRecord {
  std::string kernel, boundary, form;
  double h_over_dx = 0;
  int n = 0;
  double dt = 0;
  long steps = 0;
  std::string status, message;
  double setup_s = 0, run_s = 0, total_s = 0, us_per_particle_step = NAN;
  double l1 = NAN, l2 = NAN, l1_mean = NAN, momentum_error = NAN, energy_change = NAN;
  long builds = 0;
  double max_u_over_dx = NAN;  ///< max |u_i| / dx at the end (or at the blow-up)
};

/// Velocity errors over the particles, normalised by v0 = 0.01 and the bar length:
/// L1 = Σ |v_i - v(X_i, t)| V_i / (v0 L), L2 = sqrt(Σ (v_i - v(X_i, t))² V_i / L) / v0.
inline std::pair<double, double> velocity_errors(const ElasticBar1D& bar, const BarJumpExact& ex,
                                                 const Eigen::VectorXd& v, double t) {
  double l1 = 0, l2 = 0;
  const double v0 = std::abs(ex.problem().velocity_left), L = ex.problem().length;
  for (int i = 0; i < bar.size(); ++i) {
    const double e = v[i] - ex.velocity(bar.positions()[i], t);
    l1 += std::abs(e) * bar.volumes()[i];
    l2 += e * e * bar.volumes()[i];
  }
  return {l1 / (v0 * L), std::sqrt(l2 / L) / v0};
}

/// runs.csv, error_history.csv and profiles.csv (columns: see README.md).
struct RunTables {
  CsvWriter runs, history, profiles;
  explicit RunTables(const std::string& out)
      : runs(out + "/runs.csv",
             {"kernel", "h_over_dx", "boundary", "formulation", "n", "dt", "steps", "status", "setup_s", "run_s",
              "total_s", "l1_final", "l2_final", "l1_time_mean", "momentum_drift", "energy_rel_change",
              "neighbour_builds", "us_per_particle_step", "max_u_over_dx"}),
        history(out + "/error_history.csv", {"kernel", "h_over_dx", "boundary", "formulation", "n", "t", "l1", "l2"},
                false),
        profiles(out + "/profiles.csv", {"kernel", "h_over_dx", "boundary", "formulation", "n", "x", "v"}, false) {}
};

/// The exact velocity profile at t (2001 points over the bar) for the plots.
inline void write_exact_profile(CsvWriter& profiles, const BarJumpExact& exact, double t) {
  for (int k = 0; k <= 2000; ++k) {
    const double x = k / 2000.0;
    profiles.row({"exact", 0.0, "-", "exact", 0L, x, exact.velocity(x, t)});
  }
}

/// One runs.csv row.
inline void write_run(CsvWriter& runs, const RunRecord& rec) {
  runs.row({rec.kernel, rec.h_over_dx, rec.boundary, rec.form, static_cast<long>(rec.n), rec.dt, rec.steps, rec.status,
            rec.setup_s, rec.run_s, rec.total_s, rec.l1, rec.l2, rec.l1_mean, rec.momentum_error, rec.energy_change,
            rec.builds, rec.us_per_particle_step, rec.max_u_over_dx});
}

/// One run of the sweep; writes its error history (and, for cubic, h/dx = 1.3, n = 100 and 400, its velocity profile
/// at t_end) to `tables` while it runs, not its runs.csv row (write_run).
inline RunRecord run_case(const SweepSettings& s, KernelType kt, double hr, BarBoundary bnd, const Formulation& form,
                          int n, RunTables& tables) {
  RunRecord rec;
  rec.kernel = kernel_name(kt);
  rec.boundary = bar_boundary_name(bnd);
  rec.form = form.name;
  rec.h_over_dx = hr;
  rec.n = n;
  const auto t0 = Clock::now();
  const ElasticBarOptions o{.particles = n,
                            .kernel = kt,
                            .h_over_dx = hr,
                            .gradient = form.gradient,
                            .divergence = form.divergence,
                            .boundary = bnd,
                            .frame = form.frame};
  ElasticBar1D bar(o);
  auto sys = bar_system(bar, form.xsph_eps, VelocityHookMode::Replace);
  BarJumpProblem pf = s.problem;
  pf.velocity_left = form.amplitude;
  pf.velocity_right = -form.amplitude;
  const BarJumpExact ex(pf);
  Eigen::VectorXd u0 = Eigen::VectorXd::Zero(n), v0(n);
  for (int i = 0; i < n; ++i) v0[i] = ex.initial_velocity(bar.positions()[i]);
  rec.setup_s = seconds_since(t0);

  LeapfrogOptions opt;
  opt.dt = cfl_time_step(s.courant, bar.h(), s.c);
  opt.t_end = s.t_end;
  const long nsteps = static_cast<long>(std::ceil(s.t_end / opt.dt - 1e-9));
  opt.observe_every = static_cast<int>(std::max(1L, nsteps / 60));
  opt.record_every = 0;  // first and last only
  opt.limits.check_every = 10;
  opt.limits.max_displacement = 0.5;  // 50 x the physical displacement scale
  opt.limits.energy_growth = 10.0;
  double observe_s = 0, l1_sum = 0;
  int l1_count = 0;
  opt.observer = [&](const StepView& st) {
    const auto q0 = Clock::now();
    auto [l1, l2] = velocity_errors(bar, ex, st.v, st.time);
    if (st.step > 0) {
      l1_sum += l1;
      ++l1_count;
    }
    tables.history.row({rec.kernel, hr, rec.boundary, rec.form, static_cast<long>(n), st.time, l1, l2});
    observe_s += seconds_since(q0);
  };
  auto res = run_leapfrog(sys, u0, v0, opt);
  rec.run_s = std::max(0.0, res.wall_seconds - observe_s);
  if (rec.run_s < 0.05) {  // short runs: best of up to 5 unobserved repeats for a stable time
    LeapfrogOptions topt = opt;
    topt.observer = nullptr;
    topt.observe_every = 0;
    for (int rep = 0; rep < 5; ++rep) {
      ElasticBar1D tb(o);  // fresh UL caches
      auto tsys = bar_system(tb, form.xsph_eps, VelocityHookMode::Replace);
      rec.run_s = std::min(rec.run_s, run_leapfrog(tsys, u0, v0, topt).wall_seconds);
    }
  }
  rec.total_s = rec.setup_s + rec.run_s;
  if (res.steps > 0) rec.us_per_particle_step = 1e6 * rec.run_s / (static_cast<double>(res.steps) * n);
  rec.dt = res.dt;
  rec.steps = res.steps;
  rec.status = run_status_name(res.status);
  rec.message = res.message;
  rec.builds = bar.neighbour_builds();
  rec.max_u_over_dx = res.u.cwiseAbs().maxCoeff() / bar.spacing();
  if (res.completed()) {
    auto [l1, l2] = velocity_errors(bar, ex, res.v, res.time);
    rec.l1 = l1;
    rec.l2 = l2;
    rec.l1_mean = l1_count ? l1_sum / l1_count : NAN;
    const double p0 = bar.masses().dot(v0);
    rec.momentum_error = std::abs(bar.masses().dot(res.v) - p0) / std::abs(p0);
    const auto& h0 = res.history.front();
    const auto& h1 = res.history.back();
    rec.energy_change = (h1.total - h0.total) / h0.total;
    if (kt == KernelType::CubicSpline && hr == 1.3 && (n == 100 || n == 400))
      for (int i = 0; i < n; ++i)
        tables.profiles.row({rec.kernel, hr, rec.boundary, rec.form, static_cast<long>(n), bar.positions()[i],
                             res.v[i] * (0.01 / form.amplitude)});
  }
  return rec;
}

}  // namespace speed_error
