// Ismail (2009) §5.3: a 1D compressible Neo-Hookean bar stretched to lambda = 6, with the finite-strain
// total-Lagrangian SPH form (forms/finite_strain_total_lagrangian.hpp, 1D strain: P = mu (F - 1/F) + lambda ln F / F,
// algorithm 5.1).
//   1. static: the homogeneous stretch u = (lambda - 1) X on every particle; SPH T11 against the analytic table
//      (reference_t11_table.csv: T11/mu tabulated for this project from [Ismail2009, (5.5)]);
//   2. quasi-static run: both ends' fixed layers carry u = (lambda(t) - 1) X, lambda(t) ramped smoothly 1 -> 6 over
//      --ramp transit times L / c_L, leap-frog from rest; the centre particle's T11 against the analytic curve;
//   3. loss of hyperbolicity at nu = 0.49: the root of the material tangent dP/dF (bisection on the model) and the
//      stretch at which the linearised TL Jacobian A = -da/du (complex step, at the stretched equilibrium) stops
//      being positive definite (secant iteration on the critical-load engine's definiteness routes).
// Writes to --out DIR: table.csv, history_nu<nu>_ramp<r>[_n<n>].csv, ramps.csv, resolution.csv, hyperbolicity.csv,
// summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/critical_load.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

// SI units. Ismail's bar (§4.6.3, §5.3): steel-like E = 200 GPa, rho = 8000; the quasi-static bar is 15 mm long.
constexpr double kE = 200e9, kRho = 8000, kLength = 0.015, kStretch = 6;
// Ismail's h = 5.5 dx with the mollifier's native support h: sphstab's support-2h convention gives h = 2.75 dx.
constexpr double kHOverDx = 2.75;

struct TableRow {
  double nu, lambda1, t11;
};

std::vector<TableRow> read_table(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read " + path);
  std::vector<TableRow> rows;
  std::string line;
  bool header = true;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::stringstream s(line);
    std::string nu, l2, l1, t;
    std::getline(s, nu, ',');
    std::getline(s, l2, ',');
    std::getline(s, l1, ',');
    std::getline(s, t, ',');
    if (std::stod(l2) == 1) rows.push_back({std::stod(nu), std::stod(l1), std::stod(t)});
  }
  return rows;
}

/// The bar: n free particles on [0, L], fixed layers two kernel supports deep at both ends (every particle within a
/// support of a free one has a complete neighbourhood, so the homogeneous stretch is an exact equilibrium).
struct Bar {
  std::shared_ptr<const Discretisation<1>> disc;
  std::shared_ptr<NeoHookean<1>> material;
  std::shared_ptr<FiniteStrainTotalLagrangian<1>> tl;
  Eigen::VectorXd x_free, x_fixed;
  double dx = 0, m1 = 0;
  int centre = 0;  // free slot of the centre particle

  Bar(int n, double nu) {
    dx = kLength / n;
    const Kernel<1> kernel(KernelType::ModifiedMollifier);
    const double h = kHOverDx * dx;
    ParticleSet<1> set =
        make_lattice<1>(LatticeType::Line, n, {.spacing = dx, .support_radius = 2 * kernel.support_radius(h)});
    disc = make_discretisation(set, kernel, h);
    material = std::make_shared<NeoHookean<1>>(LameParameters::from_young_poisson(kE, nu));
    // the variational pair (plain reference gradient, difference strain, plus divergence): symmetric Jacobian
    tl = std::make_shared<FiniteStrainTotalLagrangian<1>>(disc, material, kRho);
    x_free = disc->free_positions().col(0);
    x_fixed.resize(disc->size() - disc->free_count());
    for (int i = 0, k = 0; i < disc->size(); ++i)
      if (disc->free_slot[i] < 0) x_fixed[k++] = disc->particles.x(i, 0);
    centre = n / 2;
    // discrete first moment: F - 1 = m1 (lambda - 1) for the plain gradient
    set_stretch(2.0);
    m1 = tl->deformation_gradients(Eigen::VectorXd(x_free))(disc->free[centre], 0) - 1;
    set_stretch(1.0);
  }
  void set_stretch(double lambda) { tl->set_fixed_displacement((lambda - 1) * x_fixed); }
  Eigen::VectorXd homogeneous(double lambda) const { return (lambda - 1) * x_free; }
  double c_l() const { return std::sqrt(material->lame().uniaxial_modulus(UniaxialState::Strain) / kRho); }
  double mu() const { return material->lame().mu; }
  /// P = T11 (1D strain: J = F) of free particle f.
  double t11(const Eigen::VectorXd& u, int f) const { return tl->stresses(u)(disc->free[f], 0); }
  double F(const Eigen::VectorXd& u, int f) const { return tl->deformation_gradients(u)(disc->free[f], 0); }
  double analytic_t11(double lambda) const {
    return material->stress(Deformation<double, 1>(Deformation<double, 1>::Constant(lambda)))(0, 0);
  }
  double tangent(double f) const {
    return material->tangent(Deformation<double, 1>(Deformation<double, 1>::Constant(f)))(0, 0);
  }
  /// A = -da/du at the homogeneous stretch (an equilibrium), symmetrised (complex step is symmetric to ~1e-16).
  Eigen::MatrixXd jacobian_at(double lambda) {
    set_stretch(lambda);
    const Eigen::MatrixXd A(jacobian(*tl, homogeneous(lambda)));
    set_stretch(1.0);
    return 0.5 * (A + A.transpose());
  }
};

