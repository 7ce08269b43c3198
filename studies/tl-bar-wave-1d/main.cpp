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
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
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

struct Run {
  std::string name;
  std::shared_ptr<const HyperelasticModel<1>> material;
  double c = 0;  ///< small-strain speed of the material's 1D state
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
      {"neo-hookean-1d-stress", std::make_shared<NeoHookean<1>>(lame, UniaxialState::Stress), cb}};
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
  CsvWriter scsv(out + "/speeds.csv", {"run", "n", "dx", "c_model", "speed_sph_005_010", "max_error_kpa_x0.05",
                                       "max_error_kpa_x0.1", "max_error_kpa_x0.15", "steps"});
  std::string md, md_speed;
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
    for (const Run& run : runs) {
      FiniteStrainTotalLagrangian<1> tl(disc, run.material, kRho);
      const double c = run.c, v0 = -kStress / (kRho * c);  // particle velocity of the incoming compressive wave
      Eigen::VectorXd d(x_fixed.size());
      auto set_time = [&](double t) {
        for (std::size_t k = 0; k < x_fixed.size(); ++k)
          d[k] = x_fixed[k] < 0 ? v0 * shape_integral(t - x_fixed[k] / c) : 0.0;  // left: incoming wave; right: clamp
        tl.set_fixed_displacement(d);
      };
      // time step: half the leap-frog limit 2 / sqrt(mu_max(A)) at rest
      set_time(0);
      const double mu_max =
          symmetric_eigen(Eigen::MatrixXd(jacobian(tl, Eigen::VectorXd::Zero(tl.dofs())))).values.maxCoeff();
      const double dt = 0.5 * 2 / std::sqrt(mu_max);
      const double t_end = 1.9 * kLength / c;  // before the fixed-end reflection reaches the source
      SecondOrderSystem sys;
      sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { tl.acceleration(u, a); };
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
      if (base) summary.set("dt_ns_" + run.name, dt * 1e9, 4);
      std::cout << run.name << ": dt = " << dt * 1e9 << " ns, " << stepper.steps()
                << " steps, max |sigma - exact| = " << worst[0] << ", " << worst[1] << ", " << worst[2] << " kPa\n";
      for (std::size_t p = 0; base && p < kProbes.size(); ++p) {
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
      scsv.row({run.name, n_level, dx, c, speed, worst[0], worst[1], worst[2], stepper.steps()});
      study::md_row(md_speed, {run.name, std::to_string(n_level), study::sig(c, 6), study::sig(speed, 6),
                               study::fixed(100 * (speed / c - 1), 3, true) + " %", study::sig(worst[0], 3),
                               study::sig(worst[1], 3), study::sig(worst[2], 3), std::to_string(stepper.steps())});
    }
  }
  summary.set("arrivals", md);
  summary.set("speeds", md_speed);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
