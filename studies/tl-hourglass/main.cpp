// Zero-energy (hourglass) modes of the finite-strain total-Lagrangian form (forms/finite_strain_total_lagrangian.hpp)
// and the [Ganzenmueller2015] hourglass control term (FiniteStrainOptions::hourglass):
// (a) the spectrum of A = -da/du at u = 0 (mass-weighted: A already carries 1/m) on 1D lines and 2D square blocks,
//     periodic and with fixed layers, plain and NCSPH reference gradients, difference and direct strain sums: the
//     exact null space of the periodic lattices identified with the sawtooth / checkerboard patterns, the Fourier
//     symbol of the strain operator at k = pi/dx, the soft zigzag modes of the blocks and their shapes;
// (b) the lift of those eigenvalues against the coefficient c_HG, with the closed form of the periodic 1D sawtooth
//     and the 2 x 2 Bloch symbols of the 2D hourglass wavevectors, and the shift of the softest smooth mode;
// (c) the accuracy cost on Ismail's 1D validation bar (studies/tl-bar-wave-1d: Hooke 1D stress, clamped end) and
//     explicit leap-frog runs from a noisy initial velocity, with and without control.
// Writes to --out DIR: spectrum.csv, null_modes.csv, symbol.csv, modes.csv, lift.csv, bar.csv, bar_probes.csv,
// noise.csv, summary.json.
// The cases are in hourglass_cases.hpp, the patterns and symbols in lattice_symbols.hpp, (a) + (b) in
// spectrum_lift.hpp, the bar in bar_accuracy.hpp (on common/ismail_bar.hpp, shared with studies/tl-bar-wave-1d), the
// noise runs in noise_runs.hpp.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "bar_accuracy.hpp"
#include "common/cli.hpp"
#include "common/ismail_bar.hpp"
#include "common/study.hpp"
#include "hourglass_cases.hpp"
#include "noise_runs.hpp"
#include "spectrum_lift.hpp"

using namespace hourglass;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  study::DriverCli cli{"Hourglass modes of the finite-strain TL form and the Ganzenmueller (2015) control term",
                       "results/tl-hourglass",
                       "pipeline check: lattices of 20 (1D) and 8 x 8 (2D) free particles instead of 40 and 12 x 12, "
                       "validation bar of 50 free particles"};
  int bar_n = 300;
  cli.app.add_option("--bar-n", bar_n, "free particles of the validation bar")->check(CLI::Range(50, 5000));
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  std::vector<Config> configs = kConfigs;
  if (cli.quick) {
    bar_n = 50;
    for (Config& c : configs) c.n = c.dim == 1 ? 20 : 8;
  }
  const auto t0 = study::Clock::now();
  study::Summary summary;

  // ---------------- (a) + (b): spectra at u = 0 against the coefficient ----------------
  SpectrumTables spectrum_tables(cli.out);
  for (const Config& cfg : configs) {
    if (cfg.dim == 1)
      spectra<1>(cfg, spectrum_tables, summary, t0);
    else
      spectra<2>(cfg, spectrum_tables, summary, t0);
  }
  spectrum_tables.summarise(summary);

  // ---------------- (c) the validation bar against the coefficient ----------------
  {
    const ib::Bar bar = ib::make_bar(bar_n);
    BarTables bar_tables(cli.out);
    for (double chg : kCoefficients) {
      const BarResult r = bar_run(bar, chg, bar_tables.probes);
      bar_tables.add(chg, r);
      std::cout << "bar c_HG = " << chg << ": dt " << r.dt * 1e9 << " ns, max err " << r.worst[1] << " kPa\n";
    }
    summary.set("bar", bar_tables.md_bar);
    summary.set("bar_n", bar_n);
    summary.set("bar_dx_mm", bar.dx * 1e3, 4);
  }

  // ---------------- (c) explicit runs from a noisy initial velocity ----------------
  {
    NoiseTables noise_tables(cli.out);
    noise_run<1>(configs[0], noise_tables);
    noise_run<1>(configs[1], noise_tables);
    noise_run<2>(configs[3], noise_tables);
    noise_run<2>(configs[4], noise_tables);
    summary.set("noise", noise_tables.md_noise);
  }
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(cli.out);
  return 0;
}
