// Study critical-strain-2d: critical pre-strain of 2D SPH lattices (square, hexagonal; elastic forms, plane strain),
// GitHub issue 3; comparison with [GMS2001, §5]. What the study asks: README.md; the prose of the summary:
// summary.md.in (rendered from summary.json by scripts/render_summary.py).
//
// Writes to --out DIR:
//   sweep.csv         n = 16 free particles per side, fixed layers; 4 kernels x h/dx = 1.0..2.5 (0.1); isotropic and
//                     uniaxial pre-strain; tension and compression; forms conservative, plus, uncorrected (isotropic:
//                     definiteness; uniaxial plus/uncorrected: symmetric-part criterion, labelled), minus; e_crit by
//                     bisection and eigen routes, mechanism, critical-mode wavevector, infinite-lattice limit
//   nonsymmetric.csv  uniaxial plus form with the stability criterion proper (all eigenvalues real and positive,
//                     dense dgeev): n = 12 for every kernel, h/dx = 1.0..2.5 (0.3)
//   versus_n.csv      e_crit(n), n = 10..80 per side, conservative isotropic, with the periodic (exact symbol) value
//                     at the same n and the infinite-lattice limit
//   infinite.csv      infinite-lattice e_crit (Fourier symbols) for square, hex, face-centred, every kernel and h
//   gms.csv           Gray, Monaghan & Swift (2001) lattice sums at k = (pi/dp, 0) (cubic spline) and the stability
//                     of that single mode against the whole Brillouin zone
//   summary.json      key numbers and tables for summary.md.in
// The material, kernels, lattices and h grid are in strain_setup.hpp; one case of the finite-lattice sweeps in
// sweep_row.hpp, the sweeps in finite_sweep.hpp and nonsymmetric_sweep.hpp; e_crit(n) in versus_n.hpp; the infinite
// lattice in infinite_lattice.hpp; the GMS check in gms_lattice_sums.hpp; the key numbers in strain_summary.hpp.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "finite_sweep.hpp"
#include "gms_lattice_sums.hpp"
#include "infinite_lattice.hpp"
#include "nonsymmetric_sweep.hpp"
#include "strain_setup.hpp"
#include "strain_summary.hpp"
#include "versus_n.hpp"

using namespace cstrain;

int main(int argc, char** argv) {
  CLI::App app{"Critical pre-strain of 2D SPH lattices (issue 3)"};
  std::string out_dir = "results/critical-strain-2d";
  bool quick = false;
  app.add_option("--out", out_dir, "Output directory");
  app.add_flag("--quick", quick, "Small smoke run (n = 8, few h, n up to 20)");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out_dir);
  const auto t_start = Clock::now();
  const int n_main = quick ? 8 : 16, n_nonsym = quick ? 6 : 12;
  const std::vector<double> hs = quick ? std::vector<double>{1.0, 1.3, 2.0} : h_grid(1);

  // ---- A. The main sweep, n = n_main (sweep.csv). ----
  auto t0 = Clock::now();
  const std::vector<SweepRow> sweep = finite_sweep(hs, n_main, out_dir);
  const double t_sweep = seconds_since(t0);

  // ---- B. The non-symmetric uniaxial plus form, spectrum criterion (nonsymmetric.csv). ----
  t0 = Clock::now();
  const std::vector<SweepRow> nonsym =
      nonsymmetric_sweep(quick ? std::vector<double>{1.3} : h_grid(3), n_nonsym, out_dir);
  const double t_nonsym = seconds_since(t0);

  // ---- C. e_crit versus n (versus_n.csv). ----
  t0 = Clock::now();
  const std::vector<NRow> nrows =
      versus_n(quick ? std::vector<int>{10, 20} : std::vector<int>{10, 20, 40, 80}, out_dir);
  const double t_versus_n = seconds_since(t0);

  // ---- D. The infinite lattice (infinite.csv). ----
  const std::vector<InfRow> infrows = infinite_lattice(out_dir);

  // ---- E. Gray, Monaghan & Swift (2001) §5 (gms.csv; the n = 20 blocks not in the quick case). ----
  const std::vector<GmsRow> gms = gms_lattice_sums(!quick, out_dir);
  const double t_total = seconds_since(t_start);

  // ---- Key numbers and tables for summary.md.in. ----
  study::Summary sum;
  sum.set("lambda", kMaterial.lambda(), 6);
  sum.set("mu", kMaterial.mu(), 6);
  sum.set("n_main", n_main);
  sum.set("n_nonsymmetric", n_nonsym);
  sum.set("sweep_rows", static_cast<int>(sweep.size()));
  sum.set("sweep_seconds", t_sweep);
  sum.set("nonsymmetric_rows", static_cast<int>(nonsym.size()));
  sum.set("nonsymmetric_seconds", t_nonsym);
  sum.set("versus_n_rows", static_cast<int>(nrows.size()));
  sum.set("versus_n_seconds", t_versus_n);
  sum.set("total_seconds", t_total);
  summarise_routes(sum, sweep);
  summarise_form_ratios(sum, sweep);
  summarise_conservative(sum, sweep);
  summarise_infinite(sum, infrows);
  summarise_versus_n(sum, nrows);
  summarise_nonsymmetric(sum, nonsym, sweep);
  summarise_gms(sum, gms);
  sum.write(out_dir);
  std::cout << "critical-strain-2d: wrote " << out_dir << " in " << sig(seconds_since(t_start), 3) << " s\n";
  return 0;
}
