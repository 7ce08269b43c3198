// Issue 11, Ismail (2009) §5.4.4: the quarter plate with a hole under remote tension S, static solution of the
// finite-strain TL SPH form (NCSPH corrected reference gradient, difference strain, Plus divergence) by Newton with the
// complex-step Jacobian and a sparse LU, mirror layers on the symmetry planes (problems/plate_with_hole.hpp).
// (1) linear (Hooke, S/E = 1e-3) against Kirsch's factor 3: resolution a/dx = 4, 8, 16 at W/a = 5 and the width W/a =
// 5, 10, 20 at a/dx = 4; (2) Ismail's case E = 70 MPa, nu = 0.49, S = 5 MPa (Neo-Hookean, load steps) beside Hooke.
// Writes to --out DIR: cases.csv, profile_<tag>.csv, ring_<tag>.csv, particles_<tag>.csv, summary.json.
#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/problems/plate_with_hole.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kA = 1, kHOverDx = 1.3;

struct Run {
  std::string tag, model;
  double a_over_dx = 0, w_over_a = 0, nu = 0, youngs = 0, traction = 0;
  int steps = 1;
  bool lumped = false;  ///< edge load S x edge length on the last column instead of the consistent load
};

struct Outcome {
  int particles = 0, real = 0, dofs = 0, iterations = 0;
  double residual = 0, seconds = 0;
  double peak_hoop = 0, peak_theta = 0, peak_r = 0, kirsch_at_peak = 0;  // first ring, hoop / S
  double edge = 0;                                                       // sigma_xx(0, a) / S, extrapolated
  double peak_principal = 0, peak_principal_r = 0;                       // max principal Cauchy stress (absolute)
  double total_force = 0;                                                // consistent traction total / (S W)
  double max_strain = 0;                                                 // max |F - I| over the real particles
  double load_column = 0;  // max |sigma_xx / S - 1| on the loaded column x = W - dx/2
  double net_section = 0;  // sum of sigma_xx dx over the column x = dx/2, / (S W): 1 for the exact equilibrium
};

