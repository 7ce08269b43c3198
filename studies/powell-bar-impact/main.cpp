// Study: Powell's asymmetrical bar impact [Powell2012, ch. 4 §4.2, Figs. 4.10-4.12] with basic SPH, NCSPH, S-SPH and
// TL-SPH (problems/powell_impact.hpp: a 4 x 0.4 cm steel bar whose left quarter starts with v_x = +v0 and the rest
// with -v0, v0 = 0.06 cm/us: "identical to the previous case save the dimensions ... only the case of an initial
// impact"), at several resolutions, to t = 40 us (Powell's S-SPH departs from TL-SPH "after 20 us"). The rate forms
// run MCM's configuration (the staggered leap-frog, (2.71) eps = 0.1, the deck's bulk viscosity, dt = TSSFAC h / c_P);
// TL-SPH the linear total-Lagrangian form. The finite-element reference and the errors against it are the
// post-processing step (plot.py, with ../common/impact_fe.py).
//
// Writes to --out DIR: signals.csv (t, global KE, the bar's length, pressure and speed at particle A, per run),
// runs.csv, snapshots.csv (every particle at t = 20 and 40 us at the snapshot resolution), summary.json
// (common/impact.hpp runs and writes the cases). Units g, cm, us (stress in Mbar).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/impact.hpp"
#include "sphstab/core/threads.hpp"

using namespace sphstab;

int main(int argc, char** argv) try {
  std::string out = "results/powell-bar-impact";
  // Whole numbers of particles across the 0.4 cm height and in the left quarter (1 cm) of the bar.
  std::vector<double> spacings{0.05, 0.04, 0.025, 0.02, 0.0125, 0.01};
  double snapshot_spacing = 0.02;  // the MCM deck's
  double verdict_spacing = 0.1;    // dense eigenvalues: 160 particles (J 1280 x 1280)
  const std::vector<std::string> formulations{"sph", "ncsph", "ssph", "tl"};
  const double speed = 0.06;  // [§4.2: as §4.1]
  double t_end = 40;          // us
  std::vector<double> snapshot_times{20, 40};
  int threads = 2;
  bool quick = false;
  study::impact::Settings settings{.measures = {"length", "pressure_A", "speed_A"}};
  CLI::App app{"Powell ch. 4 §4.2: asymmetrical bar impact with SPH, NCSPH, S-SPH and TL-SPH"};
  app.add_option("--out", out, "output directory");
  app.add_option("--spacings", spacings, "particle spacings dx (cm)")->check(CLI::PositiveNumber);
  app.add_option("--t-end", t_end, "run length (us)")->check(CLI::PositiveNumber);
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--verdict-spacing", verdict_spacing, "dx (cm) of the runs whose states get a stability verdict")
      ->check(CLI::Range(0.02, 0.2));
  app.add_flag("--quick", quick, "one coarse resolution (dx 0.05), to t = 10 us");
  CLI11_PARSE(app, argc, argv);
  if (!std::isfinite(t_end) || !(t_end > 0))  // NaN would mean the scene's default t_end
    throw std::invalid_argument("--t-end must be finite and > 0");
  if (quick) spacings = {0.05}, snapshot_spacing = 0.05, t_end = 10, snapshot_times = {10};
  std::filesystem::create_directories(out);
  settings.vtk_dir = out + "/vtk";
  set_threads(1);  // cases run side by side; each on one thread (CPU seconds are per run)

  std::vector<study::impact::Case> cases, verdict_cases;
  for (double dx : spacings)
    for (const std::string& f : formulations)
      cases.push_back(
          {.form = f,
           .name = "impact",
           .scene = {.problem = ImpactProblem::Bar, .spacing = dx, .speed = speed, .t_end = t_end},
           .snapshot_times = std::abs(dx - snapshot_spacing) < 1e-12 ? snapshot_times : std::vector<double>{}});
  for (const std::string& f : formulations)  // the initial state and 20 us, where Powell sees S-SPH deviate [§4.2]
    verdict_cases.push_back(
        {.form = f,
         .name = "impact",
         .scene = {.problem = ImpactProblem::Bar, .spacing = verdict_spacing, .speed = speed, .t_end = t_end},
         .verdict_times = {0, 20 <= t_end ? 20 : 0.5 * t_end}});
  const auto wall0 = study::Clock::now();
  const auto outcomes = study::impact::run_cases(cases, settings, threads);
  const int completed = study::impact::write_runs(out, cases, outcomes, settings);
  study::impact::write_verdicts(out, verdict_cases, study::impact::run_cases(verdict_cases, settings, threads));
  const PowellImpactOptions bar = problem_defaults({.problem = ImpactProblem::Bar});
  study::Summary s;
  study::impact::set_run_keys(s, cases.size(), completed, spacings, snapshot_spacing, speed, settings, t_end, quick,
                              wall0);
  s.set("snapshot_times", study::impact::list(snapshot_times));
  s.set("length", bar.length);
  s.set("height", bar.height);
  s.set("split", bar.split);
  s.write(out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "powell-bar-impact: error: %s\n", e.what());
  return 1;
}
