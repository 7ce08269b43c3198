#pragma once
// The quasi-static run of the tl-neo-hookean-1d study, Ismail (2009) §5.3: both ends' fixed layers of the bar
// (neo_hookean_bar.hpp) carry u = (lambda(t) - 1) X, lambda(t) ramped smoothly 1 -> 6 over a number of small-strain
// transit times L / c_L, leap-frog from rest; the centre particle's T11 against the analytic curve, the spread of F
// over the free particles (the departure from the homogeneous stretch), and the history CSV of one run.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "neo_hookean_bar.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/run.hpp"
#include "sphstab/integrate/run_observer.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"

namespace nh1d {

/// Smooth ramp 0 -> 1 over tau in [0, 1] with zero velocity at both ends.
inline double ramp(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau - std::sin(2 * std::numbers::pi * tau) / (2 * std::numbers::pi);
}

struct QuasiStaticRun {
  std::vector<double> t11_at;         // centre T11 when lambda(t) first reaches each table stretch
  double departure = std::nan("");    // imposed stretch at which the F spread exceeds the threshold
  double spread_before_lambda = 3.5;  // the spread max F - min F when lambda(t) last was <= this
  double spread_before = std::nan("");
  std::string end = "completed";
  long steps = 0;
  double dt = 0, t_load = 0;
};

/// One run, its history written to <out>/history_nu<nu>_ramp<ramp_transits><suffix>.csv.
inline QuasiStaticRun quasi_static_run(Bar& bar, double nu, double ramp_transits, const std::vector<double>& stretches,
                                       double spread_threshold, const std::string& out,
                                       const std::string& suffix = "") {
  QuasiStaticRun r;
  r.t_load = ramp_transits * kLength / bar.c_l();
  // leap-frog limit 2 / sqrt(mu_max(A)) at rest; the Neo-Hookean tangent only decreases below lambda = e^1.5
  const double mu_max = symmetric_eigen(bar.jacobian_at(1.0)).values.maxCoeff();
  r.dt = 0.5 * 2 / std::sqrt(mu_max);
  double lambda_now = 1;
  SecondOrderSystem sys;
  sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { bar.tl->acceleration(u, a); };
  sys.set_time = [&](double t) {
    lambda_now = 1 + (kStretch - 1) * ramp(t / r.t_load);
    bar.set_stretch(lambda_now);
  };
  sys.mass = bar.tl->dof_mass();
  sys.set_time(0);
  LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(bar.tl->dofs()), Eigen::VectorXd::Zero(bar.tl->dofs()));
  CsvWriter csv(out + "/history_nu" + format_number(nu) + "_ramp" + format_number(ramp_transits) + suffix + ".csv",
                {"t_us", "lambda_imposed", "F_centre", "t11_centre_over_mu", "t11_analytic_over_mu", "F_min", "F_max"},
                false);
  r.t11_at.assign(stretches.size(), std::nan(""));
  const long nsteps = static_cast<long>(std::ceil(r.t_load / r.dt));
  const long every = std::max(1L, nsteps / 1500);
  SnapshotFunction probe([&](const StepView& view) {
    const long s = view.step;
    sys.set_time(view.time);
    Eigen::VectorXd F, P;
    try {
      F = bar.tl->deformation_gradients(view.u).col(0);
      P = bar.tl->stresses(view.u).col(0);
    } catch (const std::invalid_argument& e) {
      r.end = "stopped: J <= 0 at lambda = " + format_number(lambda_now, 4);
      probe.stop(r.end);
      return;
    }
    double fmin = 1e300, fmax = -1e300;
    for (int i : bar.disc->free) fmin = std::min(fmin, F[i]), fmax = std::max(fmax, F[i]);
    const int ic = bar.disc->free[bar.centre];
    for (std::size_t k = 0; k < stretches.size(); ++k)
      if (std::isnan(r.t11_at[k]) && lambda_now >= stretches[k] - 1e-12) r.t11_at[k] = P[ic] / bar.mu();
    if (std::isnan(r.departure) && fmax - fmin > spread_threshold) r.departure = lambda_now;
    if (lambda_now <= r.spread_before_lambda) r.spread_before = fmax - fmin;
    if (s % every == 0 || s == nsteps)
      csv.row(
          {view.time * 1e6, lambda_now, F[ic], P[ic] / bar.mu(), bar.analytic_t11(lambda_now) / bar.mu(), fmin, fmax});
    if (!std::isfinite(F[ic]) || fmax - fmin > 10) {
      r.end = "stopped: F spread > 10 at lambda = " + format_number(lambda_now, 4);
      probe.stop(r.end);
    }
  });
  RunOptions o{.dt = r.dt, .max_steps = nsteps, .snapshot_every = 1};
  o.observers = {&probe};
  const RunResult result = run(stepper, o);
  if (result.status == RunStatus::Exception)  // the TL stress refuses J <= 0
    r.end = "stopped: J <= 0 at lambda = " + format_number(lambda_now, 4);
  else if (!result.completed() && result.status != RunStatus::Stopped)
    r.end = "stopped: " + result.message;
  r.steps = result.steps;
  return r;
}

}  // namespace nh1d
