#pragma once
// The closed loop of the tl-bar-wave-1d Hooke runs (issue 11): with Hooke's law the TL form is linear, so each fixed
// end's run is u'' = -A u + source exactly. A = -da/du is probed from the time-stepped acceleration with its ghost
// closure (bar_runs.hpp), with the source at rest; its eigenvalues mu give the growth rate gamma = max Re sqrt(-mu)
// [Powell2012, Thm 3.1] (growth/growth_rate.hpp) and the leap-frog rate at the run's dt (integrate/time_step.hpp,
// checked against the dense one-step map); at the base resolution the modified closure's growth per number of
// constrained ghost layers. The observed rate is the least-squares slope of ln |T11 - exact| at the end particle over
// t in [kFitStart, 1.9] L / c.
// Holds the probe of A, the analysis of one run, the observed-growth fit and the CSV tables closure_growth.csv,
// closure_spectrum.csv, closure_layers.csv, closure_mode.csv, end_error.csv with their Markdown tables.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "bar_runs.hpp"
#include "common/study.hpp"
#include "fixed_end.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"

namespace bar_wave {

constexpr double kFitStart = 1.5;  // observed growth fitted over t in [1.5, 1.9] L / c: the pulse has left the end

/// Dense A = -da/du of an acceleration that is linear in u with a(0) = 0 (Hooke's law, the source at rest): column k
/// is -a(s e_k) / s, exact to round-off for any s small enough to keep J > 0. The closure code that is time-stepped
/// is probed itself, so A is the linearisation of exactly what runs.
inline Eigen::MatrixXd probed_matrix(const AccelerationFunction& accel, int n, double s) {
  Eigen::MatrixXd A(n, n);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n), a;
  for (int k = 0; k < n; ++k) {
    u[k] = s;
    accel(u, a);
    A.col(k) = -a / s;
    u[k] = 0;
  }
  return A;
}

/// Least-squares slope of ln e(t) over the samples with t in [t0, t1] and e > 0: the observed exponential rate.
inline double log_slope(const std::vector<double>& t, const std::vector<double>& e, double t0, double t1) {
  double n = 0, st = 0, sy = 0, stt = 0, sty = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] < t0 || t[k] > t1 || !(e[k] > 0)) continue;
    const double y = std::log(e[k]);
    n += 1, st += t[k], sy += y, stt += t[k] * t[k], sty += t[k] * y;
  }
  return n < 3 ? NAN : (n * sty - st * sy) / (n * stt - st * st);
}

/// The closed-loop CSV files and Markdown tables.
struct ClosureTables {
  CsvWriter growth, spectrum, layers, mode, end_error;
  std::string md_closed, md_layers;
  explicit ClosureTables(const std::string& out)
      : growth(out + "/closure_growth.csv", {"fixed_end", "n", "dx", "dt", "gamma", "mu_re", "mu_im", "gamma_dx_over_c",
                                             "leapfrog_rate", "max_abs_mu_dx2_over_c2", "dt_limit_abs_mu", "asymmetry",
                                             "observed_rate", "leapfrog_efolds_window", "observed_efolds_window"}),
        spectrum(out + "/closure_spectrum.csv", {"fixed_end", "n", "mu_re_dx2_over_c2", "mu_im_dx2_over_c2"}),
        layers(out + "/closure_layers.csv", {"layers", "gamma", "mu_re", "mu_im", "gamma_dx_over_c", "unstable_modes"}),
        mode(out + "/closure_mode.csv", {"n", "x", "shape"}),
        end_error(out + "/end_error.csv", {"fixed_end", "n", "t_us", "error_kpa"}) {}
  void summarise(study::Summary& summary) const {
    summary.set("closed_loop", md_closed);
    summary.set("closure_layers", md_layers);
    summary.set("fit_start", kFitStart, 3);
  }
};

/// The closed loop of one Hooke run.
struct ClosedLoop {
  GrowthAnalysis closed;
  double lf_rate = NAN, asym = NAN, max_abs_mu = NAN;
};