double smallest_eigenvalue(const Eigen::MatrixXd& A) { return symmetric_eigen(A).values[0]; }

/// Root of g in [a, b] (g(a) > 0 > g(b)) by bisection to |b - a| <= tol.
template <class G>
double bisect(G g, double a, double b, double tol) {
  while (b - a > tol) {
    const double m = 0.5 * (a + b);
    (g(m) > 0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

struct Crossing {
  double lambda = std::nan("");  ///< the converged prediction of the engine
  bool verified = false;         ///< A positive definite at lambda - tol and indefinite at lambda + tol
  int iterations = 0;
};

/// The stretch at which A(lambda) stops being positive definite, by regula falsi on the critical-load engine: on the
/// bracket [lo, hi] (A(lo) positive definite, A(hi) not) the affine interpolation A(lo) + t (A(hi) - A(lo)) / (hi -
/// lo) is a Linearisation whose critical load t (CHOLMOD bisection and the generalised eigenproblem, which must agree)
/// predicts the crossing lo + t; the bracket end on the same side as the prediction moves there. Stops when two
/// predictions differ by less than tol, then checks definiteness at the prediction -+ tol.
Crossing definiteness_crossing(Bar& bar, double lo, double hi, double tol) {
  Crossing c;
  Eigen::MatrixXd Alo = bar.jacobian_at(lo), Ahi = bar.jacobian_at(hi);
  CriticalLoadOptions opt = CriticalLoadOptions::tension_1d();
  opt.criterion = Criterion::Definiteness;
  opt.want_mode = false;
  opt.start = 1e-6 * (hi - lo);
  double previous = std::nan("");
  for (; c.iterations < 100; ++c.iterations) {
    Linearisation lin;
    lin.A0 = Alo.sparseView();
    lin.A1 = ((Ahi - Alo) / (hi - lo)).sparseView();
    lin.symmetric = true;
    const CriticalLoad r = critical_load(lin, LoadDirection::Tension, opt);
    if (r.info() != Status::Successful || !std::isfinite(r.load))
      throw std::runtime_error("critical_load: " + r.reason);
    c.lambda = lo + r.load;
    if (std::abs(c.lambda - previous) < tol) break;
    previous = c.lambda;
    const Eigen::MatrixXd A = bar.jacobian_at(c.lambda);
    if (smallest_eigenvalue(A) > 0)
      lo = c.lambda, Alo = A;
    else
      hi = c.lambda, Ahi = A;
  }
  c.verified = smallest_eigenvalue(bar.jacobian_at(c.lambda - tol)) > 0 &&
               smallest_eigenvalue(bar.jacobian_at(c.lambda + tol)) <= 0;
  return c;
}

/// Smooth ramp 0 -> 1 over tau in [0, 1] with zero velocity at both ends.
double ramp(double tau) {
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

QuasiStaticRun quasi_static_run(Bar& bar, double nu, double ramp_transits, const std::vector<double>& stretches,
                                double spread_threshold, const std::string& out, const std::string& suffix = "") {
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
      csv.row({view.time * 1e6, lambda_now, F[ic], P[ic] / bar.mu(), bar.analytic_t11(lambda_now) / bar.mu(), fmin,
               fmax});
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ismail 2009 §5.3: finite-strain TL SPH of a 1D Neo-Hookean bar stretched to 6"};
  std::string out = "results/tl-neo-hookean-1d";
  int n = 100;
  double ramp_transits = 30, spread = 0.25;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles")->check(CLI::Range(20, 2000));
  app.add_option("--ramp", ramp_transits, "loading time in small-strain transit times L / c_L (Ismail: 30)")
      ->check(CLI::PositiveNumber);
  app.add_option("--spread", spread, "departure: max F - min F over the free particles above this")
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  const fs::path here = SPHSTAB_STUDY_DIR;
  const std::vector<TableRow> table = read_table((here / "reference_t11_table.csv").string());
  const std::vector<double> stretches{1.5, 2, 3, 4, 6};
  study::Summary summary;
  summary.set("n", n);
  summary.set("h_over_dx", kHOverDx, 3);
  summary.set("ramp", ramp_transits, 3);
  summary.set("spread", spread, 3);

  CsvWriter tcsv(out + "/table.csv", {"nu", "lambda1", "t11_thesis_over_mu", "t11_analytic_over_mu",
                                      "t11_static_sph_over_mu", "t11_dynamic_sph_over_mu", "dynamic_relative_error"});
  CsvWriter rcsv(out + "/ramps.csv",
                 {"nu", "ramp_transits", "t_load_us", "dt_ns", "steps", "spread_at_3.5", "departure_lambda", "end"});
  std::vector<double> ramps{ramp_transits, 100, 300, 1000};
  std::sort(ramps.begin(), ramps.end());
  ramps.erase(std::unique(ramps.begin(), ramps.end()), ramps.end());
  std::string md, md_ramps;
  double worst_static = 0, worst_thesis = 0;
  for (double nu : {0.3, 0.49}) {
    Bar bar(n, nu);
    const std::string tag = nu == 0.3 ? "03" : "049";
    summary.set("m1", bar.m1, 10);
    std::cout << "nu = " << nu << ": c_L = " << bar.c_l() << " m/s, m1 = " << bar.m1 << "\n";
    QuasiStaticRun run;
    for (double r : ramps) {
      const QuasiStaticRun q = quasi_static_run(bar, nu, r, stretches, spread, out);
      std::cout << "  ramp " << r << ": " << q.steps << " steps, " << q.end << ", departure at lambda = " << q.departure
                << "\n";
      rcsv.row({nu, r, q.t_load * 1e6, q.dt * 1e9, q.steps, q.spread_before, q.departure, q.end});
      study::md_row(md_ramps,
                    {study::fixed(nu, 2), study::sig(r, 4), study::sig(q.t_load * 1e6, 4), std::to_string(q.steps),
                     study::sig(q.spread_before, 2), std::isnan(q.departure) ? "none" : study::fixed(q.departure, 3)});
      if (r == ramp_transits) run = q;
    }
    summary.set("dt_ns_" + tag, run.dt * 1e9, 4);
    summary.set("steps_" + tag, run.steps);
    summary.set("t_load_us_" + tag, run.t_load * 1e6, 4);
    summary.set("run_end_" + tag, run.end);
    summary.set("departure_" + tag, run.departure, 5);
    for (std::size_t k = 0; k < stretches.size(); ++k) {
      const double l1 = stretches[k];
      double thesis = std::nan("");
      for (const TableRow& row : table)
        if (row.nu == nu && row.lambda1 == l1) thesis = row.t11;
      const double analytic = bar.analytic_t11(l1) / bar.mu();
      bar.set_stretch(l1);
      const Eigen::VectorXd u = bar.homogeneous(l1);
      double static_sph = std::nan("");  // the worst free particle
      for (int f = 0; f < bar.disc->free_count(); ++f) {
        const double t = bar.t11(u, f) / bar.mu();
        if (std::isnan(static_sph) || std::abs(t - analytic) > std::abs(static_sph - analytic)) static_sph = t;
      }
      bar.set_stretch(1.0);
      const double dyn = run.t11_at[k];
      const double rel = (dyn - analytic) / analytic;
      worst_thesis = std::max(worst_thesis, std::abs(analytic - thesis));
      worst_static = std::max(worst_static, std::abs(static_sph - analytic) / analytic);
      tcsv.row({nu, l1, thesis, analytic, static_sph, dyn, rel});
      study::md_row(md, {study::fixed(nu, 2), study::fixed(l1, 1), study::fixed(thesis, 4), study::fixed(analytic, 4),
                         study::fixed(static_sph, 4), study::fixed(dyn, 4),
                         study::fixed(100 * rel, 2, true) + " %" + (run.departure <= l1 ? " (after departure)" : "")});
    }
  }
  summary.set("table", md);
  summary.set("ramps", md_ramps);
  summary.set("worst_thesis_difference", worst_thesis, 2);
  summary.set("worst_static_relative", worst_static, 2);

  // resolution: the departure at the slowest ramp for n / 2, n, 2 n (nu = 0.49)
  {
    std::string md_res;
    CsvWriter ncsv(out + "/resolution.csv", {"n", "ramp_transits", "spread_at_3.5", "departure_lambda", "end"});
    for (int nr : {n / 2, n, 2 * n}) {
      Bar bar(nr, 0.49);
      const QuasiStaticRun q =
          quasi_static_run(bar, 0.49, ramps.back(), stretches, spread, out, "_n" + std::to_string(nr));
      std::cout << "  n = " << nr << ", ramp " << ramps.back() << ": departure at lambda = " << q.departure << "\n";
      ncsv.row({nr, ramps.back(), q.spread_before, q.departure, q.end});
      study::md_row(md_res, {std::to_string(nr), study::sig(ramps.back(), 4), study::sig(q.spread_before, 2),
                             std::isnan(q.departure) ? "none" : study::fixed(q.departure, 3)});
    }
    summary.set("resolution", md_res);
  }

  // 3. loss of hyperbolicity at nu = 0.49
  {
    Bar bar(n, 0.49);
    const double lam = bar.material->lame().lambda, mu = bar.mu();
    summary.set("lambda_over_mu", lam / mu, 6);
    // analytic: dP/dF of the model changes sign (two roots; the first on [1, e^1.5], the second above)
    const auto g = [&](double f) { return bar.tangent(f); };
    const double f1 = bisect(g, 1.0, std::exp(1.5), 1e-13);
    const double f2 = bisect([&](double f) { return -g(f); }, std::exp(1.5), 20.0, 1e-13);
    // independent residual of the closed form mu (F^2 + 1) + lambda (1 - ln F) = 0
    const double residual = mu * (f1 * f1 + 1) + lam * (1 - std::log(f1));
    summary.set("f_tangent", f1, 8);
    summary.set("f_tangent_upper", f2, 8);
    summary.set("f_tangent_residual", std::abs(residual) / lam, 2);
    std::cout << "tangent dP/dF = 0 at F = " << f1 << " and " << f2 << "\n";
    // SPH: A(lambda) on a grid, then the engine's crossing
    CsvWriter hcsv(out + "/hyperbolicity.csv", {"lambda_imposed", "F_sph", "tangent_over_modulus",
                                                "mu_min_over_mu_min_rest", "mu_max_over_mu_max_rest"});
    const auto rest = symmetric_eigen(bar.jacobian_at(1.0)).values;
    double lo = 1, hi = std::nan("");
    for (double l = 1.0; l <= 7.0 + 1e-9; l += 0.05) {
      const Eigen::VectorXd ev = symmetric_eigen(bar.jacobian_at(l)).values;
      bar.set_stretch(l);
      const double F = bar.F(bar.homogeneous(l), bar.centre);
      bar.set_stretch(1.0);
      hcsv.row({l, F, bar.tangent(F) / (lam + 2 * mu), ev[0] / rest[0], ev.maxCoeff() / rest.maxCoeff()});
      if (std::isnan(hi)) (ev[0] > 0 ? lo : hi) = l;
    }
    const double tol = 1e-9;
    const Crossing c = definiteness_crossing(bar, lo, hi, tol);
    bar.set_stretch(c.lambda);
    const double f_sph = bar.F(bar.homogeneous(c.lambda), bar.centre);
    bar.set_stretch(1.0);
    summary.set("lambda_sph", c.lambda, 10);
    summary.set("f_sph", f_sph, 10);
    summary.set("sph_verified", c.verified ? "yes" : "NO");
    summary.set("sph_iterations", c.iterations);
    summary.set("f_difference", std::abs(f_sph - f1), 2);
    summary.set("lambda_difference", std::abs(c.lambda - f1), 2);
    summary.set("crossing_tol", tol, 2);
    std::cout << "A(lambda) indefinite from lambda = " << c.lambda << " (F = " << f_sph
              << "), |F - F_tangent| = " << std::abs(f_sph - f1) << "\n";
  }
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
