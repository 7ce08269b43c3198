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

using namespace sphstab;

int main(int argc, char** argv) try {
  study::impact::StudyOptions opt{
      .out = "results/powell-bar-impact",
      // Whole numbers of particles across the 0.4 cm height and in the left quarter (1 cm) of the bar.
      .spacings = {0.05, 0.04, 0.025, 0.02, 0.0125, 0.01},
      .snapshot_spacing = 0.02,  // the MCM deck's
      .verdict_spacing = 0.1,    // dense eigenvalues: 160 particles (J 1280 x 1280)
      .t_end = 40};              // us
  const std::vector<std::string> formulations{"sph", "ncsph", "ssph", "tl"};
  const double speed = 0.06;  // [§4.2: as §4.1]
  std::vector<double> snapshot_times{20, 40};
  study::impact::Settings settings{.measures = {"length", "pressure_A", "speed_A"}};
  CLI::App app{"Powell ch. 4 §4.2: asymmetrical bar impact with SPH, NCSPH, S-SPH and TL-SPH"};
  study::impact::add_options(app, opt,
                             {.verdict_spacing_max = 0.2, .quick = "one coarse resolution (dx 0.05), to t = 10 us"});
  CLI11_PARSE(app, argc, argv);
  study::impact::prepare(opt, settings, [&] {
    opt.spacings = {0.05}, opt.snapshot_spacing = 0.05, opt.t_end = 10, snapshot_times = {10};
  });

  std::vector<study::impact::Case> cases, verdict_cases;
  for (double dx : opt.spacings)
    for (const std::string& f : formulations)
      cases.push_back(
          {.form = f,
           .name = "impact",
           .scene = {.problem = ImpactProblem::Bar, .spacing = dx, .speed = speed, .t_end = opt.t_end},
           .snapshot_times = std::abs(dx - opt.snapshot_spacing) < 1e-12 ? snapshot_times : std::vector<double>{}});
  for (const std::string& f : formulations)  // the initial state and 20 us, where Powell sees S-SPH deviate [§4.2]
    verdict_cases.push_back(
        {.form = f,
         .name = "impact",
         .scene = {.problem = ImpactProblem::Bar, .spacing = opt.verdict_spacing, .speed = speed, .t_end = opt.t_end},
         .verdict_times = {0, 20 <= opt.t_end ? 20 : 0.5 * opt.t_end}});
  const auto wall0 = study::Clock::now();
  const int completed = study::impact::run_study(opt, cases, verdict_cases, settings);
  study::Summary s;
  study::impact::set_run_keys(s, cases.size(), completed, opt, speed, settings, wall0);
  const PowellImpactOptions bar = study::impact::set_body_keys(s, ImpactProblem::Bar, snapshot_times);
  s.set("split", bar.split);
  s.write(opt.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "powell-bar-impact: error: %s\n", e.what());
  return 1;
}
