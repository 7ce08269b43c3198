// Study: the oscillating cantilever plate of Gray, Monaghan & Swift [GMS2001, §7.1] with the rate-form scheme
// (forms/rate_form.hpp: continuity -rho div vhat, EOS, Jaumann rate, XSPH 1/2, viscosity, artificial stress 0.3, n 4;
// GMS predictor-corrector) on the scene of problems/gms_scenes.hpp. Periods from tip zero crossings
// (analysis/oscillation.hpp) against GMS Tables 1 and 2, thin-plate theory (7.1) and the Timoshenko beam; the linear
// SPH period from the spectrum of the initial state (growth/rate_form_spectrum.hpp); resolution, clamp length and
// time-step sensitivity; the eps = 0 root break. See README.md; the prose of the summary is summary.md.in.
//
// Phases: 1. the cases (plate_case.hpp), 2. the runs (plate_run.hpp), 3. the linear periods (linear_period.hpp),
// 4. the frozen spectra before the root break (common/gms.hpp), 5. tables and summary (plate_tables.hpp).
//
// Writes to --out DIR: periods.csv, convergence.csv, clamp.csv, dt.csv, viscosity.csv, eps.csv, root.csv, si.csv,
// linear.csv, extrapolation.csv, frozen_*.csv, series/<tag>.csv, vtk/<tag>/*, summary.json. GMS units: rho0 = c0 = 1
// (K = 1), lengths in cm, time in cm / c0.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "common/driver.hpp"
#include "common/gms.hpp"
#include "common/study.hpp"
#include "linear_period.hpp"
#include "plate_case.hpp"
#include "plate_run.hpp"
#include "plate_tables.hpp"

using namespace sphstab;
using namespace sphstab::gms_plate;

