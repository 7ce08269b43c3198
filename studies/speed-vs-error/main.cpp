// Study speed-vs-error: the 1D velocity-jump problem [Powell2012, ch. 2 §3.1, (2.68)] on a 1 cm bar with free
// ends, solved with linear SPH (total- and updated-Lagrangian) and compared with the exact d'Alembert solution.
// Writes runs.csv, error_history.csv, profiles.csv, stability.csv, rates.csv, powell.csv, ul_linearised.csv,
// ul_tensile_seed.csv and summary.json to --out (see README.md); the prose of summary.md is in summary.md.in.
// The formulations are in bar_formulations.hpp, one run of the sweep in velocity_jump_run.hpp, the time-step limits
// in stability_limits.hpp, the rates in convergence_rates.hpp, the [Powell2012, Table 2.1] comparison in
// powell_table21.hpp, the UL tensile instability in ul_tensile_instability.hpp, the key numbers in speed_summary.hpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bar_formulations.hpp"
#include "common/study.hpp"
#include "convergence_rates.hpp"
#include "powell_table21.hpp"
#include "speed_summary.hpp"
#include "sphstab/io/progress.hpp"
#include "stability_limits.hpp"
#include "ul_tensile_instability.hpp"
#include "velocity_jump_run.hpp"

using namespace speed_error;
using study::fixed;
using study::sig;

int main(int argc, char** argv) {
  CLI::App app{"speed-vs-error: 1D velocity-jump bar, SPH error against particle count and wall time"};
  std::string out = "results/speed-vs-error";
  bool quick = false;
  double courant = kDefaultCourant;
  app.add_option("--out", out, "output directory");
  app.add_flag("--quick", quick, "small smoke-test sweep (N <= 200, one kernel)");
  app.add_option("--courant", courant, "CFL number C in dt = C h / c");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out);
  const auto wall0 = Clock::now();

  BarJumpProblem problem;  // L = 1 cm, rho = 7.8, E = 2.1, jump at 0.35, ±0.01 cm/µs, free ends
  const BarJumpExact exact(problem);
  const double t_end = 1.5, c = exact.wave_speed();
  const SweepSettings settings{problem, t_end, c, courant};
  const std::vector<int> ns = quick ? std::vector<int>{50, 100, 200} : std::vector<int>{50, 100, 200, 400, 800, 1600};
  const std::vector<KernelType> kernels =
      quick ? std::vector<KernelType>{KernelType::CubicSpline}
            : std::vector<KernelType>{KernelType::CubicSpline, KernelType::WendlandC2};
  const std::vector<double> ratios = {1.0, 1.3, 2.0};
  const std::vector<BarBoundary> boundaries = {BarBoundary::Mirror, BarBoundary::None};

  // ---- 1. The sweep: stability limits and runs per kernel, h/dx, boundary, formulation (and n). ----
  RunTables tables(out);
  CsvWriter stab_csv = stability_table(out);
  std::vector<StabRow> stab_rows;
  // Exact profile for the plots.
  write_exact_profile(tables.profiles, exact, t_end);
  std::vector<RunRecord> records;
  long total_runs =
      static_cast<long>(ns.size() * kernels.size() * ratios.size() * boundaries.size() * formulations().size());
  ProgressLine progress("speed-vs-error", 1.0);
  for (KernelType kt : kernels)
    for (double hr : ratios)
      for (BarBoundary bnd : boundaries)
        for (const auto& form : formulations()) {
          stability_limits(stab_csv, stab_rows, kt, hr, bnd, form, ns, courant, c);
          for (int n : ns) {
            const RunRecord rec = run_case(settings, kt, hr, bnd, form, n, tables);
            write_run(tables.runs, rec);
            records.push_back(rec);
            progress.update(static_cast<double>(records.size()), static_cast<double>(total_runs),
                            rec.kernel + " h/dx=" + sig(hr, 4) + " " + rec.boundary + " " + rec.form +
                                " N=" + std::to_string(n) + " " + rec.status);
          }
        }
  progress.finish(std::to_string(records.size()) + " runs");

  // ---- 2. Convergence rates (rates.csv). ----
  const std::vector<RateRow> rate_rows = convergence_rates(out, records, kernels, ratios, boundaries, ns);

  // ---- 3. Powell Table 2.1, reference row (powell.csv). ----
  const auto powell_rows = powell_comparison(out, problem, courant, c);

  // ---- 4. UL tensile instability: linearised (ul_linearised.csv) and seeded (ul_tensile_seed.csv). ----
  const std::vector<LinRow> lin_rows = ul_linearised(out, kernels, ratios);
  const SeededGrowth seeded = seeded_sawtooth(out, courant, c);

  const double wall = seconds_since(wall0);

  // ---- 5. Key numbers for summary.md.in. ----
  const int nmax = ns.back();
  const std::string k0 = "cubic", k1 = quick ? "cubic" : "wendland-c2";
  study::Summary sum;
  sum.set("out", out);
  sum.set("quick_flag", quick ? " --quick" : "");
  sum.set("wall_seconds", fixed(wall, 1));
  sum.set("c", fixed(c, 6));
  sum.set("kernels", quick ? "cubic B-spline" : "cubic B-spline and Wendland C2");
  std::string n_list;
  for (int n : ns) n_list += (n_list.empty() ? "" : ", ") + std::to_string(n);
  sum.set("n_list", n_list);
  sum.set("runs_per_config", static_cast<int>(ns.size()));
  sum.set("courant", courant, 6);
  sum.set("nmax", nmax);
  sum.set("k1", k1);
  summarise_accuracy(sum, records, rate_rows, k0, k1, nmax);
  summarise_updated_lagrangian(sum, records, k0, nmax, lin_rows, seeded);
  summarise_cost_and_time_step(sum, records, stab_rows, k0, nmax, courant);
  summarise_tables(sum, records, lin_rows, rate_rows, ratios, k0, nmax);
  summarise_powell(sum, powell_rows);
  summarise_blowups(sum, records);
  sum.write(out);
  std::fprintf(stderr, "[speed-vs-error] wrote %s/summary.json (wall %.1f s)\n", out.c_str(), wall);
  return 0;
}