Outcome solve(const Run& run, double c_hg, const std::string& out) {
  const auto t0 = study::Clock::now();
  Outcome o;
  const Kernel<2> kernel(KernelType::CubicSpline);
  const double dx = kA / run.a_over_dx, h = kHOverDx * dx, W = run.w_over_a * kA;
  const PlateWithHole plate = make_plate_with_hole(
      {.radius = kA, .width = W, .spacing = dx, .ghost_depth = 2 * kernel.support_radius(h) + 0.5 * dx});
  const auto disc = make_discretisation(plate.particles, kernel, h);
  const auto lame = LameParameters::from_young_poisson(run.youngs, run.nu);
  std::shared_ptr<const HyperelasticModel<2>> material;
  if (run.model == "hooke")
    material = std::make_shared<Hooke<2>>(lame);
  else
    material = std::make_shared<NeoHookean<2>>(lame);
  FiniteStrainTotalLagrangian<2> tl(disc, material, 1.0,
                                    {.gradient = make_gradient_provider<2>(Correction::Ncsph),
                                     .divergence = StressDivergence::Plus,
                                     .hourglass = c_hg});
  const int nr = 2 * plate.real_count;
  const SparseMatrix<> T = mirror_map(plate);
  const Eigen::VectorXd f =
      run.lumped ? lumped_traction(plate, run.traction) : consistent_traction(plate, *disc, run.traction);
  o.total_force = f.sum() / (run.traction * W);
  const Eigen::VectorXd m = tl.dof_mass().head(nr);
  const ComplexStepJacobian csj(tl);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(nr), a;
  for (int step = 1; step <= run.steps; ++step) {
    const Eigen::VectorXd load = (static_cast<double>(step) / run.steps) * f.cwiseQuotient(m);
    for (int it = 0;; ++it) {
      const Eigen::VectorXd ua = T * u;
      tl.acceleration(ua, a);
      const Eigen::VectorXd r = a.head(nr) + load;
      o.residual = r.lpNorm<Eigen::Infinity>() / load.lpNorm<Eigen::Infinity>();
      if (o.residual < 1e-10) break;
      if (it == 12) throw std::runtime_error(run.tag + ": Newton did not converge");
      const SparseMatrix<> A = csj.compute(ua);
      const Eigen::SparseMatrix<double> Ar = SparseMatrix<>(A.topRows(nr)) * T;
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(Ar);
      if (lu.info() != Eigen::Success) throw std::runtime_error(run.tag + ": sparse LU failed");
      u += lu.solve(r);
      ++o.iterations;
    }
  }
  const Eigen::VectorXd ua = T * u;
  const Eigen::MatrixXd F = tl.deformation_gradients(ua);
  const auto& X = plate.particles.x;
  CsvWriter pcsv(out + "/particles_" + run.tag + ".csv",
                 {"x", "y", "sigma_xx_over_S", "hoop_over_S", "principal_over_S"});
  CsvWriter rcsv(out + "/ring_" + run.tag + ".csv", {"theta_deg", "r_over_a", "hoop_over_S", "kirsch_over_S"});
  CsvWriter ccsv(out + "/profile_" + run.tag + ".csv", {"y_over_a", "x_over_a", "sigma_xx_over_S", "kirsch_over_S"});
  std::vector<std::pair<double, double>> column;  // (y, sigma_xx / S) on x = dx/2
  o.peak_hoop = -1e300;
  for (int i = 0; i < plate.real_count; ++i) {
    Deformation<double, 2> Fi;
    Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
    o.max_strain = std::max(o.max_strain, (Fi - Deformation<double, 2>::Identity()).cwiseAbs().maxCoeff());
    // small-strain runs (Hooke): P itself (Hooke is linear in F: P / S does not depend on S); Neo-Hookean: Cauchy
    const Eigen::Matrix2d s = run.model == "hooke" ? material->stress(Fi) : material->cauchy_stress(Fi);
    const double r = X.row(i).norm(), th = std::atan2(X(i, 1), X(i, 0));
    const Eigen::Vector2d et(-std::sin(th), std::cos(th));
    const double hoop = et.dot(s * et) / run.traction;
    const double principal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(0.5 * (s + s.transpose())).eigenvalues()[1];
    pcsv.row({X(i, 0), X(i, 1), s(0, 0) / run.traction, hoop, principal / run.traction});
    if (X(i, 0) > W - dx) o.load_column = std::max(o.load_column, std::abs(s(0, 0) / run.traction - 1));
    if (principal > o.peak_principal) {
      o.peak_principal = principal;
      o.peak_principal_r = r;
    }
    if (r < kA + dx) {
      const double kirsch = kirsch_polar_stress(kA, r, th, 1.0)[1];
      rcsv.row({th * 180 / std::numbers::pi, r / kA, hoop, kirsch});
      if (hoop > o.peak_hoop) {
        o.peak_hoop = hoop;
        o.peak_theta = th * 180 / std::numbers::pi;
        o.peak_r = r / kA;
        o.kirsch_at_peak = kirsch;
      }
    }
  }
  // profile along theta = 90 deg: the column x = dx/2 against Kirsch's sigma_xx at the same points
  for (int i = 0; i < plate.real_count; ++i) {
    if (std::abs(X(i, 0) - 0.5 * dx) > 1e-9 * dx) continue;
    Deformation<double, 2> Fi;
    Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
    const Eigen::Matrix2d s = run.model == "hooke" ? material->stress(Fi) : material->cauchy_stress(Fi);
    const double r = X.row(i).norm(), th = std::atan2(X(i, 1), X(i, 0));
    const Eigen::Vector3d k = kirsch_polar_stress(kA, r, th, 1.0);  // rr, tt, rt
    const double c = std::cos(th), sn = std::sin(th);
    const double kxx = k[0] * c * c + k[1] * sn * sn - 2 * k[2] * sn * c;
    ccsv.row({X(i, 1) / kA, X(i, 0) / kA, s(0, 0) / run.traction, kxx});
    column.emplace_back(X(i, 1), s(0, 0) / run.traction);
    o.net_section += s(0, 0) * dx / (run.traction * W);
  }
  // edge value: least-squares line through the three innermost particles of the column, evaluated at y = a
  std::sort(column.begin(), column.end());
  {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const int k = std::min<int>(3, static_cast<int>(column.size()));
    for (int j = 0; j < k; ++j) {
      const double y = column[j].first - kA;
      sx += y, sy += column[j].second, sxx += y * y, sxy += y * column[j].second;
    }
    const double slope = (k * sxy - sx * sy) / (k * sxx - sx * sx);
    o.edge = (sy - slope * sx) / k;
  }
  o.particles = plate.particles.size();
  o.real = plate.real_count;
  o.dofs = nr;
  o.seconds = study::seconds_since(t0);
  std::cout << run.tag << ": " << o.real << " particles, " << o.iterations << " Newton iterations, residual "
            << o.residual << ", peak hoop/S " << o.peak_hoop << ", edge " << o.edge << ", " << o.seconds << " s"
            << std::endl;
  return o;
}

