// Study: Powell's transient load on a clamped beam [Powell2012, ch. 4 §4.3, Figs. 4.13-4.18] with basic SPH, NCSPH,
// S-SPH and TL-SPH (problems/powell_impact.hpp: the bar's 4 x 0.4 cm steel block, Fig. 4.13; the first and last five
// vertical layers fixed; a 0.4 cm section at mid-span starts with v_y = -0.3 cm/us), at several resolutions, to
// t = 20 us. The clamped width is held at 0.1 cm (five layers at Powell's dx = 0.02 cm) so that every resolution
// solves the same problem. TL-SPH runs twice: Powell's linear form ("tl") and the same operators with St
// Venant-Kirchhoff finite strain ("tl-svk"): the deflection is large enough that rotations are not small. The rate
// forms run MCM's configuration (staggered leap-frog, (2.71) eps = 0.1, the deck's bulk viscosity, dt = TSSFAC h /
// c_P). The finite-element reference and the errors against it are the post-processing step (plot.py, with
// ../common/impact_fe.py).
//
// Two sensitivities (why S-SPH fails here), run after the study's own cases and written to their own files: S-SPH
// with the means of G itself instead of the first-step Shepard gradient's (4.18), "ssph-g" (common/impact.hpp), at
// Powell's load and every resolution (case "load"); and every formulation at half Powell's load, v0 = 0.15 cm/us, at
// the snapshot resolution (case "half-load").
//
// Writes to --out DIR: signals.csv (t, global KE, the deflection of the bottom mid-span particle, pressure and speed
// there, per run), runs.csv, snapshots.csv (every particle at t = 10 and 20 us at the snapshot resolution),
// sensitivity_{signals,runs,snapshots,order}.csv (the sensitivities' runs; snapshots at the last snapshot time),
// summary.json (common/impact.hpp runs and writes the cases). Units g, cm, us (stress in Mbar).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/impact.hpp"

using namespace sphstab;

int main(int argc, char** argv) try {
  study::impact::StudyOptions opt{.out = "results/powell-clamped-beam",
                                  .spacings = {0.05, 0.025, 0.02, 0.0125, 0.01},  // whole layers in the 0.1 cm clamp
                                  .snapshot_spacing = 0.02,                       // the MCM deck's
                                  // dense eigenvalues: 160 particles, one clamped layer at each end
                                  .verdict_spacing = 0.1,
                                  .t_end = 20};  // us
  const std::vector<std::string> formulations{"sph", "ncsph", "ssph", "tl", "tl-svk"};
  const double speed = 0.3;               // [§4.3]
  const double half_speed = 0.5 * speed;  // the load sensitivity: v0 / c_S about 0.47 instead of 0.93
  const double clamp = 0.1;               // cm: five layers at dx = 0.02 [Fig. 4.13]
  std::vector<double> snapshot_times{10, 20};
  study::impact::Settings settings{.measures = {"deflection", "pressure_A", "speed_A"}};
  CLI::App app{"Powell ch. 4 §4.3: transient load on a clamped beam with SPH, NCSPH, S-SPH and TL-SPH"};
  study::impact::add_options(
      app, opt,
      {.spacings = "particle spacings dx (cm), each dividing the 0.1 cm clamp",
       .verdict_spacing = "dx (cm) of the runs whose states get a stability verdict, dividing the 0.1 cm clamp",
       .verdict_spacing_max = 0.1,
       .quick = "one coarse resolution (dx 0.05), to t = 5 us, verdicts at t = 2.5 us only"});
  CLI11_PARSE(app, argc, argv);
  study::impact::prepare(
      opt, settings, [&] { opt.spacings = {0.05}, opt.snapshot_spacing = 0.05, opt.t_end = 5, snapshot_times = {5}; });

  const auto make = [&](double dx, const std::string& f, double v0 = std::nan(""), const std::string& name = "load") {
    return study::impact::Case{.form = f,
                               .name = name,
                               .scene = {.problem = ImpactProblem::Beam,
                                         .spacing = dx,
                                         .speed = std::isnan(v0) ? speed : v0,
                                         .t_end = opt.t_end,
                                         .clamp_layers = impact_clamp_layers(clamp, dx)}};
  };
  std::vector<study::impact::Case> cases, verdict_cases;
  for (double dx : opt.spacings)
    for (const std::string& f : formulations) {
      cases.push_back(make(dx, f));
      if (std::abs(dx - opt.snapshot_spacing) < 1e-12) cases.back().snapshot_times = snapshot_times;
    }
  for (const std::string& f : formulations) {  // the initial state and mid-run
    verdict_cases.push_back(make(opt.verdict_spacing, f));
    verdict_cases.back().verdict_times = {0, 10 <= opt.t_end ? 10 : 0.5 * opt.t_end};
    // --quick: one dense verdict per formulation, mid-run
    if (opt.quick) verdict_cases.back().verdict_times = {0.5 * opt.t_end};
  }
  // The sensitivities: S-SPH with the means of G at Powell's load (every resolution), and every formulation (with
  // ssph-g) at half the load at the snapshot resolution; snapshots at the last snapshot time only.
  std::vector<study::impact::Case> sensitivity_cases;
  for (double dx : opt.spacings) {
    sensitivity_cases.push_back(make(dx, "ssph-g"));
    if (std::abs(dx - opt.snapshot_spacing) < 1e-12) sensitivity_cases.back().snapshot_times = {snapshot_times.back()};
  }
  for (const std::string& f : {"sph", "ncsph", "ssph", "ssph-g", "tl", "tl-svk"}) {
    sensitivity_cases.push_back(make(opt.snapshot_spacing, f, half_speed, "half-load"));
    sensitivity_cases.back().snapshot_times = {snapshot_times.back()};
  }
  const auto wall0 = study::Clock::now();
  const int completed = study::impact::run_study(opt, cases, verdict_cases, settings);
  const auto sensitivity_wall0 = study::Clock::now();
  const int sensitivity_completed = study::impact::write_runs(
      opt.out, sensitivity_cases, study::impact::run_cases(sensitivity_cases, settings, opt.threads), settings,
      "sensitivity_");
  const double sensitivity_wall = study::seconds_since(sensitivity_wall0);
  study::Summary s;
  study::impact::set_run_keys(s, cases.size(), completed, opt, speed, settings, wall0);
  const PowellImpactOptions beam = study::impact::set_body_keys(s, ImpactProblem::Beam, snapshot_times);
  s.set("section", beam.split * beam.length);
  s.set("clamp", clamp);
  s.set("half_speed", half_speed);
  s.set("sensitivity_runs", static_cast<long>(sensitivity_cases.size()));
  s.set("sensitivity_completed", sensitivity_completed);
  s.set("sensitivity_wall_seconds", sensitivity_wall);
  s.write(opt.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "powell-clamped-beam: error: %s\n", e.what());
  return 1;
}
