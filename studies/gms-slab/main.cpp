// Study: the plastic slab in tension of Gray, Monaghan & Swift [GMS2001, §7.3] with the rate-form scheme
// (forms/rate_form.hpp: continuity -rho tr L, EOS, Jaumann rate, XSPH 1/2, viscosity 1 / 2 with the compression switch,
// artificial stress eps = 0 or 0.3, n = 4; von Mises radial return, yield 0.03; GMS predictor-corrector with a Verlet
// neighbour list). The particles within 0.2 of each end are driven at +-5e-6 along x (RateFormScheme::set_driven).
// Measures: the width profile between the driven zones (analysis/neck.hpp), the neck onset (localisation: narrowest
// width against the median), the break (the two driven ends no longer joined by bonds, analysis/fragments.hpp) with
// its time, place and the neck width just before it. Runs go in chunks from the previous chunk's state and stop once
// the slab has broken plus a margin. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, series/<tag>.csv, profiles.csv, frames.csv, vtk/<tag>/*.vtp + <tag>.pvd,
// summary.json. GMS units: rho0 = c0 = 1 (K = 1), lengths in cm, time in cm / c0.
// The constants and the table of runs are in slab_case.hpp, one run in slab_run.hpp (its breaks in slab_break.hpp),
// the CSV files in slab_tables.hpp, the key numbers in slab_summary.hpp, the frozen-state spectra in slab_spectra.hpp.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/driver.hpp"
#include "common/gms.hpp"
#include "common/study.hpp"
#include "slab_case.hpp"
#include "slab_run.hpp"
#include "slab_spectra.hpp"
#include "slab_summary.hpp"
#include "slab_tables.hpp"

using namespace gslab;
namespace fs = std::filesystem;

int main(int argc, char** argv) try {
  study::DriverCli cli{"GMS 2001 §7.3: plastic slab in tension with and without the artificial stress",
                       "results/gms-slab", "pipeline check: dp 0.08, both runs to t = 40"};
  std::vector<double> dps = {0.04, 0.05};
  double t_max0 = 200, t_max3 = 650, margin = 40, chunk = 10, skin = 0.5;
  int threads = 2, frames = 12;
  double dp_spectrum = 0.0625;
  std::vector<double> spectrum_times = {60, 100};
  cli.app.add_option("--dp", dps, "particle spacings, comma list (GMS 0.016: about 30 CPU minutes for eps = 0.3)")
      ->delimiter(',')
      ->check(CLI::Range(0.004, 0.2));
  cli.app.add_option("--t-max-eps0", t_max0, "longest eps = 0 run (GMS break 119)")->check(CLI::Range(1.0, 1e5));
  cli.app.add_option("--t-max-eps03", t_max3, "longest eps = 0.3 run (GMS break 542)")->check(CLI::Range(1.0, 1e5));
  cli.app
      .add_option("--margin", margin,
                  "run on at most this long after the break (1.5 dp bonds) when the ends have not separated (2h)")
      ->check(CLI::Range(0.0, 1e5));
  cli.app.add_option("--chunk", chunk, "chunk length between break checks (whole time units)")
      ->check(CLI::Range(1.0, 1000.0));
  cli.app.add_option("--skin", skin, "Verlet skin of the neighbour list in dp")->check(CLI::Range(0.05, 10.0));
  cli.add_threads(threads);
  cli.app.add_option("--frames", frames, "regular VTK frames per run (0: none)")->check(CLI::Range(0, 1000));
  study::add_frozen_spectra_options(cli.app, dp_spectrum, spectrum_times, 0.2, 0.01,
                                    "times of the frozen spectra (the last also with the viscosity on)");
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick)
    dps = {0.08}, t_max0 = t_max3 = 40, frames = std::min(frames, 4), dp_spectrum = 0.125, spectrum_times = {20};
  std::sort(spectrum_times.begin(), spectrum_times.end());
  std::sort(dps.begin(), dps.end());
  dps.erase(std::unique(dps.begin(), dps.end()), dps.end());
  const auto t0 = study::Clock::now();
  const std::string load_start = study::load_average();
  const std::string& out = cli.out;
  fs::create_directories(out + "/series");

  // ---- The runs: every dp with eps = 0.3 and 0, longest first on the threads; series/<tag>.csv per run. ----
  const std::vector<SlabCase> cases = slab_cases(dps, t_max0, t_max3, margin, chunk, skin, frames);
  const std::vector<std::size_t> order = longest_first(cases);
  std::fprintf(stderr, "gms-slab: %zu runs on %d threads\n", cases.size(), threads);

  std::vector<SlabRun> runs(cases.size());
  std::vector<std::vector<FrameInfo>> frame_logs(cases.size());
  std::vector<std::vector<std::string>> profile_logs(cases.size());
  std::mutex m;
  study::parallel_for(order.size(), threads, [&](std::size_t q) {
    const std::size_t k = order[q];
    runs[k] = run_slab(cases[k], out, frame_logs[k], profile_logs[k]);
    write_series(out, runs[k]);
    std::lock_guard<std::mutex> lock(m);
    const SlabRun& r = runs[k];
    std::printf(
        "%-16s %5d particles, %6ld steps to t = %.0f, %7.1f s wall (%.1f s CPU), %.3g us per particle-step "
        "(%.3g CPU), %ld builds: %s; "
        "neck %.4g, break %.4g (1.5 dp) / %.4g (2h) at x = %.3g, width before %.3g = %.3g dp\n",
        r.c.tag.c_str(), r.particles, r.cost.steps, r.t_stop, r.cost.wall, r.cost.cpu, r.cost.us_per_particle_step(),
        r.cost.us_cpu(), r.cost.neighbour_builds, r.status.c_str(), r.t_neck, r.brk.t, r.brk_support.t, r.brk.left.x,
        r.brk.width_before(), r.brk.width_before() / r.c.dp);
    std::fflush(stdout);
  });

  // ---- frames.csv, profiles.csv, runs.csv. ----
  write_frames_profiles(out, frame_logs, profile_logs);
  write_runs(out, runs);

  // ---- Key numbers for summary.md.in. ----
  study::Summary s;
  summarise_runs(s, runs, dps);
  s.set("t_max_eps0", t_max0, 4);
  s.set("t_max_eps03", t_max3, 4);
  s.set("margin", margin, 3);
  s.set("chunk", chunk, 3);
  s.set("skin", skin, 3);
  s.set("neck_ratio", kNeckRatio, 3);
  s.set("c_p", ElasticMaterial::from_bulk_shear(1, kMu, 1).p_wave_speed(), 4);
  s.set("threads", threads);
  s.set("load_start", load_start);
  s.set("load_end", study::load_average());
  // ---- Frozen-state spectra along the eps = 0 run at a coarser grid. ----
  if (dp_spectrum > 0) {
    const auto ts = study::Clock::now();
    frozen_spectra(dp_spectrum, skin, spectrum_times, out, s);
    s.set("frozen_wall", study::seconds_since(ts), 3);
  }
  study::write_summary(s, out, t0, {.wall_key = "wall_total"});
  std::printf("gms-slab done in %.1f s\n", study::seconds_since(t0));
  return 0;
} catch (const std::exception& e) {
  return study::exit_on_error("study_gms_slab", e);
}
