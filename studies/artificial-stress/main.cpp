// Study: critical artificial-stress coefficient and transverse-mode signs on the square and face-centred
// lattices versus h/dp [GMS2001, §5.3], from the lattice dispersion tool. See README.md; the prose of the
// summary is summary.md.in.
//
// Writes to --out DIR: thresholds.csv, by_sign.csv, long_wave.csv, n_dependence.csv, summary.json.
// Units: rho0 = c0 = 1, dp = 1 (sums in 1/dp, 1/dp^2; stresses in rho0 c0^2; rates in c0/dp).
#include <CLI/CLI.hpp>
#include <array>
#include <filesystem>
#include <iostream>
#include <string>

#include "common/study.hpp"
#include "gms_statements.hpp"
#include "lattice_thresholds.hpp"

using namespace artificial_stress;

int main(int argc, char** argv) {
  CLI::App app{"GMS 2001 artificial stress: critical coefficients and transverse-mode signs versus h/dp"};
  std::string out = "results/artificial-stress";
  double h_min = 1.0, h_max = 2.0, h_step = 0.005, epsilon = 0.3, n = 4, mu = 0.22;
  app.add_option("--out", out, "output directory");
  app.add_option("--h-min", h_min, "smallest h/dp")->check(CLI::PositiveNumber);
  app.add_option("--h-max", h_max, "largest h/dp")->check(CLI::PositiveNumber);
  app.add_option("--h-step", h_step, "h/dp step of the CSV scan")->check(CLI::PositiveNumber);
  app.add_option("--epsilon", epsilon, "artificial stress coefficient to compare with");
  app.add_option("--n", n, "artificial stress exponent")->check(CLI::NonNegativeNumber);
  app.add_option("--mu", mu, "shear modulus (rho0 c0^2) of the material examples");
  bool quick = false;
  app.add_flag("--quick", quick, "the thresholds scan in h/dp steps of 0.02 (the study's test case)");
  CLI11_PARSE(app, argc, argv);
  if (quick && app.count("--h-step") == 0) h_step = 0.02;
  const auto t0 = study::Clock::now();
  std::filesystem::create_directories(out);
  const Lattices g{.w = Kernel<2>(KernelType::CubicSpline), .opt = {.exponent = n}, .mu = mu};

  // 1. thresholds.csv: lattice sums, GMS coefficients and critical epsilon for isotropic tension.
  std::cout << "scan h/dp in [" << h_min << ", " << h_max << "] step " << h_step << "\n";
  write_thresholds(out + "/thresholds.csv", g, h_min, h_max, h_step);

  // 2. by_sign.csv + roots of B_y, B_x, f_yy (sign changes) on [h_min, h_max].
  const std::array<Roots, 2> r = write_by_sign(out + "/by_sign.csv", g, h_min, h_max);

  // 3. long_wave.csv: the lattice moments behind the long-wave limit (GMS 5.10 assumes -A/k = B/k^2 = 1).
  write_long_wave(out + "/long_wave.csv", g);

  // 4. n_dependence.csv: f_xx(n) at h = dp (GMS: square 30(3n+2)/(7 pi), face-centred "proportional to 4n + 3.7").
  const NFit nf = write_n_dependence(out + "/n_dependence.csv", g.w);

  // 5. Key numbers.
  const KeyNumbers key = key_numbers(g, n, epsilon, h_min, h_max);

  const double wall = study::seconds_since(t0);
  std::cout << "wall time " << fixed(wall, 2) << " s\n";

  // 6. summary.json; the prose and the GMS statements (numbered rows) are in summary.md.in.
  study::Summary s;
  s.set("n", n, 6), s.set("epsilon", epsilon, 6), s.set("mu", mu, 6), s.set("h_min", h_min, 6);
  s.set("h_max", h_max, 6), s.set("h_step", h_step, 6), s.set("wall_seconds", fixed(wall, 2));
  summarise_statements(s, g, key, r, nf, n, epsilon, h_min, h_max);
  s.write(out);
  std::cout << "wrote " << out << "/{thresholds,by_sign,long_wave,n_dependence}.csv and summary.json\n";
  return 0;
}
