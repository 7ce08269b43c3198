// Ismail (2009) §5.4.3: large-strain validation of 2D (plane strain) finite-strain TL SPH on a block of 31 x 6
// particles of compressible Neo-Hookean material, with the centre particle's Cauchy stress T11 against the analytic
// (5.5) along three stretch paths: (1) lambda_2 = 1, lambda_1 1 -> 6; (2) lambda_2 = 2 (ramped first), lambda_1 1 -> 6;
// (3) lambda_1 1 -> 6 and lambda_2 1 -> 2 together (Ismail: "the exact solution for the entire path has not been
// computed"; for a homogeneous deformation it is (5.5) along the path).
// The boundary: fixed layers two kernel supports deep around the block carry the homogeneous field
// u = (diag(lambda_1(t), lambda_2(t)) - I) X; leap-frog from rest. Writes to --out DIR: history_case<k>.csv,
// table.csv, summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/reference_t11_table.hpp"
#include "common/study.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/models/neo_hookean.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kE = 200e9, kRho = 8000, kDx = 0.5e-3, kHOverDx = 2.75;  // Ismail's steel; h = 5.5 dx (his)
constexpr int kNx = 31, kNy = 6;

/// Smooth ramp 0 -> 1 over tau in [0, 1] with zero velocity at both ends.
double ramp(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau - std::sin(2 * std::numbers::pi * tau) / (2 * std::numbers::pi);
}

/// The 31 x 6 block (free, x_i = (i + 1/2) dx) inside `layers` fixed layers on every side.
ParticleSet<2> block(int layers) {
  ParticleSet<2> set;
  const int nx = kNx + 2 * layers, ny = kNy + 2 * layers;
  set.x.resize(nx * ny, 2);
  set.volume = Eigen::VectorXd::Constant(nx * ny, kDx * kDx);
  set.role.clear();
  int k = 0;
  for (int pass = 0; pass < 2; ++pass)  // free block first
    for (int j = -layers; j < kNy + layers; ++j)
      for (int i = -layers; i < kNx + layers; ++i) {
        const bool free = i >= 0 && i < kNx && j >= 0 && j < kNy;
        if (free != (pass == 0)) continue;
        set.x(k, 0) = (i + 0.5) * kDx;
        set.x(k, 1) = (j + 0.5) * kDx;
        set.role.push_back(free ? Role::Free : Role::Fixed);
        ++k;
      }
  set.spacing = kDx;
  return set;
}

struct Case {
  int id;
  std::string name;
  /// (lambda_1, lambda_2) at loading fraction s in [0, 1].
  std::function<Eigen::Vector2d(double)> path;
};

}  // namespace

