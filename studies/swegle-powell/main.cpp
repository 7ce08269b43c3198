// Study: the Swegle test as Powell ran it [Powell2012, ch. 4 §2.2, Figs. 4.1, 4.2] — MCM's configuration: the rate
// form with MCM's continuity -rho tr L (1.32), the staggered leap-frog (algorithm 1.1), XSPH as (2.71) on the velocity
// with eps = 0.1, the material card's bulk viscosity (QBVC 1.5, LBVC 0.06: RateFormOptions::bulk_viscosity_*) and
// TSSFAC 0.8. Sweeps h / dx, the block size and the volume strain xi; every case gets its verdict
// (growth/stability_verdict.hpp: gamma_J of the semi-discrete scheme, gamma_M of the leap-frog's one-step map with
// Powell's XSPH, both in the mirror class the kick excites, against the run's detection floor) and a nonlinear run
// whose kinetic-energy growth is fitted. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, ke.csv, summary.json. Units g, cm, us (stress in Mbar).
// The constants, formulations and case table are in powell_cases.hpp, one case (run and verdict) in powell_run.hpp,
// the CSV files in powell_tables.hpp, the key numbers in powell_summary.hpp; the block with its excited mirror class
// and the measurement of a run are common/rate_form_swegle.hpp's.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "powell_cases.hpp"
#include "powell_run.hpp"
#include "powell_summary.hpp"
#include "powell_tables.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/growth/stability_verdict.hpp"

using namespace swegle_powell;

int main(int argc, char** argv) {
  CLI::App app{"The Swegle test in Powell's MCM configuration: h, block size and xi sweeps with verdicts"};
  std::string out = "results/swegle-powell";
  int n = 21, threads = 2;
  double t_end = 45;
  bool quick = false;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles per side of the main block (odd)")->check(CLI::Range(5, 61));
  app.add_option("--t-end", t_end, "run length (us)")->check(CLI::PositiveNumber);
  app.add_option("--threads", threads, "concurrent cases")->check(CLI::Range(1, 64));
  app.add_flag("--quick", quick, "h = 1.1 only, a 7 x 7 block, 10 us, no size or sensitivity sets");
  CLI11_PARSE(app, argc, argv);
  const auto t0 = study::Clock::now();
  std::filesystem::create_directories(out);
  set_threads(1);  // cases run side by side (parallel_for); each scheme on one thread
  if (quick) n = 7, t_end = std::min(t_end, 10.0);

  // ---- The formulations, the cases and the blocks (h, n, layers) they need, built once. ----
  const std::vector<Formulation> forms = formulations();
  const Sweeps sw = sweeps(n, quick);
  const double floor = detection_floor(t_end, kOnset);  // ln(100) / (2 t_end)
  const std::vector<Case> cases = powell_cases(forms.size(), sw);
  const Blocks blocks = make_blocks(cases, forms);

  // ---- 1. Every case: verdict at rest and the kicked run (runs.csv, ke.csv). ----
  const std::vector<Outcome> outcomes = run_all(cases, forms, blocks, t_end, floor, threads);
  write_tables(out, cases, forms, outcomes, floor);

  // ---- 2. The main set: classes, the map against the run, the verdict tables per h. ----
  const MainSet main_set = tally(cases, forms, outcomes, floor);
  study::Summary s;
  s.set("verdict_tables", verdict_tables(main_set, forms, sw.hs));

  // ---- 3. Powell's Fig. 4.2 statements per h, and what XSPH does to the growth. ----
  summarise_statements(s, main_set, sw.hs);

  // ---- 4. Block size and sensitivity sets: one row per case. ----
  s.set("size_table", set_table("size", main_set, cases, forms, outcomes));
  s.set("no_bulk_table", set_table("no-bulk", main_set, cases, forms, outcomes));
  s.set("half_dt_table", set_table("half-dt", main_set, cases, forms, outcomes));

  // ---- 5. Setup, tally and wall times for summary.md.in. ----
  summarise_setup(s, sw, blocks.begin()->second.scene, t_end, floor);
  summarise_tally(s, main_set, cases.size());
  s.set("wall_total", study::seconds_since(t0), 3);
  s.write(out);
  std::printf("%d main cases: S %d U %d I %d B %d; map predicts the run in %d\n", main_set.cases, main_set.count("S"),
              main_set.count("U"), main_set.count("I"), main_set.count("B"), main_set.agree);
  return 0;
}
