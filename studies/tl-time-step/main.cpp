// Ismail (2009) (4.47): the time step dt = h / c of the central-difference TL scheme, against the linear stability
// limit dt_max = 2 / sqrt(lambda_max(M^-1 K)) of the finite-strain TL form (integrate/stable_time_step.hpp).
// 1. limits.csv: for Ismail's compact kernels (modified mollifier, Lucy, cubic B-spline) and the truncated Gaussian
//    over support / dx, three independent numbers: the von Neumann symbol 2 / (c max_k |X(k)|) over continuous k,
//    the periodic TL bar (LAPACK / Spectra on the mass-scaled Jacobian) and the bar with clamped ghost layers; each
//    in units of Ismail's h (his kernel's own h: the support radius for the mollifiers and Lucy, half of it for the
//    B-spline) over c.
// 2. runs.csv / energy.csv: the validation bar (L = 0.15 m, rho = 8000, E = 200 GPa, Hooke 1D stress, c = c_b,
//    1000 free particles, modified mollifier with support 5.5 dx, Ismail's h / c = 165 ns) stepped from a random
//    displacement at 0.99 and 1.01 of the predicted limit, at 0.72 and 0.73 h/c (the notes' periodic limit
//    0.7226 h/c) and at Ismail's h / c; the total energy ratio E / E0 over the steps.
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/particles/lattice.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kE = 200e9, kRho = 8000, kNu = 0.3, kLength = 0.15;

/// Ismail's h of a kernel at sphstab's h: the kernel's native h (support radius / native support factor).
double ismail_h(KernelType type, double h) {
  return Kernel<1>(type).support_radius(h) / Kernel<1>(type, KernelScaling::Native).support_factor();
}

/// max over continuous k of |X(k)| dx, X(k) = 2 sum_{j > 0} W'(j dx) dx sin(k j dx), dx = 1 (fine grid, then
/// golden-section refinement around the best grid point).
double symbol_max(const Kernel<1>& kernel, double h) {
  const int jmax = static_cast<int>(std::ceil(kernel.support_radius(h))) + 1;
  auto x = [&](double k) {
    double s = 0;
    for (int j = 1; j <= jmax; ++j) s += kernel.d1(static_cast<double>(j), h) * std::sin(k * j);
    return std::abs(2 * s);
  };
  const int m = 4000;
  double best_k = 0, best = 0;
  for (int i = 0; i <= m; ++i) {
    const double k = std::numbers::pi * i / m;
    if (x(k) > best) best = x(k), best_k = k;
  }
  double a = std::max(0.0, best_k - std::numbers::pi / m),
         b = std::min(std::numbers::pi, best_k + std::numbers::pi / m);
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  for (int it = 0; it < 100; ++it) {
    const double c1 = b - g * (b - a), c2 = a + g * (b - a);
    (x(c1) > x(c2) ? b : a) = x(c1) > x(c2) ? c2 : c1;
  }
  return std::max(best, x(0.5 * (a + b)));
}

