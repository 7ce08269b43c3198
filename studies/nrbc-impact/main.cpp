// Powell (2012) ch. 2 §3.2(c): surface impact on a half-space with non-reflecting boundaries, and the cost of a
// non-reflecting boundary against a larger domain. A patch of the surface (|x| < 0.3 cm, the top two rows) starts
// moving into a steel half-space (rho 7.8, E 2.1, nu 0.3; g, cm, us) at v_patch; the P, S and Rayleigh waves spread.
// Truncations, full width (Powell's half-models mirrored at x = 0): "narrow", 2 cm wide and 2 cm deep with absorbing
// particles on both sides (normal (+-1, 0)); "shallow", 4 cm wide and 0.6 cm deep with absorbing particles at the
// bottom (normal (0, -1)); each against the same particles in a reference 6 cm wide and 2 cm deep whose own
// boundaries are not heard at the probes before t_end. Measures: v_x, v_y at surface probes every 0.1 cm and at depth;
// the Rayleigh speed of the incident surface wave (reference) and of the wave the narrow truncation's sides send back
// (the difference narrow - reference), against rayleigh_speed() (A.35); the error at the probes against wall time for
// the absorbing truncations and for free truncations of growing width (the cost of a non-reflecting boundary).
//
// Writes to --out DIR: runs.csv (one row per run: the error at the probes, wall time), speeds.csv (arrival fits),
// series/<tag>.csv (t and v_x, v_y at each probe), summary.json.
// Powell's steel and grid, the boundaries and his leap-frog are in common/nrbc.hpp (shared with nrbc-2d and
// nrbc-plane-wave), the truncations, probes and case table in impact_cases.hpp, one run in impact_run.hpp, the wave
// speeds and errors in impact_measures.hpp, the CSV files in impact_tables.hpp, the key numbers in impact_summary.hpp.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "common/driver.hpp"
#include "common/study.hpp"
#include "impact_cases.hpp"
#include "impact_measures.hpp"
#include "impact_run.hpp"
#include "impact_summary.hpp"
#include "impact_tables.hpp"

using namespace nrbc_impact;

int main(int argc, char** argv) try {
  CLI::App app{"Powell 2012 ch. 2 §3.2(c): surface impact with non-reflecting boundaries, and their cost"};
  std::string out = "results/nrbc-impact";
  int threads = 2;
  double t_end = 6, cfl = 0.3;
  std::string gradient = "plain";
  bool quick = false;
  app.add_option("--out", out, "output directory");
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--t-end", t_end, "run length (us)")->check(CLI::Range(0.1, 100.0));
  app.add_option("--cfl", cfl, "dt = cfl dx / c_p")->check(CLI::Range(0.01, 2.0));
  app.add_option("--gradient", gradient, "plain or ncsph")->check(CLI::IsMember({"plain", "ncsph"}));
  app.add_flag("--quick", quick,
               "pipeline check: to 3 us (the incident surface wave has passed s9), the slow impact's reference, "
               "narrow and shallow truncations only");
  CLI11_PARSE(app, argc, argv);
  if (quick) t_end = std::min(t_end, 3.0);
  const auto t0 = study::Clock::now();
  std::filesystem::create_directories(out + "/series");
  const ImpactCase base{
      .cfl = cfl, .t_end = t_end, .gradient = gradient == "ncsph" ? RateFormGradient::Ncsph : RateFormGradient::Plain};

  // 1. Every truncation and its reference, recording v at the probes (series/).
  const std::vector<ImpactRun> runs = run_all(impact_cases(base, quick), threads);
  write_series(out, runs);

  // 2. The incident Rayleigh wave: the peak of |v_y| at the surface probes beyond the patch (s5..s9, x >= 0.51) in the
  // slow reference, fitted as x(t).
  const Incident incident = incident_wave(runs[0]);

  // 3. Every run against its reference: the error at the probes, and the surface wave sent back by absorbing sides.
  const std::vector<Measures> measures = measure_all(runs, incident);
  write_speeds(out, incident, measures);
  write_runs(out, runs, measures);

  // 4. Key numbers for summary.md.in.
  study::Summary sum;
  summarise(sum, runs, measures, incident, base, gradient);
  study::write_summary(sum, out, t0);
  return 0;
} catch (const std::exception& e) {
  return study::exit_on_error("nrbc-impact", e);
}