namespace {

/// The study's case groups; a case in several groups (e.g. the base plate at 10 across) runs once.
struct PlateCases {
  std::vector<PlateCase> table, conv, clamp, dt, visc, eps, root, si;
  /// Each distinct case once (by tag), with the most VTK frames any group asks of it.
  std::vector<PlateCase> distinct() const {
    std::vector<PlateCase> all;
    for (const auto* group : {&table, &conv, &clamp, &dt, &visc, &eps, &root, &si})
      for (const PlateCase& c : *group) {
        auto same = std::find_if(all.begin(), all.end(), [&](const PlateCase& a) { return a.tag == c.tag; });
        if (same == all.end())
          all.push_back(c);
        else
          same->vtk_frames = std::max(same->vtk_frames, c.vtk_frames);
      }
    return all;
  }
};

PlateCases study_cases(int across_h2, int across_h1, const std::vector<int>& convergence, int si_across,
                       double periods) {
  PlateCases g;
  // H = 2, mu = 0.22, V_f = 0.01, eps = 0.3, alpha 1, beta 2, clamp 4
  const PlateCase base{.periods = periods, .cfl = 0.5};
  auto at = [&](auto&& set) {
    PlateCase c = base;
    c.across = across_h2, c.paper = 1671.5;
    set(c);
    return with_tag(c);
  };
  // 1. GMS Tables 1 and 2.
  for (const PaperRow& p : paper_periods())
    g.table.push_back(at([&](PlateCase& c) {
      c.thickness = p.thickness, c.mu = p.mu, c.tip_speed = p.tip_speed, c.paper = p.period;
      c.across = p.thickness == 2 ? across_h2 : across_h1;
    }));
  // 2. Resolution (H = 2, mu = 0.22, V_f = 0.01), 3. clamp length, 4. time step, 5. viscosity, 6. eps at small V_f,
  // 7. the root break (mu = 0.6, V_f = 0.05, eps = 0 and 0.3, with snapshots).
  for (int n : convergence) g.conv.push_back(at([&](PlateCase& c) { c.across = n; }));
  for (int layers : {2, 3, 4, 8}) g.clamp.push_back(at([&](PlateCase& c) { c.clamp_layers = layers; }));
  for (double cfl : {0.25, 0.5}) g.dt.push_back(at([&](PlateCase& c) { c.cfl = cfl; }));
  for (auto [a, b] : {std::pair{0.06, 1.5}, {0.5, 1.0}, {1.0, 2.0}, {2.0, 4.0}})
    g.visc.push_back(at([&](PlateCase& c) { c.alpha = a, c.beta = b; }));
  for (double e : {0.0, 0.3})
    for (double v : {0.001, 0.01})
      g.eps.push_back(at([&](PlateCase& c) {
        c.eps = e, c.tip_speed = v;
        c.paper = v == 0.001 ? 1674.6 : 1671.5;
      }));
  for (double e : {0.0, 0.3})
    g.root.push_back(
        at([&](PlateCase& c) { c.mu = 0.6, c.tip_speed = 0.05, c.eps = e, c.vtk_frames = 12, c.paper = 1136.1; }));
  // 8. The plate in SI units as commonly configured: L = 0.2 m, H = 0.02 m, E = 2 MPa, nu = 0.3975, rho0 = 1000
  // kg/m^3, dx = 0.002 m (10 across), h = 1.3 dx, V_f = 0.05 m/s at the tip, run to 1 s.
  PlateCase si = base;
  si.length = 0.2, si.thickness = 0.02, si.across = si_across, si.h_factor = 1.3;
  si.youngs = 2e6, si.poisson = 0.3975, si.density = 1000, si.tip_speed = 0.05;
  si.mu = material_of(si).mu();
  si.periods = 1.0 / thin_period(si);
  g.si.push_back(with_tag(si));
  return g;
}

/// The single-case modes: the linear bending period (--spectrum) or one run with its crossings (--probe).
int single_case(const PlateCase& probe, bool spectrum, const std::string& out) {
  if (spectrum) {
    const LinearPeriod lp = linear_period(probe);
    std::printf("bending mode: T %.4f overlap %.4f softer %d growth %.3e\n", lp.period, lp.overlap, lp.softer,
                lp.growth_rate);
    return 0;
  }
  PlateCase c = probe;
  c.tag = "probe";
  const PlateRun r = run_plate(c, out);
  for (std::size_t k = 0; k < r.osc.crossings.size(); ++k)
    std::printf("crossing %.3f extreme %.5g\n", r.osc.crossings[k], r.osc.extremes[k]);
  std::printf("T %.3f thin %.3f timoshenko %.3f\n", r.osc.period, thin_period(c), timoshenko_period(c));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"GMS cantilever plate study"};
  std::string out = "results/gms-plate";
  int threads = 2, table_across_h2 = 10, table_across_h1 = 6;
  std::vector<int> convergence = {6, 10, 12, 14, 16, 20, 30, 40};
  PlateCase probe;
  bool probe_mode = false, spectrum_mode = false, quick = false;
  app.add_option("--out", out, "output directory");
  app.add_flag("--quick", quick,
               "the regression case of tests/study_quick/gms-plate: every phase on plates of 2-4 particles across "
               "(seconds)");
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--table-across-h2", table_across_h2, "particles across H = 2 for Table 1")->check(CLI::Range(2, 100));
  app.add_option("--table-across-h1", table_across_h1, "particles across H = 1 for Table 2")->check(CLI::Range(2, 100));
  app.add_option("--convergence", convergence, "particles across H = 2 of the resolution study");
  app.add_flag("--spectrum", spectrum_mode, "print the linear bending period of the case below");
  app.add_flag("--probe", probe_mode, "one run of the case below");
  app.add_option("--H", probe.thickness);
  app.add_option("--across", probe.across);
  app.add_option("--mu", probe.mu);
  app.add_option("--vf", probe.tip_speed);
  app.add_option("--eps", probe.eps);
  app.add_option("--periods", probe.periods);
  app.add_option("--cfl", probe.cfl);
  app.add_option("--clamp", probe.clamp_layers);
  app.add_option("--frames", probe.vtk_frames);
  app.add_option("--alpha", probe.alpha);
  app.add_option("--beta", probe.beta);
  CLI11_PARSE(app, argc, argv);
  try {
    std::filesystem::create_directories(out);
    if (spectrum_mode || probe_mode) return single_case(probe, spectrum_mode, out);
    const auto t_start = study::Clock::now();
    study::Summary sum;
    // 1. The cases.
    if (quick) table_across_h2 = 2, table_across_h1 = 2, convergence = {2, 3, 4};
    // --quick's plates of 2-4 across are up to twice slower than the thin plate: 5 thin periods give them 5 crossings.
    const PlateCases g =
        study_cases(table_across_h2, table_across_h1, convergence, quick ? 4 : 10, quick ? 5.0 : PlateCase{}.periods);
    const std::vector<PlateCase> all = g.distinct();
    // 2. The runs.
    std::fprintf(stderr, "gms-plate: %zu runs on %d threads\n", all.size(), threads);
    const std::vector<PlateRun> runs = run_all(all, out, threads);
    write_runs(out + "/periods.csv", runs, g.table);
    write_runs(out + "/convergence.csv", runs, g.conv);
    write_runs(out + "/clamp.csv", runs, g.clamp);
    write_runs(out + "/dt.csv", runs, g.dt);
    write_runs(out + "/viscosity.csv", runs, g.visc);
    write_runs(out + "/eps.csv", runs, g.eps);
    write_runs(out + "/root.csv", runs, g.root);
    write_runs(out + "/si.csv", runs, g.si);
    summarise_si(sum, find_run(runs, g.si.front()));
    // 3. Linear (spectral) bending periods of the initial state at the resolutions whose spectrum fits.
    write_linear_periods(out, g.conv, table_across_h2, runs, find_run(runs, g.eps[1]), sum);  // eps 0, V_f 0.01
    // 4. Frozen-state spectra of the root-break case (eps = 0 run) at about T/16 and T/8 of GMS's period (t = 70,
    // 140), before the break (t = 289 at 10 across), the later one also with the viscosity on.
    {
      const PlateCase& c = g.root[0];
      const Scene<2> scene = plate_scene(c);
      const auto frozen = study::frozen_spectra_along_run(*scene.scheme, scene.y0, {.dt = time_step(c, scene.spacing)},
                                                          {70, 140}, 140, out, sum);
      summarise_frozen(sum, frozen, 140, find_run(runs, c).break_time);
    }
    // 5. Tables and summary.
    summarise_crossings(sum, {&g.table, &g.conv, &g.clamp, &g.dt, &g.visc, &g.eps}, runs);
    summarise_tables(sum, g.table, runs);
    sum.set("across_h2", table_across_h2);
    sum.set("across_h1", table_across_h1);
    summarise_convergence(sum, out, g.conv, runs);
    summarise_sensitivities(sum, g.clamp, g.dt, g.visc, g.eps, runs);
    summarise_root(sum, g.root, runs);
    sum.set("runs", static_cast<long>(runs.size()));
    sum.set("wall_minutes", study::seconds_since(t_start) / 60, 3);
    sum.write(out);
  } catch (const std::exception& e) {
    return study::exit_on_error("study_gms_plate", e);
  }
  return 0;
}
