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
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
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
  std::string md, md_speed, md_fixed;
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
    const ModifiedMatrixDirichlet modified(kernel_matrix(disc->particles, disc->neighbours, kernel, h), eta_targets);
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
            modified.apply(u_all, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(eta_targets.size())));
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
      for (;;) {
        const double t = stepper.time();
        set_time(t);
        const Eigen::MatrixXd P = tl.stresses(stepper.u());
        std::vector<CsvCell> row{t * 1e6};
        for (std::size_t p = 0; p < kProbes.size(); ++p) {
          const double xp = disc->particles.x(disc->free[probe_slot[p]], 0);
          // 1D: T11 = P F / J; at this amplitude (strain 5e-7) P11 and T11 agree to 1e-6 relative
          const double s = P(disc->free[probe_slot[p]], 0);
          const double exact = kStress * (shape(t - xp / c) + shape(t - (2 * kLength - xp) / c));
          row.push_back(s / 1e3);
          row.push_back(exact / 1e3);
          worst[p] = std::max(worst[p], std::abs(s - exact) / 1e3);
          if (std::isnan(arrival[p]) && s <= threshold[p])
            arrival[p] = t_previous + (t - t_previous) * (threshold[p] - previous[p]) / (s - previous[p]);
          previous[p] = s;
        }
        t_previous = t;
        if (base) pcsv->row(row);
        if (t >= t_end) break;
        stepper.step(dt);
      }
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
      if (run.name.rfind("hooke", 0) == 0) {  // the fixed-end comparison: Hooke 1D stress, every method
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
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
