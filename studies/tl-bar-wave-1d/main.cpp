// Ismail (2009) §4.6.3 and §5.3.1: the 1D validation bar (L = 0.15 m, rho = 8000, E = 200 GPa, nu = 0.3), a
// -100 kPa compressive pulse entering at the left end, the right end fixed; probe stress histories at x = 0.05, 0.10
// and 0.15 m and the arrival times against the bar speed c_b = sqrt(E / rho) and the longitudinal speed
// c_L = sqrt((lambda + 2 mu) / rho), with the finite-strain TL form (forms/finite_strain_total_lagrangian.hpp) and
// three materials: Hooke 1D stress (Ismail's algorithm 4.1, T11 = E eps), Neo-Hookean 1D strain (algorithm 5.1) and
// Neo-Hookean 1D stress.
// Source: the left fixed layers carry the exact incoming wave u(x, t) = f(t - x / c) of the material's small-strain
// speed c (as if the bar continued to the left), with f' = v(t) = -sigma(t) / (rho c) and sigma(t) a smoothed square
// pulse of -100 kPa; the right fixed layers are clamped. Exact linear solution before the reflection reaches the left
// end: sigma(x, t) = sigma_in(t - x / c) + sigma_in(t - (2L - x) / c) (full, same-sign reflection at the fixed end).
// Writes to --out DIR: probes_<run>.csv (base resolution), arrivals.csv, speeds.csv (n, 2n, 4n), summary.json.
#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/operators/ismail_boundary.hpp"
#include "sphstab/particles/lattice.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kE = 200e9, kRho = 8000, kNu = 0.3, kLength = 0.15, kStress = -100e3;
constexpr double kHOverDx = 2.75;  // Ismail's h = 5.5 dx (mollifier support h) in sphstab's support-2h convention
constexpr double kRise = 2e-6, kDuration = 10e-6;  // smoothed square pulse: sin^2 ramps of kRise, total kDuration
const std::vector<double> kProbes{0.05, 0.10, 0.15};
constexpr double kFitStart = 1.5;  // observed growth fitted over t in [1.5, 1.9] L / c: the pulse has left the end

/// The pulse shape in [0, 1]: sin^2 rise over kRise, plateau, sin^2 fall, zero outside [0, kDuration].
double shape(double t) {
  if (t <= 0 || t >= kDuration) return 0;
  auto s2 = [](double x) { return std::pow(std::sin(0.5 * std::numbers::pi * x), 2); };
  if (t < kRise) return s2(t / kRise);
  if (t > kDuration - kRise) return s2((kDuration - t) / kRise);
  return 1;
}
/// Integral of shape from 0 to t (for the displacement f(t) = int v).
double shape_integral(double t) {
  if (t <= 0) return 0;
  const double r = kRise;
  auto ramp_int = [r](double x) { return 0.5 * x - r / (2 * std::numbers::pi) * std::sin(std::numbers::pi * x / r); };
  if (t < r) return ramp_int(t);
  const double rise = ramp_int(r);  // = r / 2
  if (t < kDuration - r) return rise + (t - r);
  const double plateau = kDuration - 2 * r;
  if (t < kDuration) return rise + plateau + (rise - ramp_int(kDuration - t));
  return 2 * rise + plateau;
}

/// The fixed (right) end: how the right ghost layers get their displacement from the free particles.
enum class FixedEnd {
  Clamped,   ///< u = 0 on every right ghost
  Mirror,    ///< odd mirror about the wall x = L: u(L + s) = -u(L - s)
  Eta,       ///< Ismail's eta method (2.42) at the wall point x = L, one-sided on the ghosts within its support
  Modified,  ///< Ismail's modified SPH matrix (2.46)-(2.47): <u> = 0 on every right ghost row (exact form)
};
std::string fixed_end_name(FixedEnd e) {
  switch (e) {
    case FixedEnd::Clamped:
      return "clamped";
    case FixedEnd::Mirror:
      return "mirror";
    case FixedEnd::Eta:
      return "eta";
    case FixedEnd::Modified:
      return "modified";
  }
  return "?";
}