/// The suddenly applied load of [Ismail2009, §5.4.4] ("loaded dynamically from rest"): leap-frog from rest with the
/// traction switched on at t = 0 and no damping, rho = 1 (the stress history in units of the transit time W / c_s
/// does not depend on rho). Records the largest principal Cauchy stress near the hole (r < a + 2 dx) and anywhere.
struct DynamicOutcome {
  double peak_hole = 0, peak_time = 0, peak_all = 0, dt = 0, t_end = 0;
  long steps = 0;
  std::string end = "completed";
};

DynamicOutcome dynamic_step(const Run& run, double c_hg, double transits, const std::string& out) {
  DynamicOutcome o;
  const Kernel<2> kernel(KernelType::CubicSpline);
  const double dx = kA / run.a_over_dx, h = kHOverDx * dx, W = run.w_over_a * kA;
  const PlateWithHole plate = make_plate_with_hole(
      {.radius = kA, .width = W, .spacing = dx, .ghost_depth = 2 * kernel.support_radius(h) + 0.5 * dx});
  const auto disc = make_discretisation(plate.particles, kernel, h);
  const auto lame = LameParameters::from_young_poisson(run.youngs, run.nu);
  const auto material = std::make_shared<NeoHookean<2>>(lame);
  FiniteStrainTotalLagrangian<2> tl(disc, material, 1.0,
                                    {.gradient = make_gradient_provider<2>(Correction::Ncsph),
                                     .divergence = StressDivergence::Plus,
                                     .hourglass = c_hg});
  const int nr = 2 * plate.real_count;
  const SparseMatrix<> T = mirror_map(plate);
  const Eigen::VectorXd load = consistent_traction(plate, *disc, run.traction).cwiseQuotient(tl.dof_mass().head(nr));
  // dt: 0.4 x the leap-frog limit 2 / sqrt(mu_max), mu_max of A at rest by power iteration (dominant |eigenvalue|)
  const Eigen::SparseMatrix<double> A =
      SparseMatrix<>(ComplexStepJacobian(tl).compute(Eigen::VectorXd::Zero(tl.dofs())).topRows(nr)) * T;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(nr);
  double mu_max = 0;
  for (int it = 0; it < 300; ++it) {
    const Eigen::VectorXd y = A * x;
    mu_max = y.norm() / x.norm();
    x = y / y.norm();
  }
  o.dt = 0.4 * 2 / std::sqrt(mu_max);
  const double cs = std::sqrt(lame.mu / 1.0);
  o.t_end = transits * W / cs;
  SecondOrderSystem sys;
  Eigen::VectorXd a_all;
  sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) {
    tl.acceleration(T * u, a_all);
    a = a_all.head(nr) + load;
  };
  sys.dofs_per_particle = 2;
  LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(nr), Eigen::VectorXd::Zero(nr));
  CsvWriter csv(out + "/dynamic_" + run.tag + ".csv",
                {"t_over_transit", "peak_principal_hole_mpa", "peak_principal_mpa"}, false);
  const long nsteps = static_cast<long>(std::ceil(o.t_end / o.dt));
  const long every = std::max(1L, nsteps / 2000);
  SnapshotFunction peaks([&](const StepView& view) {
    {
      double hole = 0, all = 0;
      try {
        const Eigen::MatrixXd F = tl.deformation_gradients(T * view.u);
        for (int i = 0; i < plate.real_count; ++i) {
          Deformation<double, 2> Fi;
          Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
          const Eigen::Matrix2d c = material->cauchy_stress(Fi);
          const double p1 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(0.5 * (c + c.transpose())).eigenvalues()[1];
          all = std::max(all, p1);
          if (plate.particles.x.row(i).norm() < kA + 2 * dx) hole = std::max(hole, p1);
        }
      } catch (const std::exception& e) {
        o.end = std::string("stopped: ") + e.what();
        peaks.stop(o.end);
        return;
      }
      if (!std::isfinite(all)) {
        o.end = "stopped: non-finite stress";
        peaks.stop(o.end);
        return;
      }
      csv.row({view.time * cs / W, hole, all});
      if (hole > o.peak_hole) {
        o.peak_hole = hole;
        o.peak_time = view.time * cs / W;
      }
      o.peak_all = std::max(o.peak_all, all);
    }
  });
  sphstab::RunOptions ro{.dt = o.dt, .max_steps = nsteps, .snapshot_every = static_cast<int>(every)};
  ro.observers = {&peaks};
  const RunResult result = sphstab::run(stepper, ro);
  if (result.status == RunStatus::Exception)
    o.end = "stopped: " + result.reason;
  else if (!result.completed() && result.status != RunStatus::Stopped)
    o.end = "stopped: " + result.message;
  o.steps = stepper.steps();
  std::cout << run.tag << " dynamic: " << o.steps << " steps, " << o.end << ", peak near hole " << o.peak_hole
            << " MPa at t = " << o.peak_time << " W/c_s" << std::endl;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Issue 11 / Ismail 2009 §5.4.4: plate with a hole (quarter), static TL SPH against Kirsch"};
  std::string out = "results/tl-plate-hole";
  double c_hg = 0;
  int finest = 32;
  double transits = 6;
  app.add_option("--out", out, "output directory");
  app.add_option("--hourglass", c_hg, "hourglass coefficient c_HG (0 = off)")->check(CLI::NonNegativeNumber);
  app.add_option("--finest", finest, "finest a/dx of the resolution study (4, 8, 16, ...)")->check(CLI::Range(4, 64));
  app.add_option("--transits", transits, "length of the dynamic runs in shear transit times W / c_s")
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  std::vector<Run> runs;
  for (int n = 4; n <= finest; n *= 2)
    runs.push_back({"linear-n" + std::to_string(n) + "-w5", "hooke", double(n), 5, 0.3, 70, 70e-3, 1});
  for (int w : {10, 20}) runs.push_back({"linear-n8-w" + std::to_string(w), "hooke", 8, double(w), 0.3, 70, 70e-3, 1});
  runs.push_back({"linear-n8-w5-lumped", "hooke", 8, 5, 0.3, 70, 70e-3, 1, true});
  for (int n = 4; n <= std::min(finest, 16); n *= 2) {
    runs.push_back({"ismail-hooke-n" + std::to_string(n), "hooke", double(n), 5, 0.49, 70, 5, 1});
    runs.push_back({"ismail-nh-n" + std::to_string(n), "neo-hookean", double(n), 5, 0.49, 70, 5, 2});
  }
  CsvWriter csv(out + "/cases.csv", {"tag",
                                     "model",
                                     "a_over_dx",
                                     "w_over_a",
                                     "nu",
                                     "youngs_mpa",
                                     "traction_mpa",
                                     "real_particles",
                                     "all_particles",
                                     "dofs",
                                     "newton_iterations",
                                     "relative_residual",
                                     "total_force_over_SW",
                                     "peak_hoop_over_S",
                                     "peak_theta_deg",
                                     "peak_r_over_a",
                                     "kirsch_at_peak",
                                     "edge_over_S",
                                     "heywood_over_S",
                                     "peak_principal_mpa",
                                     "peak_principal_r_over_a",
                                     "max_abs_F_minus_I",
                                     "net_section_over_SW",
                                     "load_column_max_dev",
                                     "seconds"});
  study::Summary summary;
  std::string md_lin, md_w, md_is;
  std::vector<double> res_dx, res_edge, res_peak_err;
  for (const Run& run : runs) {
    const Outcome o = solve(run, c_hg, out);
    const double hw = heywood_gross_concentration(kA, run.w_over_a * kA);
    csv.row({run.tag,
             run.model,
             run.a_over_dx,
             run.w_over_a,
             run.nu,
             run.youngs,
             run.traction,
             o.real,
             o.particles,
             o.dofs,
             o.iterations,
             o.residual,
             o.total_force,
             o.peak_hoop,
             o.peak_theta,
             o.peak_r,
             o.kirsch_at_peak,
             o.edge,
             hw,
             o.peak_principal,
             o.peak_principal_r / kA,
             o.max_strain,
             o.net_section,
             o.load_column,
             o.seconds});
    const std::vector<std::string> common{study::sig(run.a_over_dx), study::sig(run.w_over_a), std::to_string(o.real),
                                          std::to_string(o.iterations), study::sig(o.residual, 2)};
    if (run.tag.rfind("linear", 0) == 0) {
      std::vector<std::string> row = common;
      for (const std::string& c :
           {study::fixed(o.total_force, 4), study::fixed(o.peak_hoop, 3), study::fixed(o.peak_r, 3),
            study::fixed(o.peak_theta, 1), study::fixed(o.kirsch_at_peak, 3), study::fixed(o.edge, 3),
            study::fixed(hw, 3), study::fixed(o.net_section, 4), std::string(run.lumped ? "lumped" : "consistent"),
            study::fixed(o.load_column, 4), study::fixed(o.seconds, 1)})
        row.push_back(c);
      const bool resolution = run.w_over_a == 5 && !run.lumped;
      study::md_row(resolution ? md_lin : md_w, row);
      if (resolution) {
        res_dx.push_back(kA / run.a_over_dx);
        res_edge.push_back(o.edge);
        res_peak_err.push_back(o.peak_hoop - o.kirsch_at_peak);
      }
    } else {
      std::vector<std::string> row{run.model,
                                   study::sig(run.a_over_dx),
                                   std::to_string(run.steps),
                                   std::to_string(o.iterations),
                                   study::sig(o.residual, 2),
                                   study::fixed(o.max_strain, 3),
                                   study::fixed(o.peak_hoop * run.traction, 2),
                                   study::fixed(o.peak_hoop, 3),
                                   study::fixed(o.peak_principal, 2),
                                   study::fixed(o.peak_principal / run.traction, 3),
                                   study::fixed(o.seconds, 1)};
      study::md_row(md_is, row);
    }
  }
  // the suddenly applied load (Ismail's "dynamically from rest") on his 21 x 21-like grid and at twice the resolution
  std::string md_dyn;
  for (int n : {4, 8}) {
    const Run run{"ismail-nh-n" + std::to_string(n), "neo-hookean", double(n), 5, 0.49, 70, 5, 1};
    const DynamicOutcome d = dynamic_step(run, c_hg, transits, out);
    study::md_row(md_dyn, {study::sig(run.a_over_dx),
                           study::sig(d.dt * std::sqrt(LameParameters::from_young_poisson(70, 0.49).mu) / 5, 3),
                           std::to_string(d.steps), d.end, study::fixed(d.peak_hole, 2), study::fixed(d.peak_time, 2),
                           study::fixed(d.peak_all, 2)});
  }
  summary.set("dynamic", md_dyn);
  summary.set("transits", transits, 3);
  // observed order of the edge value: successive differences of the W/a = 5 sequence (dx halves)
  std::string orders;
  for (std::size_t k = 0; k + 2 < res_edge.size(); ++k) {
    const double p =
        std::log(std::abs(res_edge[k] - res_edge[k + 1]) / std::abs(res_edge[k + 1] - res_edge[k + 2])) / std::log(2.0);
    orders += (orders.empty() ? "" : ", ") + study::sig(p, 3);
  }
  summary.set("orders_edge", orders.empty() ? "-" : orders);
  summary.set("slope_peak_error", study::loglog_slope(res_dx, res_peak_err), 3);
  summary.set("hourglass", c_hg, 3);
  summary.set("linear", md_lin);
  summary.set("width", md_w);
  summary.set("ismail", md_is);
  summary.set("heywood5", heywood_gross_concentration(1, 5), 4);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.set("load", study::load_average());
  summary.write(out);
  return 0;
}
