// Powell (2012) ch. 2 §3.1: the 1D non-reflecting boundary (2.69)-(2.70) on a semi-infinite elastic bar (2.68),
// Table 2.1 (SPH, XSPH, NCSPH, NCXSPH with the reference, 1-5 absorbing particles and upwind), the h-study of
// Fig. 2.12, and the time-step limits that explain the table's X entries.
//
// Writes to --out DIR: table.csv (every case: form, layers, timing, CFL, status, mean error (2.72), steps),
// series/<tag>.csv (t, v of particle 80, about 400 records), cfl_sweep.csv, dt_limit.csv, h_study.csv, summary.json.
// The bar, its cases and its exact solution are in bar_problem.hpp, one run in bar_run.hpp, the case tables of the
// phases in study_cases.hpp, the time-step limits in step_limits.hpp, the CSV tables in nrbc_tables.hpp, the key
// numbers in nrbc_summary.hpp.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "bar_problem.hpp"
#include "bar_run.hpp"
#include "common/cli.hpp"
#include "common/driver.hpp"
#include "common/study.hpp"
#include "nrbc_summary.hpp"
#include "nrbc_tables.hpp"
#include "step_limits.hpp"
#include "study_cases.hpp"

using namespace nrbc1d;
namespace fs = std::filesystem;

int main(int argc, char** argv) try {
  study::DriverCli cli{
      "Powell 2012 ch. 2: 1D non-reflecting boundary, Table 2.1, h-study, time-step limits", "results/nrbc-1d",
      "pipeline check: every run to 10 us; Table 2.1 in full, the sweep at the tuned step only, h / dx 1.3 "
      "only, and the step limits of SPH with one absorbing layer and NCXSPH with the upwind eight (half-step "
      "timing)"};
  double cfl = 0.5, tssfac = 0.8;
  int threads = 2;
  std::vector<double> sweep = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8};
  std::vector<double> h_values = {1.1, 1.2, 1.3, 1.5, 1.7, 2.0, 2.5, 3.0};
  cli.app
      .add_option("--cfl", cfl,
                  "the tuned dt = cfl dx / c of the Table 2.1 sensitivity (the value at which the "
                  "symmetric bar reproduces Powell's X pattern)")
      ->check(CLI::Range(0.01, 2.0));
  cli.app.add_option("--tssfac", tssfac, "the headline dt = tssfac h / c (MCM deck TSSFAC 0.8, DYNA's rule at rest)")
      ->check(CLI::Range(0.01, 1.5));
  cli.add_threads(threads);
  cli.app.add_option("--cfl-sweep", sweep, "CFL values of the sweep")->delimiter(',')->check(CLI::Range(0.01, 2.0));
  cli.app.add_option("--h", h_values, "h / dx of the h-study")->delimiter(',')->check(CLI::Range(1.0, 4.0));
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick) sweep = {cfl}, h_values = {1.3};
  const auto t0 = study::Clock::now();
  fs::create_directories(cli.out + "/series");
  study::Summary sum;

  // 1. Table 2.1. Headline: Powell's geometry (free end) and timing (half) at MCM's time step, dt = TSSFAC h / c
  // (the deck's TSSFAC 0.8 with DYNA's step rule h / c at rest: c dt/dx = 1.04). Sensitivities: the symmetric bar at
  // that step, and the tuned c dt/dx = 0.5 (the value at which the symmetric bar reproduces Powell's X pattern) on the
  // symmetric bar with both timings and on the free end.
  const double cfl_mcm = tssfac * 1.3;
  const std::vector<Variant> variants = table_variants(cfl_mcm, cfl);
  const auto quick_length = [&](std::vector<BarCase> cases) {  // --quick: every run to 10 us, as the h-study's
    if (cli.quick)
      for (BarCase& c : cases) c.t_to = 10;
    return cases;
  };
  const std::vector<BarRun> runs = run_all(quick_length(table_cases(variants, cfl)), threads);
  write_table(cli.out + "/table.csv", runs);
  write_series(cli.out, runs);
  summarise_table(sum, runs, variants, cfl);

  // 2. CFL sweep: stable or not, and the error, for the truncated bars at each dt (both timings).
  const std::vector<BarRun> sweep_runs = run_all(quick_length(sweep_cases(sweep)), threads);
  write_table(cli.out + "/cfl_sweep.csv", sweep_runs);

  // 3. The largest stable CFL of every truncated configuration (bisection on whole runs to 20 us), and from the
  // linearised step (spectral radius at rest, undamped and damped).
  const StepLimits limits = step_limits(quick_length(limit_cases(cli.quick)), cfl, threads);
  write_dt_limit(cli.out, limits);
  summarise_step_limits(sum, limits);

  // 4. Fig. 2.12: NCXSPH, floor(2h/dx) + 1 absorbing particles, error over 3 < t < 10 us, reference and truncated.
  const std::vector<BarRun> hruns = run_all(h_cases(h_values, cfl), threads);
  write_h_study(cli.out, hruns);
  summarise_h_study(sum, hruns);

  sum.set("cfl", cfl, 3);
  sum.set("cfl_mcm", cfl_mcm, 3);
  sum.set("tssfac", tssfac, 3);
  sum.set("c", bar_speed(), 5);
  sum.set("runs", static_cast<long>(runs.size() + sweep_runs.size() + hruns.size()));
  study::write_summary(sum, cli.out, t0);
  return 0;
} catch (const std::exception& e) {
  return study::exit_on_error("nrbc-1d", e);
}
