#pragma once
// The static solution of one case of the plate-with-hole study (issue 11, [Ismail2009, §5.4.4]) and its measures: the
// finite-strain TL SPH form (NCSPH corrected reference gradient, difference strain, Plus divergence) on the quarter
// plate with mirror layers on the symmetry planes (problems/plate_with_hole.hpp), solved by Newton with the
// complex-step Jacobian and a sparse LU (load steps for Neo-Hookean), then
//   - the first ring (a <= r < a + dx): the largest hoop stress / S with Kirsch's value at the same point;
//   - the edge value sigma_xx(0, a) / S, extrapolated along the column x = dx/2, and the net-section force there;
//   - the largest principal stress, max |F - I|, the consistent load's total and the loaded column's deviation;
//   - the per-particle CSVs particles_<tag>.csv, ring_<tag>.csv and profile_<tag>.csv.
#include <Eigen/Eigenvalues>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "plate_model.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace plate_hole {

using namespace sphstab;

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

/// Solves `run` statically (hourglass coefficient c_hg) and writes its particle, ring and profile CSVs into `out`.
inline Outcome solve(const Run& run, double c_hg, const std::string& out) {
  const auto t0 = study::Clock::now();
  Outcome o;
  const PlateModel model = plate_model(run, c_hg);
  const PlateWithHole& plate = model.plate;
  const FiniteStrainTotalLagrangian<2>& tl = *model.tl;
  const SparseMatrix<>& T = model.T;
  const int nr = model.nr;
  const double dx = model.dx, W = model.W;
  const auto& disc = model.disc;
  const auto& material = model.material;
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

}  // namespace plate_hole