/// The closed loop linearised (Hooke: a is linear in u, so this is the whole run's operator): A = -da/du of the
/// time-stepped acceleration with its ghost closure, probed with the source at rest (t - x / c < 0 on every left
/// layer, so a(0) = 0). Non-symmetric for the eta and modified closures: complex mu, growth max Re sqrt(-mu)
/// (Powell Thm 3.1) and the leap-frog rate at the run's dt from the roots z of z^2 - (2 - dt^2 mu) z + 1 = 0.
/// At the base resolution also the modified closure on the first 1 .. all ghost layers (closure_layers.csv) and the
/// leap-frog rate from the dense one-step map (summary key lf_map_check_<fixed end>).
inline ClosedLoop closed_loop(BarRun& r, const Bar& bar, const FixedEndOperators& ends, bool base,
                              ClosureTables& tables, study::Summary& summary) {
  const auto& disc = bar.disc;
  const int n_level = bar.n;
  const double dx = bar.dx, c = r.c;
  Eigen::VectorXd x_free(disc->free_count());
  for (int f = 0; f < disc->free_count(); ++f) x_free[f] = bar.free_x(f);
  const std::vector<int>& by_distance = ends.ghosts.by_distance;
  ClosedLoop out;
  r.t_now = -1;
  const Eigen::MatrixXd A = probed_matrix(r.sys.acceleration, r.tl.dofs(), 1e-9);
  if (base && r.run.fixed_end == FixedEnd::Modified) {  // the same closure on the first 1 .. all ghost layers
    for (int layers = 1; layers <= static_cast<int>(by_distance.size()); ++layers) {
      const ModifiedMatrixDirichlet mm(
          ends.wmat, std::vector<int>(by_distance.begin(), by_distance.begin() + layers));  // deeper ghosts: u = 0
      r.modified_op = &mm;
      const GrowthAnalysis g = growth_rate(probed_matrix(r.sys.acceleration, r.tl.dofs(), 1e-9), x_free);
      r.modified_op = &ends.modified;
      const std::complex<double> mu = g.unstable.empty() ? std::complex<double>(0, 0) : g.unstable.front().mu;
      tables.layers.row(
          {layers, g.growth_rate, mu.real(), mu.imag(), g.growth_rate * dx / c, static_cast<int>(g.unstable.size())});
      study::md_row(tables.md_layers,
                    {std::to_string(layers), study::sig(g.growth_rate, 3), study::sig(g.growth_rate * dx / c, 3),
                     g.unstable.empty() ? "-" : (std::abs(mu.imag()) > 0 ? "complex" : "real < 0"),
                     std::to_string(g.unstable.size())});
    }
  }
  r.t_now = 0;
  out.asym = (A - A.transpose()).norm() / A.norm();
  out.closed = growth_rate(A, x_free);
  out.lf_rate = leapfrog_growth_rate(out.closed.eigenvalues, r.dt);
  out.max_abs_mu = out.closed.eigenvalues.cwiseAbs().maxCoeff();
  if (base)  // the leap-frog rate once more from the dense 2n x 2n one-step map (independent route)
    summary.set(
        "lf_map_check_" + fixed_end_name(r.run.fixed_end),
        std::abs(leapfrog_map_growth(A, r.dt, Eigen::MatrixXd(), VelocityHookMode::DriftOnly).gamma - out.lf_rate) /
            std::max(out.lf_rate, 1.0),
        2);
  const double scale = dx * dx / (c * c);  // mu in units of (c / dx)^2: resolution-independent
  for (const auto& mu : out.closed.eigenvalues)
    tables.spectrum.row({fixed_end_name(r.run.fixed_end), n_level, mu.real() * scale, mu.imag() * scale});
  if (r.run.fixed_end == FixedEnd::Modified && !out.closed.unstable.empty())
    for (int f = 0; f < disc->free_count(); ++f)
      tables.mode.row({n_level, x_free[f], out.closed.unstable.front().shape[f]});
  return out;
}

/// The closed-loop spectrum against the observed growth of the end-particle error (end_t, end_err: every step).
inline void observed_growth(const BarRun& r, const Bar& bar, const ClosedLoop& loop, const std::vector<double>& end_t,
                            const std::vector<double>& end_err, ClosureTables& tables) {
  const int n_level = bar.n;
  const double dx = bar.dx, c = r.c, dt = r.dt, t_end = r.t_end;
  const std::string name = fixed_end_name(r.run.fixed_end);
  for (std::size_t k = 0; k < end_t.size(); ++k) tables.end_error.row({name, n_level, end_t[k] * 1e6, end_err[k]});
  const double t_fit = kFitStart * kLength / c;  // the pulse has left the fixed end's support
  const double slope = log_slope(end_t, end_err, t_fit, t_end);
  const GrowthAnalysis& closed = loop.closed;
  const double lf_rate = loop.lf_rate, max_abs_mu = loop.max_abs_mu;
  const std::complex<double> mu = closed.unstable.empty() ? std::complex<double>(NAN, NAN) : closed.unstable.front().mu;
  const double scale = dx * dx / (c * c);
  tables.growth.row({name, n_level, dx, dt, closed.growth_rate, mu.real(), mu.imag(), closed.growth_rate * dx / c,
                     lf_rate, max_abs_mu * scale, 2 / std::sqrt(max_abs_mu), loop.asym, slope,
                     lf_rate * (t_end - t_fit), slope * (t_end - t_fit)});
  study::md_row(tables.md_closed,
                {name, std::to_string(n_level), study::sig(loop.asym, 2), study::sig(closed.growth_rate, 3),
                 closed.unstable.empty() ? "-"
                                         : study::sig(mu.real() * scale, 4) + " " + (mu.imag() < 0 ? "−" : "+") + " " +
                                               study::sig(std::abs(mu.imag()) * scale, 4) + "i",
                 study::sig(dt / (2 / std::sqrt(max_abs_mu)), 3), study::sig(lf_rate, 3), study::sig(slope, 3),
                 study::sig(lf_rate * (t_end - t_fit), 3), study::sig(slope * (t_end - t_fit), 3)});
}

}  // namespace bar_wave
