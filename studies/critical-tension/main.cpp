// Study: critical tension of a 1D SPH bar [Powell2012, ch. 3, Fig. 3.2 and conclusions p. 99-100].
// Computes and writes data (fig32.csv, forms.csv, versus_n.csv, exponents.csv, growth.csv, timing.csv,
// summary.json; see README.md); the prose of summary.md is in summary.md.in (scripts/render_summary.py).
// The cases and their computation are in tension_cases.hpp, the CSV tables in tension_tables.hpp, the key numbers in
// tension_summary.hpp.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "tension_cases.hpp"
#include "tension_summary.hpp"
#include "tension_tables.hpp"

using namespace tcrit;

int main(int argc, char** argv) {
  CLI::App app{"Critical tension study (Powell Fig. 3.2)"};
  std::string out_dir = "results/critical-tension";
  app.add_option("--out", out_dir, "Output directory");
  bool quick = false;
  app.add_flag("--quick", quick, "h/dx in steps of 0.2 instead of 0.05 (the study's test case)");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out_dir);
  const auto t_start = Clock::now();
  const std::vector<double> hs = h_grid(quick ? 4 : 1);
  const int n_cons = initial_stress_multiplier(MomentumForm::Conservative);

  // ---- Fig. 3.2: N = 30, conservative. Timed sweeps per method (jacobian assembly included). ----
  std::cout << "critical-tension: N = 30 sweep, " << kKernels.size() << " kernels x " << hs.size() << " h\n";
  std::map<std::string, double> timing;
  for (auto [name, method] :
       {std::pair{"eig", CriticalLoadMethod::Eigen}, std::pair{"bisect", CriticalLoadMethod::Bisection},
        std::pair{"both", CriticalLoadMethod::Both}})
    timing[name] = timed_sweep(method, hs, n_cons);

  std::vector<SweepRow> sweep;
  for (KernelType type : kKernels)
    for (double h : hs) sweep.push_back(sweep_case(type, h, n_cons));
  write_fig32(out_dir, sweep);
  write_forms(out_dir, sweep);

  // ---- T_crit versus N. ----
  std::cout << "critical-tension: T_crit versus N (" << kSizes.front() << " .. " << kSizes.back() << ")\n";
  std::vector<NRow> nrows;
  const auto t_n = Clock::now();
  for (KernelType type : kKernels)
    for (double h : kHVersusN)
      for (int n : kSizes) nrows.push_back(versus_n_case(type, h, n));
  const double versus_n_seconds = seconds_since(t_n);
  write_versus_n(out_dir, nrows, n_cons);
  std::vector<ExponentFit> fits;
  for (KernelType type : kKernels)
    for (double h : kHVersusN) fits.push_back(fit_exponents(nrows, type, h, n_cons));
  write_exponents(out_dir, fits);

  // ---- Growth rates above T_crit (N = 30, dense nonsymmetric eigen, h = 1.2). ----
  std::vector<GrowthRow> growth;
  for (KernelType type : kKernels)
    for (GrowthRow& r : growth_cases(type)) growth.push_back(std::move(r));
  write_growth(out_dir, growth);
  write_timing(out_dir, timing, versus_n_seconds);

  // ---- Key numbers for summary.md.in. ----
  study::Summary sum;
  summarise_timing(sum, timing, static_cast<int>(nrows.size()), versus_n_seconds);
  summarise_sweep(sum, sweep);
  summarise_versus_n(sum, nrows, fits, n_cons);
  summarise_growth(sum, growth);
  sum.set("wall_seconds", seconds_since(t_start));
  sum.write(out_dir);
  std::cout << "critical-tension: wrote " << out_dir << " in " << sig(seconds_since(t_start)) << " s\n";
  return 0;
}
