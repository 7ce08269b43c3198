// Ismail (2009) §4.6.3 and §5.3.1: the 1D validation bar (L = 0.15 m, rho = 8000, E = 200 GPa, nu = 0.3), a
// -100 kPa compressive pulse entering at the left end, the right end fixed; probe stress histories at x = 0.05, 0.10
// and 0.15 m and the arrival times against the bar speed c_b = sqrt(E / rho) and the longitudinal speed
// c_L = sqrt((lambda + 2 mu) / rho), with the finite-strain TL form (forms/finite_strain_total_lagrangian.hpp) and
// three materials: Hooke 1D stress (Ismail's algorithm 4.1, T11 = E eps), Neo-Hookean 1D strain (algorithm 5.1) and
// Neo-Hookean 1D stress.
// Source: the left fixed layers carry the exact incoming wave u(x, t) = f(t - x / c) of the material's small-strain
// speed c (as if the bar continued to the left), with f' = v(t) = -sigma(t) / (rho c) and sigma(t) a smoothed square
// pulse of -100 kPa; the right fixed layers are clamped. Exact linear solution before the reflection reaches the left
// end: sigma(x, t) = sigma_in(t - x / c) + sigma_in(t - (2L - x) / c) (full, same-sign reflection at the fixed end).
// Writes to --out DIR: probes_<run>.csv (base resolution), arrivals.csv, speeds.csv (n, 2n, 4n), summary.json; the
// fixed ends and the closed loop: wcc_conditioning.csv, closure_growth.csv, closure_spectrum.csv, closure_layers.csv,
// closure_mode.csv, end_error.csv.
// The bar, its pulse and its exact solution are in common/ismail_bar.hpp (shared with studies/tl-hourglass), the
// fixed ends in fixed_end.hpp, the runs in bar_runs.hpp, the W_CC conditioning in wcc_conditioning.hpp, the closed
// loop in closed_loop.hpp, the pulse run and its arrival and speed tables in pulse_run.hpp.
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "bar_runs.hpp"
#include "closed_loop.hpp"
#include "common/cli.hpp"
#include "common/ismail_bar.hpp"
#include "common/study.hpp"
#include "fixed_end.hpp"
#include "pulse_run.hpp"
#include "wcc_conditioning.hpp"

using namespace bar_wave;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  study::DriverCli cli{"Ismail 2009 §4.6.3 / §5.3.1: pulse in the 1D validation bar, finite-strain TL SPH",
                       "results/tl-bar-wave-1d", "pipeline check: n = 50 free particles (resolutions 50, 100, 200)"};
  int n = 300;
  cli.app.add_option("--n", n, "free particles")->check(CLI::Range(50, 5000));
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick) n = 50;
  const auto t0 = study::Clock::now();
  const ElasticMaterial lame = ElasticMaterial::from_young_poisson(kE, kNu, kRho);
  const double cb = std::sqrt(kE / kRho), cl = std::sqrt((lame.lambda() + 2 * lame.mu()) / kRho);
  const std::vector<Run> runs = bar_runs(lame, cb, cl);
  study::Summary summary;
  summary.set("n", n);
  summary.set("dx_mm", kLength / n * 1e3, 4);
  summary.set("h_over_dx", kHOverDx, 3);
  summary.set("c_b", cb, 6);
  summary.set("c_l", cl, 6);
  summary.set("rise_us", kRise * 1e6, 3);
  summary.set("duration_us", kDuration * 1e6, 3);
  PulseTables pulse_tables(cli.out);
  WccTables wcc_tables(cli.out);
  ClosureTables closure_tables(cli.out);

  for (const int level : {1, 2, 4}) {  // the resolution n, 2n, 4n at fixed h / dx
    const bool base = level == 1;
    const Bar bar = make_bar(n * level);
    const FixedEndOperators ends(bar);  // the right end's ghosts and operators, built once per resolution

    // 1. Conditioning of W_CC and the gain of the exact closure.
    wcc_conditioning(bar, ends, base, wcc_tables);

    for (const Run& run : runs) {
      BarRun r(bar, ends, run);

      // 2. The closed loop linearised (Hooke runs).
      ClosedLoop loop;
      if (run.fixed_end_run()) loop = closed_loop(r, bar, ends, base, closure_tables, summary);

      // 3. The pulse: probes, arrivals, speed; the observed growth of the end-particle error (Hooke runs).
      const PulseResult pulse = pulse_run(r, bar, base, cli.out);
      if (base && run.fixed_end == FixedEnd::Clamped) summary.set("dt_ns_" + run.name, r.dt * 1e9, 4);
      std::cout << run.name << ": dt = " << r.dt * 1e9 << " ns, " << pulse.steps
                << " steps, max |sigma - exact| = " << pulse.worst[0] << ", " << pulse.worst[1] << ", "
                << pulse.worst[2] << " kPa\n";
      pulse_tables.add(r, bar, base, pulse, cb, cl);
      if (run.fixed_end_run()) observed_growth(r, bar, loop, pulse.end_t, pulse.end_err, closure_tables);
    }
  }

  // 4. Key numbers for summary.md.in.
  pulse_tables.summarise(summary);
  wcc_tables.summarise(summary);
  closure_tables.summarise(summary);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(cli.out);
  return 0;
}
