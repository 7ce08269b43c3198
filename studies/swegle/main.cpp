// Study: the Swegle stability test [Powell2012, ch. 4 §2.2, Figs. 4.1/4.2] for every SPH formulation, with the
// linear-theory growth rate of the same force function next to the measured kinetic-energy growth, a 1D version,
// and the energy conservation of the conservative form. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, ke.csv, equilibrium.csv, energy.csv, energy_series.csv, onedim_runs.csv,
// onedim_ke.csv, modes/*.vtp, summary.json. Units: g, cm, us (stress in g cm^-1 us^-2 = 1e11 Pa = Mbar).
// The options are in swegle_options.hpp, the formulations in swegle_formulations.hpp, the linear theory in
// linear_theory.hpp, the wavevectors and snapshots of modes in mode_shapes.hpp, the 2D runs in swegle_runs.hpp, the
// energy conservation in energy_conservation.hpp, the 1D version in onedim_runs.hpp, the key numbers in
// swegle_summary.hpp.
#include <malloc.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "energy_conservation.hpp"
#include "linear_theory.hpp"
#include "onedim_runs.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/problems/swegle.hpp"
#include "swegle_formulations.hpp"
#include "swegle_options.hpp"
#include "swegle_runs.hpp"
#include "swegle_summary.hpp"

using namespace swegle_study;

int main(int argc, char** argv) {
  // Force evaluations allocate and free operator matrices every step; keep glibc from returning (and re-faulting)
  // those pages each time (as in benchmarks/jacobian_benchmark.cpp). Affects speed only.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);

  CLI::App app{"Swegle test (Powell ch. 4 Fig. 4.1/4.2): every formulation, linear vs nonlinear growth"};
  Config c;
  app.add_option("--out", c.out, "output directory");
  app.add_option("--t-end", c.t_end, "2D run length (us)")->check(CLI::PositiveNumber);
  app.add_option("--t-end-1d", c.t_end_1d, "1D run length (dx / c)")->check(CLI::PositiveNumber);
  app.add_option("--xi", c.xis, "volume strains xi = V/V0");
  app.add_option("--forms", c.only, "formulations to run (default: all available)");
  app.add_option("--energy-steps", c.energy_steps, "steps of the energy-conservation run at the CFL step")
      ->check(CLI::PositiveNumber);
  app.add_option("--record-every", c.record_every, "kinetic-energy sample interval (steps)")
      ->check(CLI::PositiveNumber);
  bool quick = false;
  app.add_flag("--quick", quick,
               "the study's test case: sph, tl and conservative at xi 0.98, 1, 1.02, t_end 5 us, 1D t_end 100, 500 "
               "energy steps (each unless given)");
  CLI11_PARSE(app, argc, argv);
  if (quick) apply_quick(c, app);
  for (double xi : c.xis)
    if (!(xi > 0)) {
      std::cerr << "study_swegle: xi must be > 0 (got " << xi << ")\n";
      return 2;
    }
  std::filesystem::create_directories(c.out + "/modes");
  const auto wall0 = study::Clock::now();
  c.detect = detection_floor(c.t_end, c.onset);  // log(onset) / (2 t_end)

  // ---- The formulations, the block at xi = 1, its mirror classes and the time step. ----
  std::vector<Formulation> forms;
  for (const Formulation& f : formulations())
    if (c.only.empty() || std::find(c.only.begin(), c.only.end(), f.name) != c.only.end()) forms.push_back(f);
  const SwegleScene base = make_swegle_scene({});
  const Classes classes = make_classes(base);
  const double dx = base.options.spacing, dt = 0.3 * base.h / base.wave_speed;
  std::cout << "Swegle block: " << base.options.n << " x " << base.options.n << " free particles + "
            << fixed_layers_needed(base.discretisation->kernel.support_radius(base.h), dx)
            << " fixed layers, dx = " << dx << " cm, h = 1.3 dx, dt = " << dt << " us, t_end = " << c.t_end
            << " us; excited class (px, py) = (" << classes.mirror.parity[classes.mirror.excited].first << ", "
            << classes.mirror.parity[classes.mirror.excited].second << ")\n";

  // ---- 1. Every (formulation, xi) 2D run with its linear theory (runs.csv, ke.csv, equilibrium.csv, modes/). ----
  const std::vector<Row> rows = run_2d(forms, c, classes, dt);
  const double wall_2d = study::seconds_since(wall0);

  // ---- 2. Energy conservation of the conservative form and TL at xi = 1 (energy.csv, energy_series.csv). ----
  const std::vector<EnergyRow> energy = energy_conservation(c, dt);

  // ---- 3. The 1D version (onedim_runs.csv, onedim_ke.csv). ----
  const std::vector<Row1D> rows1 = run_1d(c);
  const double wall_total = study::seconds_since(wall0);

  // ---- 4. Key numbers for summary.md.in. ----
  study::Summary s;
  summarise_parameters(s, base, c, dt, rows);
  s.set("wall_2d", wall_2d, 3), s.set("wall_rest", wall_total - wall_2d, 3), s.set("wall_total", wall_total, 3);
  summarise_2d_tables(s, rows, forms, c);
  summarise_2d_lists(s, rows, c);
  summarise_energy_1d(s, energy, rows1, c);
  summarise_powell(s, rows, c);
  s.write(c.out);
  std::cout << "wrote " << c.out << "/summary.json; total " << sig(wall_total) << " s\n";
  return 0;
}
