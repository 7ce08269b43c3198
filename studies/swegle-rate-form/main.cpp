// Study: the Swegle test as Powell ran it, with the rate-form scheme (forms/rate_form.hpp: continuity, equation of
// state, Jaumann rate) instead of the additive pre-stress of the §3.3 model (studies/swegle). Each (formulation, xi)
// gets its full-state linear growth rate (growth/rate_form_spectrum.hpp, in the mirror class the kick excites and
// over all classes), its stability verdict (growth/stability_verdict.hpp: the semi-discrete growth of J and the
// predictor-corrector's one-step map growth at the run's dt, in the excited class, against the run's detection floor:
// S, U, I or B) and a nonlinear run (GMS predictor-corrector, integrate/rate_form_run.hpp) whose kinetic-energy
// growth is fitted. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, ke.csv, dt_study.csv, summary.json. Units g, cm, us (stress in Mbar).
// The options, formulations and blocks (shared with studies/swegle-nonlinear) are in common/rate_form_swegle.hpp,
// one (formulation, xi) in rate_form_case.hpp, its rows and table cells in rate_form_tables.hpp, the summary's numbers
// of the cases in rate_form_tally.hpp, the time-step study at xi = 1 in dt_study.hpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "common/rate_form_swegle.hpp"
#include "common/study.hpp"
#include "dt_study.hpp"
#include "rate_form_case.hpp"
#include "rate_form_tables.hpp"
#include "rate_form_tally.hpp"
#include "sphstab/growth/stability_verdict.hpp"

using namespace swegle_rate_form;

int main(int argc, char** argv) {
  CLI::App app{"Swegle test with the rate-form SPH scheme: full-state linear versus measured growth"};
  Options o{.out = "results/swegle-rate-form", .n = 21, .t_end = 45};
  const QuickCase quick{9, 10, "sph, sph-visc and sph-as at xi = 0.96, 1, 1.04 only, a 9 x 9 block, 10 us"};
  if (const auto exit = parse_options(app, o, quick, argc, argv)) return *exit;
  const auto t0 = study::Clock::now();

  const std::vector<Formulation> forms = o.quick ? formulations({"sph", "sph-visc", "sph-as"}) : formulations();
  const std::vector<double> xis =
      o.quick ? std::vector<double>{0.96, 1.0, 1.04} : std::vector<double>{0.96, 0.98, 0.99, 1.0, 1.01, 1.02, 1.04};
  // Blocks with fixed layers of 1, 2, 3 supports (block, centre particle, kick direction) and, for each, the mirror
  // class (px, py) = (-1, +1) of the free velocity DOFs, where the kick (+x at the centre) lies.
  SwegleOptions so;
  so.n = o.n;
  Setup s{.o = o, .steel = steel(so)};
  for (int layers = 1; layers <= 3; ++layers) {
    SwegleOptions sl = so;
    sl.layer_supports = layers;
    s.blocks.push_back(make_block(sl));
  }
  const SwegleScene& scene = s.block(1).scene;
  s.dt = time_step(scene, s.steel);
  s.detect = detection_floor(o.t_end, o.onset);  // slowest growth that reaches the onset within t_end

  // ---- 1. Every (formulation, xi): spectra, verdict and run (runs.csv, ke.csv). ----
  std::ofstream runs_csv(o.out + "/runs.csv"), ke_csv(o.out + "/ke.csv");
  runs_csv << kRunsHeader;
  ke_csv << kKeHeader;
  std::string table, ratios_table;
  Tally tally;
  double wall_linear = 0, wall_runs = 0;
  for (const Formulation& form : forms) {
    std::vector<std::string> row{"**" + form.name + "**"};
    for (double xi : xis) {
      const CaseResult c = run_case(s, form, xi);
      write_ke(ke_csv, c);
      write_run(runs_csv, c, s);
      tally.add(form, c);
      row.push_back(stability_cell(c));
      study::md_row(ratios_table, ratios_row(c));
      print_case(c);
      wall_linear += c.wall_linear, wall_runs += c.wall_run;
    }
    study::md_row(table, row);
  }

  // ---- 2. Basic SPH at xi = 1 at dt and dt/2 (dt_study.csv). ----
  const DtStudy dt = dt_study(s);

  // ---- 3. Key numbers for summary.md.in. ----
  study::Summary sum;
  sum.set("dt_table", dt.table);
  sum.set("dt_ratio_gms", dt.ratio.at("gms"), 3);
  sum.set("dt_ratio_trapezoid", dt.ratio.at("trapezoid"), 3);
  summarise_setup(sum, o, scene, s.steel, s.dt);
  sum.set("states", RateFormScheme<2>(scene.discretisation, s.steel).size());
  sum.set("reduced", 2 * scene.discretisation->free_count());
  sum.set("class_size", static_cast<int>(s.block(1).excited.cols()));
  sum.set("bulk_modulus", s.steel.bulk_modulus(), 4);
  sum.set("shear_modulus", s.steel.mu(), 4);
  sum.set("detect", s.detect, 3);
  std::string xi_list;
  for (double xi : xis) xi_list += (xi_list.empty() ? "" : ", ") + study::sig(xi);
  sum.set("xi_list", xi_list);
  sum.set("stability_table", table);
  sum.set("ratios_table", ratios_table);
  tally.summarise(sum, s.detect);
  summarise_walls(sum, wall_linear, wall_runs, t0);
  sum.write(o.out);
  std::printf("linear and measured verdicts agree in %d of %d runs; ratio measured/linear %.3f..%.3f over %d\n",
              tally.agree, tally.cases, tally.ratio_min, tally.ratio_max, tally.comparable);
  return 0;
}
