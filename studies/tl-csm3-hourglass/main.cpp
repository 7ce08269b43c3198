// Zero-energy (hourglass) modes and the [Ganzenmueller2015] hourglass control term on the Turek & Hron CSM3 beam
// (problems/turek_hron_csm3.hpp, the scene and forms of studies/tl-csm3 through common/csm3.hpp):
// (a) the spectrum of A = -da/du at u = 0 (no gravity preload; A carries 1/m, eigenvalues mu in 1/s^2, f = sqrt(mu) / 2
//     pi) at the coarsest resolutions, for the plain-gradient FiniteStrainTotalLagrangian (Plus divergence) and the
//     NCSPH VariationalTotalLagrangian: the modes below the fundamental (the softest smooth mode), which of them are
//     zigzag (spectral/zigzag_modes.hpp, the classification of studies/tl-hourglass), the fundamental frequency
//     against linear beam theory, the shapes of the softest zigzag modes;
// (b) the lift of the softest zigzag eigenvalue, the fundamental followed by eigenvector overlap and the count of
//     zigzag modes below the fundamental against c_HG;
// (c) the gravity run of studies/tl-csm3 with c_HG in {0, 0.01, 0.1, 1} (and the smallest swept coefficient leaving no
//     zigzag mode below the fundamental, if another): tip mean / amplitude / frequency against the reference, the
//     stable time step and the energy drift.
// Writes to --out DIR: spectrum.csv, lift.csv, modes.csv, runs.csv, tip_<run>.csv, summary.json.
#include <Spectra/GenEigsRealShiftSolver.h>
#include <Spectra/MatOp/SparseGenRealShiftSolve.h>

#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/csm3.hpp"
#include "common/study.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"
#include "sphstab/spectral/zigzag_modes.hpp"

using namespace sphstab;
namespace fs = std::filesystem;
using C = TurekHronCsm3;

namespace {

const std::vector<double> kCoefficients{0, 0.01, 0.03, 0.1, 0.3, 1};
constexpr double kZigzag = 0.5;  // a mode is "zigzag" when its hourglass_fraction exceeds this (as tl-hourglass)
const std::vector<std::string> kForms{"plain", "ncsph-variational"};
constexpr int kShapes = 4;  // softest zigzag modes written for the shape plots

double hz(double mu) { return std::sqrt(std::max(mu, 0.0)) / (2 * std::numbers::pi); }

/// Eigenpairs of A, classified: the symmetric solver when A is symmetric to round-off (conservative forms: M A
/// symmetric with equal masses), else LAPACK dgeev.
std::vector<ZigzagMode> modes_of(const Eigen::MatrixXd& A, const GridIndices<2>& grid, double& asym) {
  asym = (A - A.transpose()).norm() / A.norm();
  if (asym < 1e-12) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()));
    return classify_modes<2>(es.eigenvalues().cast<std::complex<double>>(),
                             es.eigenvectors().cast<std::complex<double>>(), grid);
  }
  const DenseGeneralEigen ge = general_eigen(A, true);
  if (ge.status != Status::Successful)
    throw std::runtime_error("tl-csm3-hourglass: dgeev did not converge (INFO " + std::to_string(ge.lapack_info) + ")");
  return classify_modes<2>(ge.values, ge.vectors, grid);
}

/// The nev eigenpairs of the sparse, non-symmetric A nearest 0 (Spectra shift-invert at sigma = 0, sparse LU; A is
/// positive definite here, so these are the softest), classified: for the larger resolutions at c_HG > 0, where
/// dense dgeev costs minutes. Throws std::runtime_error if Spectra does not converge.
std::vector<ZigzagMode> lowest_modes(const SparseMatrix<>& A, const GridIndices<2>& grid, int nev) {
  using Op = Spectra::SparseGenRealShiftSolve<double, Eigen::RowMajor>;  // SparseMatrix<> is row-major
  Op op(A);
  Spectra::GenEigsRealShiftSolver<Op> eigs(op, nev, 4 * nev, 0.0);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 2000, 1e-12);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error("tl-csm3-hourglass: shift-invert eigen solver did not converge");
  return classify_modes<2>(eigs.eigenvalues(), eigs.eigenvectors(), grid);
}

