#pragma once
// The 2D runs of the Swegle study [Powell2012, ch. 4 §2.2, Figs. 4.1/4.2]: one run of a formulation at a volume
// strain xi (growth/swegle_run.hpp: leap-frog until t_end or max |u| > 0.1 dx, fitted KE growth rate) next to the
// linear theory of the same force function (linear_theory.hpp), at the lattice or, for the S-SPH runs out of
// equilibrium, at the Newton equilibrium nearby (stability/equilibrium.hpp); the verdicts (growth/stability_verdict.hpp
// classes, linear, run, agreement), the dominant wavevectors and mode snapshots (mode_shapes.hpp); the CSV files
// ke.csv, equilibrium.csv and runs.csv.

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "linear_theory.hpp"
#include "mode_shapes.hpp"
#include "sphstab/growth/growth_run.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/growth/swegle_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/swegle.hpp"
#include "sphstab/stability/equilibrium.hpp"
#include "swegle_formulations.hpp"
#include "swegle_options.hpp"

namespace swegle_study {

using namespace sphstab;
using study::sig;

struct Row {
  std::string form;
  bool xsph = false, switching = false;
  double xi = 0, strain = 0, sigma0 = 0, a0 = 0;
  bool equilibrium = true;
  std::string newton = "-";
  double ustar = kNaN;  ///< max |u*| / dx of the Newton equilibrium (out-of-equilibrium formulations)
  Linear lin, lin_star;
  double gamma_pred = kNaN;
  /// The verdict (growth/stability_verdict.hpp's classes) in the excited class at the run's state: gamma_J of
  /// u'' = a(u), gamma_M of the leap-frog map (with XSPH when the formulation smooths), against the floor.
  std::string verdict = "n/a";
  double gamma_j = kNaN, gamma_m = kNaN;
  GrowthRun run;
  double ratio = kNaN;
  std::string lin_verdict, run_verdict, agreement;
  ModeK k_mode, k_run;
  double wall = 0;
};

/// One Swegle run of formulation f at volume strain xi and the linear analysis of the same force function; appends
/// to ke.csv and (out of equilibrium) equilibrium.csv, writes mode snapshots; prints a progress line.
inline Row run_2d_case(const Formulation& f, double xi, const Config& c, const Classes& classes, double dt,
                       CsvWriter& ke_csv, CsvWriter& eq_csv, const std::string& progress) {
  const auto t0 = study::Clock::now();
  Row r{.form = f.name, .xsph = f.xsph, .switching = f.switching, .xi = xi};
  const SwegleScene scene = make_swegle_scene({.area_ratio = xi});
  const double dx = scene.options.spacing;
  r.strain = scene.prestrain.strain;
  r.sigma0 = scene.prestrain.stress(scene.material)(0, 0);
  const std::shared_ptr<ForceFunction> force = f.make(scene);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(force->dofs());
  Eigen::VectorXd a;
  force->acceleration(zero, a);
  r.a0 = a.cwiseAbs().maxCoeff();
  // In equilibrium when the imbalance is far below the perturbation's accelerations (omega v0 ~ 5e-9).
  r.equilibrium = r.a0 <= 1e-12;
  r.lin = analyse(*force, zero, classes, f.xsph, dt);
  r.gamma_pred = f.xsph ? r.lin.gamma_map : r.lin.gamma_exc;
  if (!r.equilibrium) {
    // Not in equilibrium at the lattice (symmetrised S-SPH in tension): find the nearby equilibrium u*, which the
    // run (damped by XSPH) approaches; the linear prediction is taken there.
    const double scale = std::abs(r.sigma0) / (scene.material.density() * dx);
    const Equilibrium eq =
        find_equilibrium(*force, zero, {.max_iterations = 15, .accel_scale = scale, .load_steps = 4});
    r.newton = eq.status == Status::Successful ? "converged" : eq.message;
    double ga = kNaN, gm = kNaN, ge = kNaN;
    if (eq.status == Status::Successful) {
      r.ustar = eq.u.cwiseAbs().maxCoeff() / dx;
      r.lin_star = analyse(*force, eq.u, classes, f.xsph, dt);
      ge = r.lin_star.gamma_exc;
      gm = r.lin_star.gamma_map;
      ga = r.lin_star.gamma_all;
      r.gamma_pred = f.xsph ? gm : ge;
    } else {
      r.gamma_pred = kNaN;
    }
    eq_csv.row({f.name, xi, r.a0, r.newton, eq.iterations, eq.residual, r.ustar, r.lin.gamma_exc, ge, gm, ga});
  }
  {
    const Linear& L = r.equilibrium ? r.lin : r.lin_star;
    r.gamma_j = L.gamma_exc;
    r.gamma_m = L.gamma_map;
    if (std::isfinite(r.gamma_j) && std::isfinite(r.gamma_m) && !(f.switching && r.sigma0 == 0))
      r.verdict = verdict_letter(classify_verdict(r.gamma_j, r.gamma_m, c.detect));
  }
  SwegleRunOptions ro;
  ro.t_end = c.t_end;
  ro.run.record_every = c.record_every;
  ro.run.xsph = f.xsph;
  ro.run.reference_time = r.equilibrium ? 0.0 : 1.0;  // out of equilibrium: KE reference = response in 1 us
  ro.run.window.envelope_time = 1.0;  // follow the bottom of XSPH-damped KE (>= the slowest period, ~0.7 us)
  r.run = run_swegle(scene, force, ro);
  const ExponentialGrowthFit& fit = r.run.fit;
  if (fit.grew && r.gamma_pred > 0) r.ratio = fit.gamma / r.gamma_pred;
  r.lin_verdict = f.switching && r.sigma0 == 0 ? "switching surface" : linear_verdict(r.gamma_pred, c.detect);
  // "late growth": no qualifying window, but after the bottom of the XSPH-damped transient log KE rises steadily
  // (fit r^2 > 0.9) by more than a factor 3 -- a growth too slow to reach the onset within the run.
  const bool late = !fit.grew && fit.gamma_late > 0 && fit.late.r2 > 0.9 && fit.late_ratio > 3;
  if (r.run.blew_up())
    r.run_verdict = "blow-up";
  else
    r.run_verdict = fit.grew ? "growth" : (late ? "late growth" : "bounded");
  const bool lin_unstable = r.lin_verdict == "unstable";
  const bool run_unstable = r.run_verdict != "bounded";
  if (late && r.gamma_pred > 0) r.ratio = fit.gamma_late / r.gamma_pred;
  if (r.lin_verdict == "n/a" || r.lin_verdict == "switching surface")
    r.agreement = "n/a";
  else if (r.lin_verdict == "weakly unstable")
    r.agreement = run_unstable ? "agree" : "below detection";
  else
    r.agreement = lin_unstable == run_unstable
                      ? "agree"
                      : (run_unstable ? "run grows, linear stable" : "linear unstable, run bounded");
  r.k_mode = mode_k(r.lin.mode, scene);
  const Eigen::VectorXd& ur =
      r.run.u_linear.size() && r.run.u_linear.cwiseAbs().maxCoeff() > 0 ? r.run.u_linear : r.run.u_end;
  r.k_run = mode_k(ur, scene);
  // Mode snapshots: every disagreement, and the tension/compression extremes of formulations whose excited
  // class is linearly unstable there (run displacement in the linear regime next to the linear mode).
  const bool key = f.name == "sph" || f.name == "ncsph" || f.name == "cij" || f.name == "conservative";
  const bool extreme = key && (xi == c.xis.front() || xi == c.xis.back()) && r.lin.gamma_exc > 1e-3;
  if ((r.agreement != "agree" && r.agreement != "n/a") || extreme) {
    char tag[64];
    std::snprintf(tag, sizeof(tag), "%s_xi%.2f", f.name.c_str(), xi);
    if (ur.size() && ur.cwiseAbs().maxCoeff() > 0)
      write_mode_vtp(c.out + "/modes/" + tag + "_run.vtp", scene, ur, "displacement");
    if (r.lin.mode.size()) write_mode_vtp(c.out + "/modes/" + tag + "_linear.vtp", scene, r.lin.mode, "mode");
  }
  // KE series (every 4th sample, 20 steps = 0.13 us, keeps the file small; the fit used all of them)
  for (std::size_t k = 0; k < r.run.t.size(); k += 4)
    ke_csv.row({f.name, xi, r.run.t[k], r.run.kinetic[k], r.run.max_displacement[k]});
  r.wall = study::seconds_since(t0);
  std::printf("%s %-15s xi = %.2f: %-9s t = %6.3g  gamma meas %-8s pred %-8s ratio %-6s (%s; %.1f s)\n",
              progress.c_str(), f.name.c_str(), xi, r.run_verdict.c_str(), r.run.t_stop,
              sig(late ? fit.gamma_late : fit.gamma, 4).c_str(), sig(r.gamma_pred, 4).c_str(), sig(r.ratio, 3).c_str(),
              r.agreement.c_str(), r.wall);
  std::fflush(stdout);
  return r;
}

inline void write_runs_csv(const std::string& path, const std::vector<Row>& rows) {
  // clang-format off
  CsvWriter csv(path, {"formulation", "xsph", "xi", "prestrain", "sigma0", "a0_max", "in_equilibrium", "status",
                       "t_stop", "steps", "dt", "t_linear_end", "grew", "gamma_measured", "fit_t_begin", "fit_t_end",
                       "fit_r2", "ke_max_ratio", "gamma_bound", "gamma_late", "late_r2", "late_ratio",
                       "gamma_linear_all", "gamma_linear_excited", "mu_excited_re", "mu_excited_im", "gamma_map",
                       "gamma_predicted", "ratio", "linear_verdict", "run_verdict", "agreement", "verdict",
                       "verdict_gamma_j", "verdict_gamma_m", "commutation_error",
                       "asymmetry", "colours", "mode_kx", "mode_ky", "run_kx", "run_ky", "run_k_peak_fraction",
                       "run_x_share", "max_abs_ustar_over_dx", "wall_seconds"});
  for (const Row& r : rows)
    csv.row({r.form, r.xsph ? 1 : 0, r.xi, r.strain, r.sigma0, r.a0, r.equilibrium ? 1 : 0,
             run_status_name(r.run.status), r.run.t_stop, r.run.steps, r.run.dt, r.run.t_linear_end,
             r.run.fit.grew ? 1 : 0, r.run.fit.gamma, r.run.fit.fit.t_begin, r.run.fit.fit.t_end, r.run.fit.fit.r2,
             r.run.fit.max_ratio, r.run.fit.gamma_bound, r.run.fit.gamma_late, r.run.fit.late.r2, r.run.fit.late_ratio,
             r.lin.gamma_all, r.lin.gamma_exc, r.lin.mu_exc.real(), r.lin.mu_exc.imag(), r.lin.gamma_map,
             r.gamma_pred, r.ratio, r.lin_verdict, r.run_verdict, r.agreement, r.verdict, r.gamma_j, r.gamma_m,
             r.lin.commutation, r.lin.asymmetry,
             r.lin.colours, r.k_mode.kx, r.k_mode.ky, r.k_run.kx, r.k_run.ky, r.k_run.peak, r.k_run.x_share, r.ustar,
             r.wall});
  // clang-format on
}

/// Every (formulation, xi) run; writes ke.csv, equilibrium.csv, runs.csv and modes/.
inline std::vector<Row> run_2d(const std::vector<Formulation>& forms, const Config& c, const Classes& classes,
                               double dt) {
  CsvWriter ke_csv(c.out + "/ke.csv", {"formulation", "xi", "t", "kinetic", "max_abs_u"});
  CsvWriter eq_csv(c.out + "/equilibrium.csv",
                   {"formulation", "xi", "a0_max", "newton", "iterations", "residual", "max_abs_ustar_over_dx",
                    "gamma_exc_lattice", "gamma_exc_ustar", "gamma_map_ustar", "gamma_all_ustar"});
  std::vector<Row> rows;
  const int total = static_cast<int>(forms.size() * c.xis.size());
  char progress[32];
  for (const Formulation& f : forms)
    for (double xi : c.xis) {
      std::snprintf(progress, sizeof progress, "[%2d/%2d]", static_cast<int>(rows.size()) + 1, total);
      rows.push_back(run_2d_case(f, xi, c, classes, dt, ke_csv, eq_csv, progress));
    }
  write_runs_csv(c.out + "/runs.csv", rows);
  return rows;
}

}  // namespace swegle_study