struct Run {
  std::string name;
  std::shared_ptr<const HyperelasticModel<1>> material;
  double c = 0;  ///< small-strain speed of the material's 1D state
  FixedEnd fixed_end = FixedEnd::Clamped;
};

struct Arrival {
  double x, t_sph, t_expected_cb, t_expected_cl;
};

/// Dense A = -da/du of an acceleration that is linear in u with a(0) = 0 (Hooke's law, the source at rest): column k
/// is -a(s e_k) / s, exact to round-off for any s small enough to keep J > 0. The closure code that is time-stepped
/// is probed itself, so A is the linearisation of exactly what runs.
Eigen::MatrixXd probed_matrix(const AccelerationFunction& accel, int n, double s) {
  Eigen::MatrixXd A(n, n);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n), a;
  for (int k = 0; k < n; ++k) {
    u[k] = s;
    accel(u, a);
    A.col(k) = -a / s;
    u[k] = 0;
  }
  return A;
}

/// Least-squares slope of ln e(t) over the samples with t in [t0, t1] and e > 0: the observed exponential rate.
double log_slope(const std::vector<double>& t, const std::vector<double>& e, double t0, double t1) {
  double n = 0, st = 0, sy = 0, stt = 0, sty = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] < t0 || t[k] > t1 || !(e[k] > 0)) continue;
    const double y = std::log(e[k]);
    n += 1, st += t[k], sy += y, stt += t[k] * t[k], sty += t[k] * y;
  }
  return n < 3 ? NAN : (n * sty - st * sy) / (n * stt - st * st);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ismail 2009 §4.6.3 / §5.3.1: pulse in the 1D validation bar, finite-strain TL SPH"};
  std::string out = "results/tl-bar-wave-1d";
  int n = 300;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles")->check(CLI::Range(50, 5000));
  CLI11_PARSE(app, argc, argv);
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  const LameParameters lame = LameParameters::from_young_poisson(kE, kNu);
  const double cb = std::sqrt(kE / kRho), cl = std::sqrt((lame.lambda + 2 * lame.mu) / kRho);
  const std::vector<Run> runs{
      {"hooke-1d-stress", std::make_shared<Hooke<1>>(lame, UniaxialState::Stress), cb},
      {"neo-hookean-1d-strain", std::make_shared<NeoHookean<1>>(lame, UniaxialState::Strain), cl},
      {"neo-hookean-1d-stress", std::make_shared<NeoHookean<1>>(lame, UniaxialState::Stress), cb},
      {"hooke-1d-stress-mirror", std::make_shared<Hooke<1>>(lame, UniaxialState::Stress), cb, FixedEnd::Mirror},
      {"hooke-1d-stress-eta", std::make_shared<Hooke<1>>(lame, UniaxialState::Stress), cb, FixedEnd::Eta},
      {"hooke-1d-stress-modified", std::make_shared<Hooke<1>>(lame, UniaxialState::Stress), cb, FixedEnd::Modified}};
  study::Summary summary;
  summary.set("n", n);
  summary.set("dx_mm", kLength / n * 1e3, 4);
  summary.set("h_over_dx", kHOverDx, 3);
  summary.set("c_b", cb, 6);
  summary.set("c_l", cl, 6);
  summary.set("rise_us", kRise * 1e6, 3);
  summary.set("duration_us", kDuration * 1e6, 3);
  CsvWriter acsv(out + "/arrivals.csv", {"run", "c_model", "probe_x", "particle_x", "t_arrival_sph_us",
                                         "t_expected_cb_us", "t_expected_cl_us", "error_vs_model_us"});
  CsvWriter scsv(out + "/speeds.csv", {"run", "fixed_end", "n", "dx", "c_model", "speed_sph_005_010",
                                       "max_error_kpa_x0.05", "max_error_kpa_x0.1", "max_error_kpa_x0.15", "steps"});
  CsvWriter wcsv(out + "/wcc_conditioning.csv",
                 {"n", "layers", "study_set", "cond2", "eig_min", "eig_max", "closure_gain_inf"});
  CsvWriter ccsv(out + "/closure_growth.csv",
                 {"fixed_end", "n", "dx", "dt", "gamma", "mu_re", "mu_im", "gamma_dx_over_c", "leapfrog_rate",
                  "max_abs_mu_dx2_over_c2", "dt_limit_abs_mu", "asymmetry", "observed_rate", "leapfrog_efolds_window",
                  "observed_efolds_window"});
  CsvWriter spcsv(out + "/closure_spectrum.csv", {"fixed_end", "n", "mu_re_dx2_over_c2", "mu_im_dx2_over_c2"});
  CsvWriter lcsv(out + "/closure_layers.csv",
                 {"layers", "gamma", "mu_re", "mu_im", "gamma_dx_over_c", "unstable_modes"});
  CsvWriter mcsv(out + "/closure_mode.csv", {"n", "x", "shape"});
  CsvWriter ecsv(out + "/end_error.csv", {"fixed_end", "n", "t_us", "error_kpa"});
  std::string md, md_speed, md_fixed, md_wcc, md_wcc_layers, md_closed, md_layers;
  for (const int level : {1, 2, 4}) {  // the resolution n, 2n, 4n at fixed h / dx
    const bool base = level == 1;
    const int n_level = n * level;
    const double dx = kLength / n_level;
    const Kernel<1> kernel(KernelType::ModifiedMollifier);
    const double h = kHOverDx * dx;
    const ParticleSet<1> set =
        make_lattice<1>(LatticeType::Line, n_level, {.spacing = dx, .support_radius = 2 * kernel.support_radius(h)});
    const auto disc = make_discretisation(set, kernel, h);
    std::vector<double> x_fixed;
    for (int i = 0; i < disc->size(); ++i)
      if (disc->free_slot[i] < 0) x_fixed.push_back(disc->particles.x(i, 0));
    std::vector<int> probe_slot;
    for (double xp : kProbes) {
      int best = 0;
      for (int f = 0; f < disc->free_count(); ++f)
        if (std::abs(disc->particles.x(disc->free[f], 0) - xp) < std::abs(disc->particles.x(disc->free[best], 0) - xp))
          best = f;
      probe_slot.push_back(best);
    }
    // the half-amplitude time of the incoming stress at x = 0: shape(t) = 1/2 at t = kRise / 2
    const double t_half = kRise / 2;
    // the right end: ghosts (fixed particles beyond L), the mirror partner of each, the eta and modified-matrix
    // operators (built once per resolution)
    std::vector<int> fixed_index, right_ghosts, mirror_free(x_fixed.size(), -1);
    for (int i = 0; i < disc->size(); ++i)
      if (disc->free_slot[i] < 0) fixed_index.push_back(i);
    std::vector<int> eta_targets;
    for (std::size_t k = 0; k < x_fixed.size(); ++k) {
      if (x_fixed[k] < kLength) continue;
      right_ghosts.push_back(fixed_index[k]);
      if (x_fixed[k] - kLength < kernel.support_radius(h)) eta_targets.push_back(fixed_index[k]);
      for (int f = 0; f < disc->free_count(); ++f)
        if (std::abs(disc->particles.x(disc->free[f], 0) - (2 * kLength - x_fixed[k])) < 1e-6 * dx) mirror_free[k] = f;
    }
    const EtaBoundary1D eta(disc->particles, kernel, h, kLength, eta_targets, BoundaryCondition::Dirichlet);
    const SparseMatrix<> wmat = kernel_matrix(disc->particles, disc->neighbours, kernel, h);
    const ModifiedMatrixDirichlet modified(wmat, eta_targets);
    // Conditioning of W_CC (Ismail (2.46)) and the gain ||W_CC^-1 W_CI||_inf of the exact closure
    // u_C = -W_CC^-1 W_CI u_I: for the study's constrained set (the ghosts within the wall's support) and, at the base
    // resolution, for the first 1 .. all right ghost layers. W_CC is symmetric (equal volumes): its eigenvalues give
    // the 2-norm condition number.
    std::vector<int> by_distance = right_ghosts;  // the right ghosts, nearest to the wall first
    std::sort(by_distance.begin(), by_distance.end(),
              [&](int a, int b) { return disc->particles.x(a, 0) < disc->particles.x(b, 0); });
    {
      const Eigen::MatrixXd wd(wmat);
      for (int layers = 1; layers <= static_cast<int>(by_distance.size()); ++layers) {
        const bool study_set = layers == static_cast<int>(eta_targets.size());
        if (!base && !study_set) continue;
        const int m = layers;
        Eigen::MatrixXd wcc(m, m), wci(m, disc->free_count());
        for (int a = 0; a < m; ++a) {
          for (int b = 0; b < m; ++b) wcc(a, b) = wd(by_distance[a], by_distance[b]);
          for (int f = 0; f < disc->free_count(); ++f) wci(a, f) = wd(by_distance[a], disc->free[f]);
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(wcc);
        const Eigen::VectorXd ev = es.eigenvalues();
        const double cond = ev.cwiseAbs().maxCoeff() / ev.cwiseAbs().minCoeff();
        const double gain = (wcc.partialPivLu().solve(wci)).rowwise().lpNorm<1>().maxCoeff();
        wcsv.row({n_level, layers, study_set ? 1 : 0, cond, ev.minCoeff(), ev.maxCoeff(), gain});
        if (study_set)
          study::md_row(md_wcc, {std::to_string(n_level), std::to_string(layers), study::sig(cond, 4),
                                 study::sig(ev.minCoeff(), 4), study::sig(gain, 4)});
        else if (base)
          study::md_row(md_wcc_layers, {std::to_string(layers), study::sig(cond, 4), study::sig(ev.minCoeff(), 4),
                                        study::sig(gain, 4)});
      }
    }
    Eigen::VectorXd x_free(disc->free_count());
    for (int f = 0; f < disc->free_count(); ++f) x_free[f] = disc->particles.x(disc->free[f], 0);
    const ModifiedMatrixDirichlet* modified_op = &modified;  // the closure of the modified runs (the layer sweep
                                                             // below points it elsewhere while probing)
    for (const Run& run : runs) {
      FiniteStrainTotalLagrangian<1> tl(disc, run.material, kRho);
      const double c = run.c, v0 = -kStress / (kRho * c);  // particle velocity of the incoming compressive wave
      Eigen::VectorXd d(x_fixed.size()), u_all = Eigen::VectorXd::Zero(disc->size());
      double t_now = 0;
      // the fixed displacements at t_now for the free displacements u: left, the incoming wave; right, the fixed end
      auto set_fixed = [&](const Eigen::VectorXd& u) {
        for (std::size_t k = 0; k < x_fixed.size(); ++k)
          d[k] = x_fixed[k] < 0 ? v0 * shape_integral(t_now - x_fixed[k] / c) : 0.0;
        if (run.fixed_end == FixedEnd::Mirror) {
          for (std::size_t k = 0; k < x_fixed.size(); ++k)
            if (mirror_free[k] >= 0) d[k] = -u[mirror_free[k]];
        } else if (run.fixed_end != FixedEnd::Clamped) {
          for (int f = 0; f < disc->free_count(); ++f) u_all[disc->free[f]] = u[f];
          for (std::size_t k = 0; k < x_fixed.size(); ++k) u_all[fixed_index[k]] = d[k];  // right ghosts start at 0
          if (run.fixed_end == FixedEnd::Eta)
            eta.apply(u_all, 0.0);  // Ismail (2.42): <u>(L) = 0
          else
            modified_op->apply(u_all,
                               Eigen::VectorXd::Zero(static_cast<Eigen::Index>(modified_op->constrained().size())));
          for (std::size_t k = 0; k < x_fixed.size(); ++k)
            if (x_fixed[k] > kLength) d[k] = u_all[fixed_index[k]];
        }
        tl.set_fixed_displacement(d);
      };
      auto set_time = [&](double t) { t_now = t; };
      // time step: half the leap-frog limit 2 / sqrt(lambda_max(M^-1 K)) at rest (clamped ghosts)
      set_fixed(Eigen::VectorXd::Zero(tl.dofs()));
      const double dt = 0.5 * stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs())).dt;
      const double t_end = 1.9 * kLength / c;  // before the fixed-end reflection reaches the source
      SecondOrderSystem sys;
      sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) {
        set_fixed(u);
        tl.acceleration(u, a);
      };
      sys.set_time = set_time;
      sys.mass = tl.dof_mass();
      // The closed loop linearised (Hooke: a is linear in u, so this is the whole run's operator): A = -da/du of the
      // time-stepped acceleration with its ghost closure, probed with the source at rest (t - x / c < 0 on every left
      // layer, so a(0) = 0). Non-symmetric for the eta and modified closures: complex mu, growth max Re sqrt(-mu)
      // (Powell Thm 3.1) and the leap-frog rate at the run's dt from the roots z of z^2 - (2 - dt^2 mu) z + 1 = 0.
      const bool fixed_end_run = run.name.rfind("hooke", 0) == 0;
      GrowthAnalysis closed;
      double lf_rate = NAN, asym = NAN, max_abs_mu = NAN;
      if (fixed_end_run) {
        t_now = -1;
        const Eigen::MatrixXd A = probed_matrix(sys.acceleration, tl.dofs(), 1e-9);
        if (base && run.fixed_end == FixedEnd::Modified) {  // the same closure on the first 1 .. all ghost layers
          for (int layers = 1; layers <= static_cast<int>(by_distance.size()); ++layers) {
            const ModifiedMatrixDirichlet mm(
                wmat, std::vector<int>(by_distance.begin(), by_distance.begin() + layers));  // deeper ghosts: u = 0
            modified_op = &mm;
            const GrowthAnalysis g = growth_rate(probed_matrix(sys.acceleration, tl.dofs(), 1e-9), x_free);
            modified_op = &modified;
            const std::complex<double> mu = g.unstable.empty() ? std::complex<double>(0, 0) : g.unstable.front().mu;
            lcsv.row({layers, g.growth_rate, mu.real(), mu.imag(), g.growth_rate * dx / c,
                      static_cast<int>(g.unstable.size())});
            study::md_row(md_layers,
                          {std::to_string(layers), study::sig(g.growth_rate, 3), study::sig(g.growth_rate * dx / c, 3),
                           g.unstable.empty() ? "-" : (std::abs(mu.imag()) > 0 ? "complex" : "real < 0"),
                           std::to_string(g.unstable.size())});
          }
        }
        t_now = 0;
        asym = (A - A.transpose()).norm() / A.norm();
        closed = growth_rate(A, x_free);
        lf_rate = leapfrog_growth_rate(closed.eigenvalues, dt);
        max_abs_mu = closed.eigenvalues.cwiseAbs().maxCoeff();
        if (base)  // the leap-frog rate once more from the dense 2n x 2n one-step map (independent route)
          summary.set(
              "lf_map_check_" + fixed_end_name(run.fixed_end),
              std::abs(leapfrog_map_growth(A, dt, Eigen::MatrixXd(), VelocityHookMode::DriftOnly).gamma - lf_rate) /
                  std::max(lf_rate, 1.0),
              2);
        const double scale = dx * dx / (c * c);  // mu in units of (c / dx)^2: resolution-independent
        for (const auto& mu : closed.eigenvalues)
          spcsv.row({fixed_end_name(run.fixed_end), n_level, mu.real() * scale, mu.imag() * scale});
        if (run.fixed_end == FixedEnd::Modified && !closed.unstable.empty())
          for (int f = 0; f < disc->free_count(); ++f) mcsv.row({n_level, x_free[f], closed.unstable.front().shape[f]});
      }
      std::vector<double> end_t, end_err;  // |sigma - exact| at the fixed-end probe, every step (Hooke runs)
      LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(tl.dofs()), Eigen::VectorXd::Zero(tl.dofs()));
      std::vector<std::string> cols{"t_us"};
      for (double xp : kProbes) {
        cols.push_back("sigma_sph_kpa_x" + format_number(xp));
        cols.push_back("sigma_exact_kpa_x" + format_number(xp));
      }
      std::unique_ptr<CsvWriter> pcsv;
      if (base) pcsv = std::make_unique<CsvWriter>(out + "/probes_" + run.name + ".csv", cols, false);
      std::vector<double> arrival(kProbes.size(), std::nan(""));
      // arrival: the first time the probe stress reaches half of the exact first peak at the probe (-100 kPa in the
      // interior, -200 kPa at the fixed end where incident and reflected waves add), linear in time between steps
      std::vector<double> threshold(kProbes.size()), previous(kProbes.size(), 0.0);
      for (std::size_t p = 0; p < kProbes.size(); ++p) {
        const double xp = disc->particles.x(disc->free[probe_slot[p]], 0);
        const double t_peak = xp / c + 0.5 * kDuration;  // mid-plateau of the incident wave
        threshold[p] = 0.5 * kStress * (shape(t_peak - xp / c) + shape(t_peak - (2 * kLength - xp) / c));
      }
      std::vector<double> worst(kProbes.size(), 0.0);  // max |sigma_sph - sigma_exact| over time, kPa
      double t_previous = 0;
      SnapshotFunction probes([&](const StepView& view) {
        const double t = view.time;
        set_time(t);
        const Eigen::MatrixXd P = tl.stresses(view.u);
        std::vector<CsvCell> row{t * 1e6};
        for (std::size_t p = 0; p < kProbes.size(); ++p) {
          const double xp = disc->particles.x(disc->free[probe_slot[p]], 0);
          // 1D: T11 = P F / J; at this amplitude (strain 5e-7) P11 and T11 agree to 1e-6 relative
          const double s = P(disc->free[probe_slot[p]], 0);
          const double exact = kStress * (shape(t - xp / c) + shape(t - (2 * kLength - xp) / c));
          row.push_back(s / 1e3);
          row.push_back(exact / 1e3);
          worst[p] = std::max(worst[p], std::abs(s - exact) / 1e3);
          if (fixed_end_run && p + 1 == kProbes.size())
            end_t.push_back(t), end_err.push_back(std::abs(s - exact) / 1e3);
          if (std::isnan(arrival[p]) && s <= threshold[p])
            arrival[p] = t_previous + (t - t_previous) * (threshold[p] - previous[p]) / (s - previous[p]);
          previous[p] = s;
        }
        t_previous = t;
        if (base) pcsv->row(row);
      });
      study::run_probed(stepper, dt, t_end, probes);
      if (base && run.fixed_end == FixedEnd::Clamped) summary.set("dt_ns_" + run.name, dt * 1e9, 4);
      std::cout << run.name << ": dt = " << dt * 1e9 << " ns, " << stepper.steps()
                << " steps, max |sigma - exact| = " << worst[0] << ", " << worst[1] << ", " << worst[2] << " kPa\n";
      const bool arrivals = base && run.fixed_end == FixedEnd::Clamped;  // the arrival table: the three materials
      for (std::size_t p = 0; arrivals && p < kProbes.size(); ++p) {
        const double xp = disc->particles.x(disc->free[probe_slot[p]], 0);
        const double tb = t_half + xp / cb, tlong = t_half + xp / cl, tm = t_half + xp / c;
        acsv.row({run.name, c, kProbes[p], xp, arrival[p] * 1e6, tb * 1e6, tlong * 1e6, (arrival[p] - tm) * 1e6});
        study::md_row(
            md, {run.name, study::fixed(kProbes[p], 2), study::fixed(arrival[p] * 1e6, 3), study::fixed(tb * 1e6, 3),
                 study::fixed(tlong * 1e6, 3), study::fixed((arrival[p] - tm) * 1e6, 3, true)});
      }
      // speed from the arrivals at 0.05 and 0.10 m (independent of the source)
      const double x0 = disc->particles.x(disc->free[probe_slot[0]], 0),
                   x1 = disc->particles.x(disc->free[probe_slot[1]], 0);
      const double speed = (x1 - x0) / (arrival[1] - arrival[0]);
      scsv.row({run.name, fixed_end_name(run.fixed_end), n_level, dx, c, speed, worst[0], worst[1], worst[2],
                stepper.steps()});
      if (fixed_end_run) {  // the closed-loop spectrum against the observed growth of the end-particle error
        for (std::size_t k = 0; k < end_t.size(); ++k)
          ecsv.row({fixed_end_name(run.fixed_end), n_level, end_t[k] * 1e6, end_err[k]});
        const double t_fit = kFitStart * kLength / c;  // the pulse has left the fixed end's support
        const double slope = log_slope(end_t, end_err, t_fit, t_end);
        const std::complex<double> mu =
            closed.unstable.empty() ? std::complex<double>(NAN, NAN) : closed.unstable.front().mu;
        const double scale = dx * dx / (c * c);
        ccsv.row({fixed_end_name(run.fixed_end), n_level, dx, dt, closed.growth_rate, mu.real(), mu.imag(),
                  closed.growth_rate * dx / c, lf_rate, max_abs_mu * scale, 2 / std::sqrt(max_abs_mu), asym, slope,
                  lf_rate * (t_end - t_fit), slope * (t_end - t_fit)});
        study::md_row(md_closed,
                      {fixed_end_name(run.fixed_end), std::to_string(n_level), study::sig(asym, 2),
                       study::sig(closed.growth_rate, 3),
                       closed.unstable.empty() ? "-"
                                               : study::sig(mu.real() * scale, 4) + " " + (mu.imag() < 0 ? "−" : "+") +
                                                     " " + study::sig(std::abs(mu.imag()) * scale, 4) + "i",
                       study::sig(dt / (2 / std::sqrt(max_abs_mu)), 3), study::sig(lf_rate, 3), study::sig(slope, 3),
                       study::sig(lf_rate * (t_end - t_fit), 3), study::sig(slope * (t_end - t_fit), 3)});
      }
      if (fixed_end_run) {  // the fixed-end comparison: Hooke 1D stress, every method
        study::md_row(md_fixed, {fixed_end_name(run.fixed_end), std::to_string(n_level), study::sig(worst[0], 3),
                                 study::sig(worst[1], 3), study::sig(worst[2], 3)});
      }
      study::md_row(md_speed, {run.name, std::to_string(n_level), study::sig(c, 6), study::sig(speed, 6),
                               study::fixed(100 * (speed / c - 1), 3, true) + " %", study::sig(worst[0], 3),
                               study::sig(worst[1], 3), study::sig(worst[2], 3), std::to_string(stepper.steps())});
    }
  }
  summary.set("arrivals", md);
  summary.set("speeds", md_speed);
  summary.set("fixed_end", md_fixed);
  summary.set("wcc", md_wcc);
  summary.set("wcc_layers", md_wcc_layers);
  summary.set("closed_loop", md_closed);
  summary.set("closure_layers", md_layers);
  summary.set("fit_start", kFitStart, 3);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
