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
// The bar is in neo_hookean_bar.hpp, the analytic table in common/reference_t11_table.hpp, the quasi-static run in
// quasi_static_run.hpp, the tangent root and the definiteness crossing in hyperbolicity.hpp.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/reference_t11_table.hpp"
#include "common/study.hpp"
#include "hyperbolicity.hpp"
#include "neo_hookean_bar.hpp"
#include "quasi_static_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"

using namespace nh1d;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  study::DriverCli cli{"Ismail 2009 §5.3: finite-strain TL SPH of a 1D Neo-Hookean bar stretched to 6",
                       "results/tl-neo-hookean-1d",
                       "pipeline check: n = 40 free particles (the resolution runs at 20, 40, 80)"};
  int n = 100;
  double ramp_transits = 30, spread = 0.25;
  cli.app.add_option("--n", n, "free particles")->check(CLI::Range(20, 2000));
  cli.app.add_option("--ramp", ramp_transits, "loading time in small-strain transit times L / c_L (Ismail: 30)")
      ->check(CLI::PositiveNumber);
  cli.app.add_option("--spread", spread, "departure: max F - min F over the free particles above this")
      ->check(CLI::PositiveNumber);
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick) n = 40;
  const auto t0 = study::Clock::now();
  const fs::path here = SPHSTAB_STUDY_DIR;
  const std::vector<study::TableRow> table = study::read_table((here / "reference_t11_table.csv").string());
  const std::vector<double> stretches{1.5, 2, 3, 4, 6};
  study::Summary summary;
  summary.set("n", n);
  summary.set("h_over_dx", kHOverDx, 3);
  summary.set("ramp", ramp_transits, 3);
  summary.set("spread", spread, 3);

  // 1. and 2. per nu: the quasi-static runs at every ramp, then static, dynamic (--ramp), analytic and thesis T11
  CsvWriter tcsv(cli.out + "/table.csv",
                 {"nu", "lambda1", "t11_thesis_over_mu", "t11_analytic_over_mu", "t11_static_sph_over_mu",
                  "t11_dynamic_sph_over_mu", "dynamic_relative_error"});
  CsvWriter rcsv(cli.out + "/ramps.csv",
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
      const QuasiStaticRun q = quasi_static_run(bar, nu, r, stretches, spread, cli.out);
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
      const double thesis = study::thesis_t11(table, nu, 1, l1);  // 1D strain: lambda2 = 1
      const double analytic = bar.analytic_t11(l1) / bar.mu();
      const double static_sph = bar.static_t11(l1);  // the worst free particle
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
    CsvWriter ncsv(cli.out + "/resolution.csv", {"n", "ramp_transits", "spread_at_3.5", "departure_lambda", "end"});
    for (int nr : {n / 2, n, 2 * n}) {
      Bar bar(nr, 0.49);
      const QuasiStaticRun q =
          quasi_static_run(bar, 0.49, ramps.back(), stretches, spread, cli.out, "_n" + std::to_string(nr));
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
    const double lam = bar.material->material().lambda(), mu = bar.mu();
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
    CsvWriter hcsv(cli.out + "/hyperbolicity.csv", {"lambda_imposed", "F_sph", "tangent_over_modulus",
                                                    "mu_min_over_mu_min_rest", "mu_max_over_mu_max_rest"});
    const auto rest = symmetric_eigen(bar.jacobian_at(1.0)).values;
    double lo = 1, hi = std::nan("");
    for (double l = 1.0; l <= 7.0 + 1e-9; l += 0.05) {
      const Eigen::VectorXd ev = symmetric_eigen(bar.jacobian_at(l)).values;
      const double F = bar.centre_F(l);
      hcsv.row({l, F, bar.tangent(F) / (lam + 2 * mu), ev[0] / rest[0], ev.maxCoeff() / rest.maxCoeff()});
      if (std::isnan(hi)) (ev[0] > 0 ? lo : hi) = l;
    }
    const double tol = 1e-9;
    const Crossing c = definiteness_crossing(bar, lo, hi, tol);
    const double f_sph = bar.centre_F(c.lambda);
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
  summary.write(cli.out);
  return 0;
}
