// Study forms: the four SPH momentum forms (uncorrected, plus, minus, conservative) in 1D, in tension AND compression
// [Powell2012, ch. 3 §3-4, (3.40), Theorem 3.8, Example 3.9, Theorem 3.10 and the conditions after it].
// Absorbs the former form_asymmetry study (Jacobian symmetry of each form, 1D and 2D, same configurations and code).
//
// Writes tcrit.csv, crosscheck.csv, compression_conditions.csv, asymmetry.csv, asymmetry_vs_amplitude.csv and
// summary.json to --out (see README.md); the prose of summary.md is in summary.md.in (scripts/render_summary.py).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/study.hpp"
#include "compression_conditions.hpp"
#include "jacobian_symmetry.hpp"
#include "tension_compression.hpp"

using namespace forms_study;

int main(int argc, char** argv) {
  study::DriverCli cli{"The 1D SPH momentum forms in tension and compression; Jacobian symmetry (Powell ch. 3)",
                       "results/forms",
                       "h/dx in steps of 0.5, the kernels' Fourier transforms in steps of 0.1 (smoke run)"};
  int n = 30;
  cli.app.add_option("--n", n, "free particles");
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  const auto start = study::Clock::now();
  std::vector<double> hs;
  for (int k = 0; k <= 30; k += cli.quick ? 10 : 1) hs.push_back(1.0 + 0.05 * k);
  const std::vector<MomentumForm> forms = all_momentum_forms();

  // 1. T_crit in tension and compression, analytic route.
  const TcritTable tcrit = critical_loads_1d(hs, n, forms);
  write_tcrit(cli.out + "/tcrit.csv", tcrit.rows);

  // 2. Cross-check: general affine route from the force functions' complex-step Jacobians.
  const CrossCheck cross = crosscheck_affine(cli.out + "/crosscheck.csv", {1.2, 1.6, 2.0, 2.4}, n, forms);
  std::cout << "crosscheck: max relative difference " << cross.max << std::endl;

  // 3. Compression conditions (Powell, after Theorem 3.10).
  const Conditions conditions = compression_conditions(hs, n, tcrit, cli.quick ? 0.1 : 0.01);
  write_compression_conditions(cli.out + "/compression_conditions.csv", conditions.rows);

  // 4. Jacobian symmetry (the former form_asymmetry study: same configurations, kernel cubic, h = 1.3).
  const AsymmetrySetup setup{.h = 1.3, .n1 = 40, .n2 = 12, .material = ElasticMaterial::from_lame(1.0, 1.0, 1.0)};
  const std::vector<AsymRow> asym = jacobian_asymmetries(setup, forms);
  write_asymmetry(cli.out + "/asymmetry.csv", asym);
  const std::vector<AmpRow> amp = asymmetry_vs_amplitude(setup, forms);
  write_asymmetry_vs_amplitude(cli.out + "/asymmetry_vs_amplitude.csv", amp);
  const double seconds = study::seconds_since(start);

  // 5. Key numbers for summary.md.in.
  study::Summary sum;
  sum.set("n", n);
  sum.set("kernels", static_cast<int>(all_kernel_types().size()));
  sum.set("h_min", hs.front(), 6);
  sum.set("h_max", hs.back(), 6);
  sum.set("h_step", cli.quick ? "0.5" : "0.05");
  sum.set("cross_cases", cross.cases);
  sum.set("cross_max", cross.max, 2);
  sum.set("cross_mismatch", cross.class_mismatch);
  sum.set("asym_h", setup.h, 6);
  sum.set("asym_n1", setup.n1);
  sum.set("asym_n2", setup.n2);
  sum.set("wall_seconds", seconds);
  summarise_critical_loads(sum, tcrit.rows, hs, conditions.ft_min);
  summarise_conditions(sum, conditions);
  summarise_asymmetry(sum, asym, amp);
  sum.write(cli.out);
  std::cout << "wrote " << cli.out << " (" << study::sig(seconds, 3) << " s)\n";
  return 0;
}
