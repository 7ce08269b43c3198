#pragma once
// The suddenly applied load of the plate-with-hole study ([Ismail2009, §5.4.4], "loaded dynamically from rest"):
// Ismail's Neo-Hookean case by leap-frog from rest (time step from the linearisation at rest by power iteration) and
// the largest principal Cauchy stress near the hole and anywhere against time (dynamic_<tag>.csv).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <exception>
#include <iostream>
#include <memory>
#include <string>

#include "plate_model.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace plate_hole {

using namespace sphstab;

/// The suddenly applied load of [Ismail2009, §5.4.4] ("loaded dynamically from rest"): leap-frog from rest with the
/// traction switched on at t = 0 and no damping, rho = 1 (the stress history in units of the transit time W / c_s
/// does not depend on rho). Records the largest principal Cauchy stress near the hole (r < a + 2 dx) and anywhere.
struct DynamicOutcome {
  double peak_hole = 0, peak_time = 0, peak_all = 0, dt = 0, t_end = 0;
  long steps = 0;
  std::string end = "completed";
};

inline DynamicOutcome dynamic_step(const Run& run, double c_hg, double transits, const std::string& out) {
  DynamicOutcome o;
  const PlateModel m = plate_model(run, c_hg);
  const FiniteStrainTotalLagrangian<2>& tl = *m.tl;
  const int nr = m.nr;
  const Eigen::VectorXd load =
      consistent_traction(m.plate, *m.disc, run.traction).cwiseQuotient(tl.dof_mass().head(nr));
  // dt: 0.4 x the leap-frog limit 2 / sqrt(mu_max), mu_max of A at rest by power iteration (dominant |eigenvalue|)
  const Eigen::SparseMatrix<double> A =
      SparseMatrix<>(ComplexStepJacobian(tl).compute(Eigen::VectorXd::Zero(tl.dofs())).topRows(nr)) * m.T;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(nr);
  double mu_max = 0;
  for (int it = 0; it < 300; ++it) {
    const Eigen::VectorXd y = A * x;
    mu_max = y.norm() / x.norm();
    x = y / y.norm();
  }
  o.dt = 0.4 * 2 / std::sqrt(mu_max);
  const double cs = std::sqrt(m.material->material().mu() / 1.0);
  o.t_end = transits * m.W / cs;
  SecondOrderSystem sys;
  Eigen::VectorXd a_all;
  sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) {
    tl.acceleration(m.T * u, a_all);
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
        const Eigen::MatrixXd F = tl.deformation_gradients(m.T * view.u);
        for (int i = 0; i < m.plate.real_count; ++i) {
          Deformation<double, 2> Fi;
          Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
          const Eigen::Matrix2d c = m.material->cauchy_stress(Fi);
          const double p1 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(0.5 * (c + c.transpose())).eigenvalues()[1];
          all = std::max(all, p1);
          if (m.plate.particles.x.row(i).norm() < kA + 2 * m.dx) hole = std::max(hole, p1);
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
      csv.row({view.time * cs / m.W, hole, all});
      if (hole > o.peak_hole) {
        o.peak_hole = hole;
        o.peak_time = view.time * cs / m.W;
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

}  // namespace plate_hole
