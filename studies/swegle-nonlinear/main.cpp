// Study: is the growth of the rate-form Swegle runs linear, nonlinear or made by the time integrator? For each
// (formulation, xi) the full-state linear growth rate (growth/rate_form_spectrum.hpp) is compared with the fitted
// kinetic-energy growth of runs kicked at three amplitudes v0, with the GMS predictor-corrector and with Powell's
// leap-frog (integrate/rate_form_run.hpp), and, for the predictor-corrector at the smallest kick, at dt and dt/2
// (integrator-made growth falls as dt^3). Each (formulation, xi, integrator, dt) gets its stability verdict
// (growth/stability_verdict.hpp, in the mirror class the kick excites): S, U, I or B from the semi-discrete growth,
// the integrator's one-step map growth and the run's detection floor. See README.md; the prose of the summary is
// summary.md.in.
//
// Writes to --out DIR: runs.csv, block_size.csv, summary.json. Units g, cm, us (stress in Mbar).
// The options, formulations and block (shared with studies/swegle-rate-form) are in common/rate_form_swegle.hpp,
// one kicked run in kick_run.hpp, one (formulation, xi) with its rows of runs.csv in kick_case.hpp, the summary's
// tables and lists of the cases in kick_lists.hpp, the block-size spectra in block_size.hpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "block_size.hpp"
#include "common/rate_form_swegle.hpp"
#include "common/study.hpp"
#include "kick_case.hpp"
#include "kick_lists.hpp"
#include "kick_run.hpp"
#include "sphstab/growth/stability_verdict.hpp"

using namespace swegle_nonlinear;

int main(int argc, char** argv) {
  CLI::App app{"Swegle test, rate-form scheme: linear, nonlinear or integrator-made growth?"};
  Options o{.out = "results/swegle-nonlinear", .n = 11, .t_end = 30};
  const QuickCase quick{7, 10, "basic SPH only, a 7 x 7 block, 10 us, block sizes 5 and 7"};
  if (const auto exit = parse_options(app, o, quick, argc, argv)) return *exit;
  const auto t0 = study::Clock::now();

  const std::vector<Formulation> forms =
      o.quick ? formulations({"sph"}) : formulations({"sph", "ncsph", "ncsph-anti", "ssph", "ssph-printed"});
  const std::vector<double> xis = {0.98, 1.02};
  const std::vector<int> sizes = o.quick ? std::vector<int>{5, 7} : std::vector<int>{9, 11, 13, 15, 17, 21};
  SwegleOptions so;
  so.n = o.n;
  so.layer_supports = 3;  // S-SPH reads neighbours of neighbours: every corrected form starts in exact equilibrium
  Setup s{.o = o, .block = make_block(so), .steel = steel(so)};
  s.dt = time_step(s.block.scene, s.steel);
  s.floor = detection_floor(o.t_end, o.onset);  // the slowest growth the fit can see in t_end
  s.v0s = {1e-10, 1e-4, 1e-2};                  // 1e-7 dropped for run time (it matched 1e-10)

  // ---- 1. Every (formulation, xi): spectra, verdicts and the kicked runs (runs.csv). ----
  std::ofstream runs_csv(o.out + "/runs.csv");
  runs_csv << kRunsHeader;
  KickLists lists;
  double wall_linear = 0, wall_runs = 0;
  for (const Formulation& form : forms)
    for (double xi : xis) {
      const KickCase c = run_case(s, form, xi);
      write_runs(runs_csv, c, s);
      lists.add(c, s);
      wall_linear += c.wall_linear, wall_runs += c.wall_runs;
    }

  // ---- 2. The full-state growth rate at rest against the block size (block_size.csv). ----
  const BlockSizes blocks = block_sizes(s, forms, xis, sizes, t0);
  wall_linear += blocks.wall_linear;

  // ---- 3. Key numbers for summary.md.in. ----
  study::Summary sum;
  summarise_setup(sum, o, s.block.scene, s.steel, s.dt);
  sum.set("floor", s.floor, 3);
  lists.summarise(sum);
  sum.set("size_table", blocks.table);
  sum.set("size_onsets", blocks.onsets);
  summarise_walls(sum, wall_linear, wall_runs, t0);
  sum.write(o.out);
  std::printf("wall: linear %.1f s, runs %.1f s, total %.1f s\n", wall_linear, wall_runs, study::seconds_since(t0));
  return 0;
}
