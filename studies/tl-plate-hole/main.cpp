// Issue 11, Ismail (2009) §5.4.4: the quarter plate with a hole under remote tension S, static solution of the
// finite-strain TL SPH form (NCSPH corrected reference gradient, difference strain, Plus divergence) by Newton with the
// complex-step Jacobian and a sparse LU, mirror layers on the symmetry planes (problems/plate_with_hole.hpp).
// (1) linear (Hooke, S/E = 1e-3) against Kirsch's factor 3: resolution a/dx = 4, 8, 16 at W/a = 5 and the width W/a =
// 10, 20 at a/dx = 8 (plate_cases.hpp); (2) Ismail's case E = 70 MPa, nu = 0.49, S = 5 MPa (Neo-Hookean, load steps)
// beside Hooke, statically and suddenly loaded.
// Writes to --out DIR: cases.csv, profile_<tag>.csv, ring_<tag>.csv, particles_<tag>.csv, dynamic_<tag>.csv,
// summary.json.
// The cases are in plate_cases.hpp, the static solution and its measures in static_solution.hpp, the suddenly applied
// load in dynamic_load.hpp, the rows of cases.csv in case_table.hpp, the key numbers in plate_summary.hpp.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "case_table.hpp"
#include "common/cli.hpp"
#include "common/study.hpp"
#include "dynamic_load.hpp"
#include "plate_cases.hpp"
#include "plate_summary.hpp"
#include "sphstab/problems/plate_with_hole.hpp"
#include "static_solution.hpp"

using namespace plate_hole;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  study::DriverCli cli{
      "Issue 11 / Ismail 2009 §5.4.4: plate with a hole (quarter), static TL SPH against Kirsch",
      "results/tl-plate-hole",
      "pipeline check: static runs at a/dx = 4 (the resolution study also 8, the width W/a = 10 only), the "
      "suddenly applied load at a/dx = 4 only, over 2 transit times"};
  double c_hg = 0;
  int finest = 32;
  double transits = 6;
  cli.app.add_option("--hourglass", c_hg, "hourglass coefficient c_HG (0 = off)")->check(CLI::NonNegativeNumber);
  cli.app.add_option("--finest", finest, "finest a/dx of the resolution study (4, 8, 16, ...)")
      ->check(CLI::Range(4, 64));
  cli.app.add_option("--transits", transits, "length of the dynamic runs in shear transit times W / c_s")
      ->check(CLI::PositiveNumber);
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick) transits = 2;
  const auto t0 = study::Clock::now();

  // ---- 1. Static runs (Newton): resolution and width against Kirsch, Ismail's case with Hooke and Neo-Hookean. ----
  CsvWriter csv = cases_csv(cli.out);
  PlateSummary tables;
  for (const Run& run : cli.quick ? quick_static_runs() : static_runs(finest)) {
    const Outcome o = solve(run, c_hg, cli.out);
    write_case(csv, run, o);
    tables.add_static(run, o);
  }

  // ---- 2. Dynamic runs: the suddenly applied load. ----
  // the suddenly applied load (Ismail's "dynamically from rest") on his 21 x 21-like grid and at twice the resolution
  for (int n : cli.quick ? std::vector<int>{4} : std::vector<int>{4, 8}) {
    const Run run = dynamic_run(n);
    tables.add_dynamic(run, dynamic_step(run, c_hg, transits, cli.out));
  }

  // ---- 3. Key numbers for summary.md.in. ----
  study::Summary summary;
  tables.put(summary);
  summary.set("transits", transits, 3);
  summary.set("hourglass", c_hg, 3);
  summary.set("heywood5", heywood_gross_concentration(1, 5), 4);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.set("load", study::load_average());
  summary.write(cli.out);
  return 0;
}