/// Energy centroid of a mode along the beam, sum |phi_f|^2 x_f (phi unit).
double centroid_x(const ZigzagMode& m, const Discretisation<2>& d) {
  double s = 0;
  for (int f = 0; f < d.free_count(); ++f) s += m.phi.segment<2>(2 * f).squaredNorm() * d.particles.x(d.free[f], 0);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  study::DriverCli cli{
      "Hourglass modes and the Ganzenmueller (2015) control term on the Turek-Hron CSM3 beam",
      "results/tl-csm3-hourglass",
      "pipeline check: spectra at 2 and 3 particles across (dense up to 200 DOFs, so 3 across takes the "
      "shift-invert path), gravity runs at 2 across to t = 3 s, measured from t = 0.5 s"};
  std::vector<int> across{4, 8}, run_across{4, 8};
  double t_end = 6, t_measure = 2, cfl = 0.8, h_over_dx = 1.5;
  int clamp_layers = 4, dense_max = 1200, nev = 24;
  cli.app.add_option("--across", across, "resolutions of the spectra (particles through the thickness)");
  cli.app.add_option("--run-across", run_across,
                     "resolutions of the gravity runs (ncsph-variational; plain: coarsest)");
  cli.app.add_option("--t-end", t_end, "physical time of the gravity runs (s)")->check(CLI::PositiveNumber);
  cli.app.add_option("--t-measure", t_measure, "start of the measuring window (s)")->check(CLI::NonNegativeNumber);
  cli.app.add_option("--cfl", cfl, "fraction of the leap-frog limit")->check(CLI::Range(0.05, 0.9));
  cli.app
      .add_option("--dense-max", dense_max,
                  "largest DOF count for the full dense spectrum at c_HG > 0 (above: the nev softest modes)")
      ->check(CLI::PositiveNumber);
  cli.app.add_option("--nev", nev, "softest modes by shift-invert above --dense-max")->check(CLI::Range(2, 50));
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick) across = {2, 3}, run_across = {2}, dense_max = 200, t_end = 3, t_measure = 0.5;
  if (across.empty() || run_across.empty())
    throw std::invalid_argument("tl-csm3-hourglass: --across and --run-across need at least one resolution");
  const auto t0 = study::Clock::now();
  study::Summary summary;
  auto svk = std::make_shared<StVenantKirchhoff<2>>(study::csm3::lame());
  const Kernel<2> kernel(KernelType::WendlandC2);
  const study::csm3::BeamTheory theory = study::csm3::beam_theory();

  // ---------------- (a) + (b): spectra at u = 0 against c_HG ----------------
  CsvWriter spec_csv(cli.out + "/spectrum.csv",
                     {"across", "form", "hourglass", "rank", "mu", "f_hz", "abs_imag", "zigzag", "centroid_x"});
  CsvWriter lift_csv(
      cli.out + "/lift.csv",
      {"across", "form", "hourglass", "spectrum", "mu_zigzag_min", "mu_smooth_min", "zigzag_below_smooth",
       "modes_below_smooth", "zigzag_rank", "mu_max_computed", "mu_fundamental", "fundamental_overlap",
       "fundamental_shift_rel", "max_abs_imag", "growth_rate", "asymmetry", "seconds"});
  CsvWriter mode_csv(cli.out + "/modes.csv",
                     {"across", "form", "kind", "rank", "mu", "zigzag", "x", "y", "phi_x", "phi_y"});
  std::string md_rest, md_lift, md_softest;
  std::map<std::string, double> removing;  // form -> smallest swept c_HG with no zigzag mode below the fundamental
  for (const std::string& form : kForms) removing[form] = 0;
  for (int n : across)
    for (const std::string& form : kForms) {
      const TurekHronBeam beam = turek_hron_beam({.across = n, .clamp_layers = clamp_layers});
      const auto disc = make_discretisation(beam.particles, kernel, h_over_dx * beam.dx);
      const GridIndices<2> grid = grid_indices<2>(*disc, beam.dx);
      double mu_fund0 = NAN, mu_zig0 = NAN;
      Eigen::VectorXd phi_fund0;
      bool cleared = false;
      for (double chg : kCoefficients) {
        const auto tc = study::Clock::now();
        const study::csm3::Form f = study::csm3::make_form(form, "plus", disc, svk, chg);
        const SparseMatrix<> As = jacobian(*f.force, Eigen::VectorXd::Zero(f.force->dofs()));
        // full spectrum: at c_HG = 0 (symmetric: fast) and on the small systems; else the nev softest modes
        const bool full = chg == 0 || As.rows() <= dense_max;
        double asym = NAN;
        const std::vector<ZigzagMode> modes =
            full ? modes_of(Eigen::MatrixXd(As), grid, asym) : lowest_modes(As, grid, nev);
        double max_imag = 0, growth = 0;  // growth: max Re sqrt(-mu) (growth/growth_rate.hpp), full spectra only
        for (const ZigzagMode& m : modes) {
          max_imag = std::max(max_imag, m.imag);
          growth = std::max(growth, mode_growth({m.mu, m.imag}));
        }
        if (!full) growth = NAN;
        // the softest smooth mode (the clamped beam has no rigid modes) and the softest zigzag mode
        double mu_smooth = NAN, mu_zig = NAN;
        int smooth_rank = -1, zig_rank = -1;
        for (std::size_t r = 0; r < modes.size(); ++r)
          if (modes[r].zigzag < kZigzag) {
            mu_smooth = modes[r].mu;
            smooth_rank = static_cast<int>(r);
            break;
          }
        for (std::size_t r = 0; r < modes.size(); ++r)
          if (modes[r].zigzag >= kZigzag) {
            mu_zig = modes[r].mu;
            zig_rank = static_cast<int>(r);
            break;
          }
        // not among the nev softest: the softest zigzag eigenvalue is above the largest one found
        const std::string zig_text = zig_rank >= 0 ? study::sig(mu_zig, 4) : "> " + study::sig(modes.back().mu, 3);
        int zig_below = 0;
        for (const ZigzagMode& m : modes) zig_below += m.zigzag >= kZigzag && m.mu < mu_smooth;
        if (chg == 0) {
          mu_fund0 = mu_smooth;
          mu_zig0 = mu_zig;
          phi_fund0 = modes[smooth_rank].phi;
        }
        double mu_fund = NAN, overlap = 0;  // the c_HG = 0 fundamental, followed by the largest |phi . phi0|
        for (const ZigzagMode& m : modes)
          if (std::abs(m.phi.dot(phi_fund0)) > overlap) {
            overlap = std::abs(m.phi.dot(phi_fund0));
            mu_fund = m.mu;
          }
        const double seconds = study::seconds_since(tc);
        for (std::size_t r = 0; r < std::min<std::size_t>(modes.size(), 40); ++r)
          spec_csv.row({n, form, chg, static_cast<long>(r), modes[r].mu, hz(modes[r].mu), modes[r].imag,
                        modes[r].zigzag, centroid_x(modes[r], *disc)});
        lift_csv.row({n, form, chg, full ? "full" : "softest " + std::to_string(nev), mu_zig, mu_smooth,
                      static_cast<long>(zig_below), static_cast<long>(smooth_rank), static_cast<long>(zig_rank),
                      modes.back().mu, mu_fund, overlap, mu_fund / mu_fund0 - 1, max_imag, growth, asym, seconds});
        if (zig_below == 0 && !cleared) {
          cleared = true;
          removing[form] = std::max(removing[form], chg);
        }
        study::md_row(
            md_lift,
            {std::to_string(n), form, study::sig(chg, 2), zig_text, zig_rank >= 0 ? std::to_string(zig_rank) : "-",
             zig_rank >= 0 ? study::sig(mu_zig / mu_zig0, 4) : "-", study::sig(mu_fund, 5),
             study::fixed(hz(mu_fund), 4), study::fixed(100 * (mu_fund / mu_fund0 - 1), 3, true) + " %",
             study::fixed(overlap, 3), std::to_string(zig_below), study::sig(asym, 2), study::sig(max_imag, 2),
             study::sig(growth, 3)});
        std::cout << "n" << n << " " << form << " c_HG = " << chg << ": " << As.rows() << " DOFs, softest zigzag "
                  << mu_zig << ", fundamental " << mu_fund << " (" << hz(mu_fund) << " Hz), zigzag below " << zig_below
                  << ", " << seconds << " s\n";
        if (chg != 0) continue;
        // ---- at rest without control: the modes below the fundamental, the fundamental, the shapes ----
        int zig_count = 0;  // zigzag modes among the 40 softest
        for (std::size_t r = 0; r < std::min<std::size_t>(modes.size(), 40); ++r)
          zig_count += modes[r].zigzag >= kZigzag;
        study::md_row(md_rest, {std::to_string(n), form, std::to_string(As.rows()), std::to_string(smooth_rank),
                                std::to_string(zig_below), std::to_string(zig_rank), std::to_string(zig_count),
                                study::sig(mu_zig, 4), study::fixed(hz(mu_zig), 4), study::sig(mu_smooth, 5),
                                study::fixed(hz(mu_smooth), 4), study::fixed(hz(modes[0].mu), 4),
                                study::fixed(100 * (hz(mu_smooth) / theory.f_timoshenko - 1), 2, true) + " %",
                                study::sig(mu_zig / mu_smooth, 3), study::sig(asym, 2)});
        for (int r = 0; r < std::min<int>(8, modes.size()); ++r)  // the 8 softest modes: where the zigzag ones sit
          study::md_row(md_softest, {std::to_string(n), form, std::to_string(r), study::sig(modes[r].mu, 4),
                                     study::fixed(hz(modes[r].mu), 4), study::fixed(modes[r].zigzag, 3),
                                     study::fixed(centroid_x(modes[r], *disc), 4)});
        std::vector<std::pair<std::string, int>> shapes{{"fundamental", smooth_rank}};
        for (std::size_t r = 0; r < modes.size() && static_cast<int>(shapes.size()) <= kShapes; ++r)
          if (modes[r].zigzag >= kZigzag) shapes.push_back({"zigzag", static_cast<int>(r)});
        for (const auto& [kind, r] : shapes)
          for (int fr = 0; fr < disc->free_count(); ++fr)
            mode_csv.row({n, form, kind, static_cast<long>(r), modes[r].mu, modes[r].zigzag,
                          disc->particles.x(disc->free[fr], 0), disc->particles.x(disc->free[fr], 1),
                          modes[r].phi[2 * fr], modes[r].phi[2 * fr + 1]});
      }
      if (!cleared) removing[form] = NAN;  // no swept coefficient cleared this resolution
    }
  summary.set("rest", md_rest);
  summary.set("softest", md_softest);
  summary.set("lift", md_lift);
  for (const std::string& form : kForms) summary.set("removing_" + form, removing[form], 2);

  // ---------------- (c) the gravity run against c_HG ----------------
  CsvWriter rcsv(cli.out + "/runs.csv", {"run", "across", "form", "hourglass", "dt", "dt_limit", "steps",
                                         "wall_seconds", "status", "energy_drift", "ux_mean", "ux_amplitude",
                                         "ux_frequency", "uy_mean", "uy_amplitude", "uy_frequency"});
  std::string md_runs;
  auto rel = [](double v, double ref) { return study::fixed(100 * (v / ref - 1), 2, true) + " %"; };
  struct Spec {
    int across;
    std::string form;
    double chg;
  };
  std::vector<Spec> specs;
  for (const std::string& form : kForms) {
    // {0, 0.01, 0.1, 1} and the smallest swept coefficient leaving no zigzag mode below the fundamental, if another
    std::vector<double> cs{0, 0.01, 0.1, 1};
    const double c_star = removing[form];
    if (c_star > 0 && std::find(cs.begin(), cs.end(), c_star) == cs.end()) cs.insert(cs.begin() + 1, c_star);
    for (int n : run_across) {
      if (form == "plain" && n != run_across.front()) continue;  // plain: not convergent (tl-csm3), coarsest only
      for (double c : cs) specs.push_back({n, form, c});
    }
  }
  std::map<std::string, study::csm3::Run> base;  // c_HG = 0 run per resolution and form
  for (const Spec& s : specs) {
    const TurekHronBeam beam = turek_hron_beam({.across = s.across, .clamp_layers = clamp_layers});
    const auto disc = make_discretisation(beam.particles, kernel, h_over_dx * beam.dx);
    const study::csm3::Form f = study::csm3::make_form(s.form, "plus", disc, svk, s.chg);
    const std::string name = "n" + std::to_string(s.across) + "-" + s.form + "-hg" + study::sig(s.chg, 2);
    const std::string tip_csv = cli.out + "/tip_" + name + ".csv";
    const study::csm3::Run r = study::csm3::gravity_run(
        f.force, beam, {.name = name, .csv_path = tip_csv, .t_end = t_end, .t_measure = t_measure, .cfl = cfl});
    const std::string key = std::to_string(s.across) + s.form;
    if (s.chg == 0) base[key] = r;
    const study::csm3::Run& b = base[key];
    rcsv.row({name, s.across, s.form, s.chg, r.dt, r.dt_limit, r.steps, r.wall, r.status, r.energy_drift, r.ux.mean,
              r.ux.amplitude, r.ux.frequency, r.uy.mean, r.uy.amplitude, r.uy.frequency});
    study::md_row(md_runs,
                  {std::to_string(s.across), s.form, study::sig(s.chg, 2), study::sig(r.dt_limit * 1e6, 4),
                   study::fixed(r.dt_limit / b.dt_limit, 4), study::fixed(1e3 * r.ux.mean, 3),
                   study::fixed(1e3 * r.uy.mean, 3), study::fixed(1e3 * r.uy.amplitude, 3),
                   study::fixed(r.uy.frequency, 4), rel(r.uy.mean, C::uy_mean), rel(r.uy.amplitude, C::uy_amplitude),
                   rel(r.uy.frequency, C::frequency), rel(r.uy.mean, b.uy.mean), rel(r.uy.frequency, b.uy.frequency),
                   study::sig(r.energy_drift, 2), std::to_string(r.steps), study::fixed(r.wall, 1), r.status});
    std::cout << name << ": dt_limit " << r.dt_limit << " s, " << r.steps << " steps, " << r.wall << " s, " << r.status
              << "; uy " << r.uy.mean << " +- " << r.uy.amplitude << " [" << r.uy.frequency << " Hz], ux mean "
              << r.ux.mean << ", energy drift " << r.energy_drift << "\n";
  }
  summary.set("runs", md_runs);
  summary.set("f_timoshenko", theory.f_timoshenko, 4);
  summary.set("f_euler_bernoulli", theory.f_euler_bernoulli, 4);
  summary.set("zigzag_threshold", kZigzag, 2);
  summary.set("h_over_dx", h_over_dx, 3);
  summary.set("clamp_layers", clamp_layers);
  summary.set("cfl", cfl, 3);
  summary.set("t_end", t_end, 3);
  summary.set("t_measure", t_measure, 3);
  summary.set("load", study::load_average());
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(cli.out);
  return 0;
}
