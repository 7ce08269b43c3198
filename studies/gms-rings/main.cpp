// Study: the colliding rubber rings of Gray, Monaghan & Swift [GMS2001, §7.2] with the rate-form scheme
// (forms/rate_form.hpp: continuity -rho tr L, EOS, Jaumann rate, XSPH 1/2, viscosity 1 / 2 with the compression switch,
// artificial stress eps = 0 or 0.3, n = 4; GMS predictor-corrector with a Verlet neighbour list). Measures over time:
// fragments (bond graph, analysis/fragments.hpp) of the whole scene and of each ring, contact (closest pair of
// particles of different rings against the kernel support 2h), ring centre-of-mass velocities (rebound) and kinetic
// energy. Also the SI configuration of the issue (17608 particles): a short timed run by default, the whole collision
// with --si-full. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, series/<tag>.csv, frames.csv, vtk/<tag>/*.vtp + <tag>.pvd, summary.json. GMS units:
// rho0 = c0 = 1 (K = 1), lengths in cm, time in cm / c0; the SI case in m, s, Pa, kg/m^3.
// The materials and the table of runs are in ring_case.hpp, one run in ring_run.hpp, what it measured in
// ring_measures.hpp, the CSV files in ring_tables.hpp, the key numbers in ring_summary.hpp, the frozen-state spectra
// in ring_spectra.hpp.
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
#include "ring_case.hpp"
#include "ring_measures.hpp"
#include "ring_run.hpp"
#include "ring_spectra.hpp"
#include "ring_summary.hpp"
#include "ring_tables.hpp"

using namespace grings;

int main(int argc, char** argv) try {
  study::DriverCli cli{"GMS 2001 §7.2: colliding rubber rings with and without the artificial stress",
                       "results/gms-rings",
                       "pipeline check: dp 0.2, t_end 20, 5 SI steps, 3 frames, spectra at dp 0.5"};
  double t_end = 250, dp = 0.1, gap = 0.2, skin = 0.5;
  int threads = 2, frames = 12;
  long si_steps = 300;
  bool si_full = false;
  double dp_spectrum = 0.25;
  std::vector<double> spectrum_times = {5, 25, 45};
  cli.app.add_option("--t-end", t_end, "run length in cm/c0 (default 250, about 2 ovalling periods)")
      ->check(CLI::Range(0.01, 1e5));
  cli.app.add_option("--dp", dp, "grid spacing of the GMS-unit rings in cm (GMS 0.1; thickness 1 needs dp <= 0.5)")
      ->check(CLI::Range(1e-3, 0.5));
  cli.app.add_option("--gap", gap, "distance between the outer circles in cm (GMS give none)")
      ->check(CLI::Range(0.0, 10.0));
  cli.app.add_option("--skin", skin, "Verlet skin of the neighbour list in dp (rebuild after skin / 2 of motion)")
      ->check(CLI::Range(0.05, 10.0));
  cli.add_threads(threads);
  cli.app.add_option("--frames", frames, "VTK frames per run (0: none)")->check(CLI::Range(0, 1000));
  cli.app.add_option("--si-steps", si_steps, "steps of the timed SI run")->check(CLI::Range(1L, 1000000L));
  cli.app.add_flag("--si-full", si_full, "run the SI configuration over the whole collision (about 20 min per eps)");
  study::add_frozen_spectra_options(cli.app, dp_spectrum, spectrum_times, 0.5, 0.0,
                                    "times of the frozen spectra (the first also with the viscosity on), cm/c0");
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick)
    dp = 0.2, t_end = 20, si_steps = 5, frames = std::min(frames, 3), dp_spectrum = 0.5, spectrum_times = {5};
  std::sort(spectrum_times.begin(), spectrum_times.end());
  const auto t0 = study::Clock::now();
  const std::string load_start = study::load_average();
  const std::string& out = cli.out;
  std::filesystem::create_directories(out + "/series");

  // ---- The runs, in case order on the threads; series/<tag>.csv per run. ----
  const std::vector<RingCase> cases = ring_cases(dp, gap, t_end, frames, skin, si_steps, si_full);
  std::fprintf(stderr, "gms-rings: %zu runs on %d threads\n", cases.size(), threads);
  std::vector<RingRun> runs(cases.size());
  std::mutex m;
  study::parallel_for(cases.size(), threads, [&](std::size_t k) {
    runs[k] = run_rings(cases[k], out);
    write_series(out, runs[k]);
    std::lock_guard<std::mutex> lock(m);
    const RingRun& r = runs[k];
    std::printf(
        "%-12s %5d particles, %6ld steps, %7.1f s wall (%.1f s CPU), %.3g us per particle-step (%.3g CPU), "
        "%ld builds: %s\n",
        r.c.tag.c_str(), r.particles, r.cost.steps, r.cost.wall, r.cost.cpu, r.cost.us_per_particle_step(),
        r.cost.us_cpu(), r.cost.neighbour_builds, r.status.c_str());
    std::fflush(stdout);
  });

  // ---- What each run measured; runs.csv. ----
  std::vector<RingMeasures> measures;
  for (const RingRun& r : runs) measures.push_back(measure(r));
  write_runs(out, runs, measures);

  // ---- Key numbers for summary.md.in. ----
  study::Summary s;
  summarise_runs(s, runs, measures, t_end);
  summarise_loops(s, runs);
  const RingRun& g = runs.front();
  const RingRun& si_run = find_run(runs, true, 0.3, PairLoop::Rows);
  const ElasticMaterial si = si_material();
  s.set("particles", g.particles);
  s.set("per_ring", g.per_ring);
  s.set("break_share_pct", 100 * kBreakShare, 3);
  s.set("break_particles", static_cast<int>(kBreakShare * g.per_ring));
  s.set("dp", dp, 3);
  s.set("h", g.h, 3);
  s.set("gap", gap, 3);
  s.set("dt", g.dt, 4);
  s.set("t_end", t_end, 4);
  s.set("speed", g.speed, 3);
  s.set("c_p", gms_material().p_wave_speed(), 4);
  s.set("ovalling_period", ring_ovalling_period(1, 0.22, 3.5, 1), 3);
  s.set("si_particles", si_run.particles);
  s.set("si_per_ring", si_run.per_ring);
  s.set("si_sound_speed", si.sound_speed(), 4);
  s.set("si_bulk_modulus", si.bulk_modulus(), 4);
  s.set("si_shear_modulus", si.mu(), 4);
  s.set("si_speed", si_run.speed, 4);
  s.set("si_dt", si_run.dt, 3);
  s.set("si_mode", si_full ? "the whole collision (--si-full)"
                           : "a timed run of " + std::to_string(si_steps) + " steps (the whole collision: --si-full)");
  s.set("threads", threads);
  s.set("skin", skin, 3);

  // ---- Frozen-state spectra along the eps = 0 collision at a coarser grid. ----
  if (dp_spectrum > 0) {
    const auto ts = study::Clock::now();
    frozen_spectra(dp_spectrum, gap, skin, spectrum_times, out, s);
    s.set("frozen_wall", study::seconds_since(ts), 3);
  }
  s.set("load_start", load_start);
  s.set("load_end", study::load_average());
  study::write_summary(s, out, t0, {.wall_key = "wall_total"});
  std::printf("gms-rings done in %.1f s\n", study::seconds_since(t0));
  return 0;
} catch (const std::exception& e) {
  return study::exit_on_error("study_gms_rings", e);
}