int main(int argc, char** argv) {
  study::DriverCli cli{"Ismail 2009 §5.4.3: 31 x 6 Neo-Hookean block stretched to lambda_1 = 6 (plane strain)",
                       "results/tl-neo-hookean-2d",
                       "pipeline check: loading over 10 transit times instead of --ramp (same block)"};
  double ramp_transits = 30, nu = 0.3;
  cli.app.add_option("--ramp", ramp_transits, "loading time in small-strain transit times (31 dx) / c_L")
      ->check(CLI::PositiveNumber);
  cli.app.add_option("--nu", nu, "Poisson's ratio")->check(CLI::Range(0.0, 0.4999));
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick) ramp_transits = 10;
  const auto t0 = study::Clock::now();
  const Kernel<2> kernel(KernelType::ModifiedMollifier);
  const double h = kHOverDx * kDx;
  const int layers = static_cast<int>(std::ceil(2 * kernel.support_radius(h) / kDx - 1e-9));
  const auto disc = make_discretisation(block(layers), kernel, h);
  auto material = std::make_shared<NeoHookean<2>>(ElasticMaterial::from_young_poisson(kE, nu, kRho));
  FiniteStrainTotalLagrangian<2> tl(disc, material, kRho);
  const double mu = material->material().mu();
  const double cl = std::sqrt(material->material().uniaxial_modulus(UniaxialState::Strain) / kRho);
  const double t_load = ramp_transits * kNx * kDx / cl;
  Eigen::MatrixXd x_fixed(disc->size() - disc->free_count(), 2);
  for (int i = 0, k = 0; i < disc->size(); ++i)
    if (disc->free_slot[i] < 0) x_fixed.row(k++) = disc->particles.x.row(i);
  // the centre: free particles (15, 2) and (15, 3) (6 across has no middle particle); report their mean
  std::vector<int> centre;
  for (int f = 0; f < disc->free_count(); ++f) {
    const double x = disc->particles.x(disc->free[f], 0) / kDx - 0.5,
                 y = disc->particles.x(disc->free[f], 1) / kDx - 0.5;
    if (std::abs(x - 15) < 1e-9 && (std::abs(y - 2) < 1e-9 || std::abs(y - 3) < 1e-9)) centre.push_back(f);
  }
  const auto analytic_t11 = [&](double l1, double l2) {
    Deformation<double, 2> F = Deformation<double, 2>::Zero();
    F(0, 0) = l1;
    F(1, 1) = l2;
    return material->cauchy_stress(F)(0, 0);
  };
  // time step: half the leap-frog limit at rest
  const double mu_max =
      symmetric_eigen(Eigen::MatrixXd(jacobian(tl, Eigen::VectorXd::Zero(tl.dofs())))).values.maxCoeff();
  const double dt = 0.5 * 2 / std::sqrt(mu_max);
  study::Summary summary;
  summary.set("nu", nu, 3);
  summary.set("layers", layers);
  summary.set("ramp", ramp_transits, 3);
  summary.set("t_load_us", t_load * 1e6, 4);
  summary.set("dt_ns", dt * 1e9, 4);
  summary.set("particles", disc->size());
  const std::vector<Case> cases{
      {1, "lambda_2 = 1", [](double s) { return Eigen::Vector2d(1 + 5 * ramp(s), 1); }},
      {2, "lambda_2 = 2 (first 20 % of the time), then lambda_1",
       [](double s) { return Eigen::Vector2d(1 + 5 * ramp((s - 0.2) / 0.8), 1 + ramp(s / 0.2)); }},
      {3, "lambda_1 1 -> 6 with lambda_2 1 -> 2",
       [](double s) { return Eigen::Vector2d(1 + 5 * ramp(s), 1 + ramp(s)); }}};
  const std::vector<double> stretches{1.5, 2, 3, 4, 6};
  // the reference table (nu = 0.3 only): (lambda2, lambda1) -> T11 / mu
  const std::vector<study::TableRow> reference =
      study::read_table((fs::path(SPHSTAB_STUDY_DIR) / "reference_t11_table.csv").string());
  CsvWriter tcsv(cli.out + "/table.csv", {"case", "lambda1", "lambda2", "t11_notes_over_mu", "t11_analytic_over_mu",
                                          "t11_sph_over_mu", "relative_error", "F22_centre"});
  std::string md, md_end;
  for (const Case& c : cases) {
    SecondOrderSystem sys;
    Eigen::Vector2d lam(1, 1);
    sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { tl.acceleration(u, a); };
    sys.set_time = [&](double t) {
      lam = c.path(t / t_load);
      Eigen::VectorXd d(2 * x_fixed.rows());
      for (int k = 0; k < x_fixed.rows(); ++k) {
        d[2 * k] = (lam[0] - 1) * x_fixed(k, 0);
        d[2 * k + 1] = (lam[1] - 1) * x_fixed(k, 1);
      }
      tl.set_fixed_displacement(d);
    };
    sys.mass.resize(tl.dofs() / 2);
    for (int f = 0; f < tl.dofs() / 2; ++f) sys.mass[f] = tl.dof_mass()[2 * f];
    sys.dofs_per_particle = 2;
    sys.set_time(0);
    LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(tl.dofs()), Eigen::VectorXd::Zero(tl.dofs()));
    CsvWriter hcsv(
        cli.out + "/history_case" + std::to_string(c.id) + ".csv",
        {"t_us", "lambda1", "lambda2", "F11_centre", "F22_centre", "t11_sph_over_mu", "t11_analytic_over_mu"}, false);
    std::vector<double> at(stretches.size(), std::nan("")), f22_at(stretches.size(), std::nan(""));
    const long nsteps = static_cast<long>(std::ceil(t_load / dt));
    const long every = std::max(1L, nsteps / 1500);
    std::string end = "completed";
    double f11 = 0, f22 = 0, t11 = 0;
    SnapshotFunction centre_probe([&](const StepView& view) {
      const long s = view.step;
      sys.set_time(view.time);
      try {
        const Eigen::MatrixXd F = tl.deformation_gradients(view.u);
        f11 = f22 = t11 = 0;
        for (int f : centre) {
          const int i = disc->free[f];
          Deformation<double, 2> Fi;
          Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
          f11 += Fi(0, 0) / centre.size();
          f22 += Fi(1, 1) / centre.size();
          t11 += material->cauchy_stress(Fi)(0, 0) / centre.size();
        }
      } catch (const std::invalid_argument& e) {
        end = std::string("stopped: ") + e.what();
        centre_probe.stop(end);
        return;
      }
      if (s % every == 0 || s == nsteps)
        hcsv.row({view.time * 1e6, lam[0], lam[1], f11, f22, t11 / mu, analytic_t11(lam[0], lam[1]) / mu});
      for (std::size_t k = 0; k < stretches.size(); ++k)
        if (std::isnan(at[k]) && lam[0] >= stretches[k] - 1e-12 && view.time > 0) {
          at[k] = t11;
          f22_at[k] = f22;
        }
    });
    RunOptions ro{.dt = dt, .max_steps = nsteps, .snapshot_every = 1};
    ro.observers = {&centre_probe};
    if (const RunResult result = run(stepper, ro); !result.completed() && result.status != RunStatus::Stopped)
      end = "stopped: " + result.message;
    std::cout << "case " << c.id << ": " << stepper.steps() << " steps, " << end << "\n";
    for (std::size_t k = 0; k < stretches.size(); ++k) {
      // the imposed lambda_2 when lambda_1 first reached the stretch
      const double s_at = [&] {
        double lo = 0, hi = 1;
        for (int it = 0; it < 60; ++it) ((c.path(0.5 * (lo + hi))[0] < stretches[k]) ? lo : hi) = 0.5 * (lo + hi);
        return hi;
      }();
      const double l2 = c.path(s_at)[1];
      const double exact = analytic_t11(stretches[k], l2);
      const double rel = (at[k] - exact) / exact;
      const double note = study::thesis_t11(reference, nu, l2, stretches[k]);
      tcsv.row({c.id, stretches[k], l2, note, exact / mu, at[k] / mu, rel, f22_at[k]});
      study::md_row(md, {std::to_string(c.id), study::fixed(stretches[k], 1), study::fixed(l2, 3),
                         study::fixed(note, 4), study::fixed(exact / mu, 4), study::fixed(at[k] / mu, 4),
                         study::fixed(100 * rel, 2, true) + " %", study::fixed(f22_at[k], 4)});
    }
    study::md_row(md_end, {std::to_string(c.id), c.name, std::to_string(stepper.steps()), end, study::fixed(f11, 4),
                           study::fixed(f22, 4)});
  }
  summary.set("table", md);
  summary.set("ends", md_end);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(cli.out);
  return 0;
}