std::shared_ptr<const Discretisation<1>> line(int n, double dx, const Kernel<1>& kernel, double h, bool periodic) {
  const ParticleSet<1> set = make_lattice<1>(
      LatticeType::Line, n, {.spacing = dx, .support_radius = kernel.support_radius(h), .periodic = periodic});
  return make_discretisation(set, kernel, h);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ismail 2009 (4.47): dt = h/c against the linear stability limit of the finite-strain TL form"};
  std::string out = "results/tl-time-step";
  int n = 1000, steps = 3000, n_table = 200;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles of the validation bar (Ismail: 1000, dt = h/c = 165 ns)");
  app.add_option("--steps", steps, "leap-frog steps per run");
  app.add_option("--n-table", n_table, "free particles of the limit table's bars");
  bool quick = false;
  app.add_flag("--quick", quick,
               "pipeline check: validation bar of 500 free particles (above the dense route's 400 unknowns: the "
               "limit still by Spectra), 1000 steps per run, limit table on bars of 100 free particles");
  CLI11_PARSE(app, argc, argv);
  if (quick) n = 500, steps = 1000, n_table = 100;
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  const ElasticMaterial lame = ElasticMaterial::from_young_poisson(kE, kNu, kRho);
  auto hooke = std::make_shared<Hooke<1>>(lame, UniaxialState::Stress);
  const double c = std::sqrt(kE / kRho);
  study::Summary summary;

  // 1. the limit table, dx = 1 and c = 1 (rho = E)
  CsvWriter lcsv(out + "/limits.csv", {"kernel", "support_over_dx", "h_over_dx", "ismail_h_over_dx",
                                       "dt_symbol_c_over_dx", "dt_periodic_c_over_dx", "dt_bar_c_over_dx",
                                       "dt_symbol_over_ismail_rule", "dt_bar_over_ismail_rule", "route_bar"});
  std::string md_limits;
  const std::vector<KernelType> kernels{KernelType::ModifiedMollifier, KernelType::Lucy, KernelType::CubicSpline,
                                        KernelType::Gaussian};
  const std::vector<double> supports{2, 2.5, 3, 3.5, 4, 4.5, 5, 5.5, 6, 7, 8, 10, 12};
  auto unit = std::make_shared<Hooke<1>>(ElasticMaterial::from_young_poisson(1.0, kNu, kRho), UniaxialState::Stress);
  for (const KernelType type : kernels) {
    const Kernel<1> kernel(type);
    for (const double s : supports) {
      const double h = s / kernel.support_factor(), hi = ismail_h(type, h);
      const double dt_symbol = 2 / symbol_max(kernel, h);
      FiniteStrainTotalLagrangian<1> periodic(line(n_table, 1.0, kernel, h, true), unit, 1.0);
      FiniteStrainTotalLagrangian<1> clamped(line(n_table, 1.0, kernel, h, false), unit, 1.0);
      const StableTimeStep rp = stable_time_step(periodic, Eigen::VectorXd::Zero(periodic.dofs()));
      const StableTimeStep rb = stable_time_step(clamped, Eigen::VectorXd::Zero(clamped.dofs()));
      if (rp.status != Status::Successful || rb.status != Status::Successful)
        throw std::runtime_error("tl-time-step: eigenvalue solver failed");
      lcsv.row({kernel_name(type), s, h, hi, dt_symbol, rp.dt, rb.dt, dt_symbol / hi, rb.dt / hi, rb.route});
      study::md_row(md_limits, {kernel_name(type), study::fixed(s, 1), study::fixed(hi, 2), study::sig(dt_symbol, 5),
                                study::sig(rp.dt, 5), study::sig(rb.dt, 5), study::sig(dt_symbol / hi, 4),
                                study::sig(rb.dt / hi, 4)});
      if (type == KernelType::ModifiedMollifier && (s == 3 || s == 4 || s == 5.5 || s == 8 || s == 12)) {
        const std::string key = "mollifier_symbol_ratio_s" + format_number(s);
        summary.set(key, dt_symbol / hi, 5);
      }
    }
  }
  summary.set("limits", md_limits);
  summary.set("n_table", n_table);
  std::cout << "limit table done (" << study::seconds_since(t0) << " s)\n";

  // 2. the validation bar at Ismail's resolution
  const double dx = kLength / n, support = 5.5 * dx;
  const Kernel<1> moll(KernelType::ModifiedMollifier);
  const double h = support / moll.support_factor(), hi = ismail_h(KernelType::ModifiedMollifier, h);
  const auto disc = line(n, dx, moll, h, false);
  FiniteStrainTotalLagrangian<1> tl(disc, hooke, kRho);
  const auto t_lim = study::Clock::now();
  const StableTimeStep lim = stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs()));
  const StableTimeStep lim_dense = stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs()), {.route = EigenRoute::Dense});
  const double dt_rule = hi / c, dt_symbol = 2 / (c * symbol_max(moll, h / dx) / dx);
  summary.set("n", n);
  summary.set("dx_mm", dx * 1e3, 4);
  summary.set("c_b", c, 6);
  summary.set("ismail_h_mm", hi * 1e3, 4);
  summary.set("dt_rule_ns", dt_rule * 1e9, 5);
  summary.set("dt_limit_ns", lim.dt * 1e9, 6);
  summary.set("dt_limit_dense_ns", lim_dense.dt * 1e9, 6);
  summary.set("dt_limit_route", lim.route);
  summary.set("dt_limit_seconds", study::seconds_since(t_lim), 3);
  summary.set("spectra_vs_dense", std::abs(lim.dt / lim_dense.dt - 1), 2);
  summary.set("dt_symbol_ns", dt_symbol * 1e9, 6);
  summary.set("limit_over_rule", lim.dt / dt_rule, 5);
  summary.set("symbol_over_rule", dt_symbol / dt_rule, 5);
  std::cout << "bar: dt limit " << lim.dt * 1e9 << " ns (" << lim.route << "), dense " << lim_dense.dt * 1e9
            << " ns, symbol " << dt_symbol * 1e9 << " ns, Ismail h/c " << dt_rule * 1e9 << " ns\n";

  struct RunSpec {
    std::string name;
    double dt;
  };
  const std::vector<RunSpec> specs{{"0.99 limit", 0.99 * lim.dt},
                                   {"1.01 limit", 1.01 * lim.dt},
                                   {"0.72 h/c", 0.72 * dt_rule},
                                   {"0.73 h/c", 0.73 * dt_rule},
                                   {"h/c (Ismail 4.47)", dt_rule}};
  std::mt19937 gen(20091);
  std::uniform_real_distribution<double> dist(-1e-15, 1e-15);  // strain ~1e-11: linear up to E/E0 ~ 1e12
  Eigen::VectorXd u0(tl.dofs());
  for (int k = 0; k < tl.dofs(); ++k) u0[k] = dist(gen);
  const Eigen::VectorXd mass = tl.dof_mass();
  CsvWriter rcsv(out + "/runs.csv", {"run", "dt_ns", "dt_over_limit", "dt_over_rule", "steps", "max_energy_ratio",
                                     "steps_to_1e6", "verdict"});
  CsvWriter ecsv(out + "/energy.csv", {"run", "step", "energy_ratio"}, false);
  std::string md_runs;
  for (const RunSpec& spec : specs) {
    SecondOrderSystem sys;
    sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { tl.acceleration(u, a); };
    sys.mass = mass;
    LeapfrogStepper stepper(sys, u0, Eigen::VectorXd::Zero(tl.dofs()));
    const double e0 = tl.strain_energy(u0);
    double worst = 1;
    long blow = -1;
    SnapshotFunction energy([&](const StepView& s) {
      if (s.step == 0) return;
      const double e = 0.5 * s.v.dot(mass.cwiseProduct(s.v)) + tl.strain_energy(s.u);
      worst = std::max(worst, e / e0);
      if (s.step % 5 == 0 || s.step < 100) ecsv.row({spec.name, s.step, e / e0});
      if (blow < 0 && e / e0 > 1e6) blow = s.step;
      if (e / e0 > 1e12 || !std::isfinite(e))  // before the growing mode leaves the linear regime
        energy.stop("energy above 1e12 E0");
    });
    RunOptions ro{.dt = spec.dt, .max_steps = steps, .snapshot_every = 1};
    ro.observers = {&energy};
    run(stepper, ro);
    const std::string verdict = blow < 0 ? "bounded" : "unstable";
    rcsv.row({spec.name, spec.dt * 1e9, spec.dt / lim.dt, spec.dt / dt_rule, stepper.steps(), worst, blow, verdict});
    study::md_row(md_runs, {spec.name, study::sig(spec.dt * 1e9, 5), study::fixed(spec.dt / lim.dt, 4),
                            study::fixed(spec.dt / dt_rule, 4), std::to_string(stepper.steps()), study::sig(worst, 3),
                            blow < 0 ? "-" : std::to_string(blow), verdict});
    std::cout << spec.name << ": max E/E0 " << worst << ", " << verdict << "\n";
  }
  summary.set("runs", md_runs);
  summary.set("steps", steps);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
