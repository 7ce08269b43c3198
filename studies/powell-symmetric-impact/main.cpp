// Study: Powell's symmetric impact [Powell2012, ch. 4 §4.1, Figs. 4.5-4.9] with basic SPH, NCSPH, S-SPH and TL-SPH
// (problems/powell_impact.hpp), in initial compression (v0 > 0) and initial expansion (v0 < 0), at several
// resolutions. The rate forms run MCM's configuration: the staggered leap-frog (algorithm 1.1) with the velocity
// smoothing (2.71) eps = 0.1 and the material card's bulk viscosity, dt = TSSFAC h / c_P; TL-SPH the linear
// total-Lagrangian form with the velocity-Verlet leap-frog at the same dt. The finite-element reference and the
// errors against it are the post-processing step (fe_reference.py, called by plot.py).
//
// Writes to --out DIR: signals.csv (t, global KE, pressure and speed at particle A, per run), runs.csv (status,
// steps, CPU seconds), snapshots.csv (every particle's position and pressure at Powell's figure time, at the
// snapshot resolution), summary.json (common/impact.hpp runs and writes the cases). Units g, cm, us (stress in Mbar).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/impact.hpp"

using namespace sphstab;

int main(int argc, char** argv) try {
  study::impact::StudyOptions opt{.out = "results/powell-symmetric-impact",
                                  .spacings = {0.05, 0.025, 0.02, 0.0125, 0.01, 0.00625},
                                  .snapshot_spacing = 0.02,  // the MCM deck's
                                  .verdict_spacing = 0.1,    // dense eigenvalues: 100 particles (J 800 x 800)
                                  .t_end = 6};               // us
  const std::vector<std::string> formulations{"sph", "ncsph", "ssph", "tl"};
  const double speed = 0.06;  // |v0| [§4.1, Fig. 4.5]
  study::impact::Settings settings{.measures = {"pressure_A", "speed_A"}};
  CLI::App app{"Powell ch. 4 §4.1: symmetric impact with SPH, NCSPH, S-SPH and TL-SPH"};
  study::impact::add_options(app, opt,
                             {.verdict_spacing_max = 0.5, .quick = "one coarse resolution (dx 0.05), to t = 2 us"});
  CLI11_PARSE(app, argc, argv);
  study::impact::prepare(opt, settings, [&] { opt.spacings = {0.05}, opt.snapshot_spacing = 0.05, opt.t_end = 2; });

  // Powell's figure times: Fig. 4.6, 3.05 us in compression; Fig. 4.8, 1.6 us in expansion.
  const auto make = [&](double dx, double sign, const std::string& f) {
    const double fig = sign > 0 ? 3.05 : 1.6;
    return study::impact::Case{
        .form = f,
        .name = sign > 0 ? "compression" : "expansion",
        .scene = {.problem = ImpactProblem::Symmetric, .spacing = dx, .speed = sign * speed, .t_end = opt.t_end},
        .snapshot_times =
            std::abs(dx - opt.snapshot_spacing) < 1e-12 ? std::vector<double>{fig} : std::vector<double>{},
        .verdict_times = {0, fig <= opt.t_end ? fig : 0.5 * opt.t_end}};
  };
  std::vector<study::impact::Case> cases, verdict_cases;
  for (double dx : opt.spacings)
    for (double sign : {1.0, -1.0})
      for (const std::string& f : formulations) cases.push_back(make(dx, sign, f)), cases.back().verdict_times.clear();
  for (double sign : {1.0, -1.0})
    for (const std::string& f : formulations) {
      verdict_cases.push_back(make(opt.verdict_spacing, sign, f));
      verdict_cases.back().snapshot_times.clear();
    }
  const auto wall0 = study::Clock::now();
  const int completed = study::impact::run_study(opt, cases, verdict_cases, settings);
  study::Summary s;
  study::impact::set_run_keys(s, cases.size(), completed, opt, speed, settings, wall0);
  s.write(opt.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "powell-symmetric-impact: error: %s\n", e.what());
  return 1;
}
