// Study mean-polishing: kernel corrections in the 1D momentum forms ([Powell2012, ch. 3 §4-4.1.1, ch. 4 §2]).
// What the study asks and what the sources claim: README.md; the prose of the summary: summary.md.in.
//
// For every correction x momentum form (x corrected operator) on the 1D pre-tensioned bar at u = 0: the exact
// A(T) = A0 + T A1 (complex step through the correction) and its critical loads in tension and compression
// (critical_load.hpp); momentum conservation and locality at displaced states.
//
// Writes to --out DIR:
//   tcrit.csv        N = n sweep (kernels cubic, wendland-c2, quintic; h/dx = 1.0..2.5) and the N = n_check check
//   momentum.csv     periodic lattice, displaced state: total force sum_i V_i a_i / sum_i V_i |a_i|, row and column
//                    sums of Ghat
//   locality.csv     stored/non-zero entries of G and Ghat, and of the Jacobian, per correction
//   thin_layers.csv  the same critical loads with fixed layers only one support thick (boundary sensitivity)
//   summary.json     key numbers and tables for summary.md.in (scripts/render_summary.py)
// The corrections and forms are in correction_cases.hpp, the CSV format in csv_cells.hpp, the phases in
// critical_loads.hpp, momentum_conservation.hpp, locality.hpp and thin_layers.hpp, the key numbers in
// polishing_summary.hpp.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "correction_cases.hpp"
#include "critical_loads.hpp"
#include "locality.hpp"
#include "momentum_conservation.hpp"
#include "polishing_summary.hpp"
#include "thin_layers.hpp"

using namespace mean_polishing;

int main(int argc, char** argv) {
  CLI::App app{"Kernel corrections in the 1D SPH momentum forms: critical loads, momentum, locality (Powell ch. 3-4)"};
  std::string out = "results/mean-polishing";
  int n = 30, n_check = 120;
  bool quick = false;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles of the main sweep");
  app.add_option("--n-check", n_check, "free particles of the size check");
  app.add_flag("--quick", quick,
               "pipeline check: h/dx in steps of 0.5 only, and unless given --n 16 and --n-check 24 (seconds)");
  CLI11_PARSE(app, argc, argv);
  if (quick && app.count("--n") == 0) n = 16;
  if (quick && app.count("--n-check") == 0) n_check = 24;
  std::filesystem::create_directories(out);
  const auto start = Clock::now();
  const std::vector<KernelType> kernels{KernelType::CubicSpline, KernelType::WendlandC2, KernelType::QuinticSpline};
  std::vector<double> hs;
  for (int k = 0; k <= 15; k += quick ? 5 : 1) hs.push_back(1.0 + 0.1 * k);

  // 1. Critical loads, N = n sweep and N = n_check check.
  const CriticalLoadSweep sweep = critical_load_sweep(n, n_check, hs, kernels);
  const std::vector<Row>& rows = sweep.rows;
  write_csv(out + "/tcrit.csv", rows);

  // 2. Momentum conservation on a periodic displaced lattice, row and column sums of Ghat there.
  const std::vector<MomentumRow> momentum = momentum_conservation(kernels);
  write_csv(out + "/momentum.csv", momentum);
  std::cout << "momentum done" << std::endl;

  // 3. Locality: entries of Ghat and of the Jacobian at a displaced state (N = n, cubic, h = 1.3).
  const std::vector<LocalityRow> locality = locality_counts(n);
  write_csv(out + "/locality.csv", locality);

  // 4. Boundary sensitivity: the same at N = n, cubic, h = 1.3, with fixed layers only ONE support thick.
  const std::vector<ThinRow> thin = thin_layers(n);
  write_csv(out + "/thin_layers.csv", thin);
  const double seconds = seconds_since(start);

  // 5. Key numbers. Per correction|form|target over the N = n sweep, first criterion of each direction.
  const Aggregates agg = aggregate(rows, n);
  study::Summary s;
  s.set("n", n);
  s.set("n_check", n_check);
  s.set("layer_supports", kLayerSupports);
  s.set("h_first", hs.front(), 6);
  s.set("h_last", hs.back(), 6);
  s.set("h_step", quick ? "0.5" : "0.1");
  s.set("dense_conservative_seconds", sweep.dense_conservative_seconds);
  s.set("wall_seconds", seconds);
  s.set("cases_per_row", static_cast<int>(kernels.size() * hs.size()));
  summarise_critical_loads(s, agg);
  summarise_size_check(s, rows, n, n_check);
  summarise_momentum(s, momentum);
  summarise_thin_layers(s, thin);
  summarise_locality(s, locality);
  summarise_powell(s, agg, momentum, locality);
  s.write(out);
  std::cout << "wrote " << out << "/tcrit.csv, momentum.csv, locality.csv, thin_layers.csv, summary.json ("
            << sig(seconds, 3) << " s)\n";
  return 0;
}
