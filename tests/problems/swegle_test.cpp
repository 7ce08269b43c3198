#include "sphstab/problems/swegle.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/growth/swegle_run.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace sphstab {
namespace swegle_test {

TEST(Swegle, SceneMatchesPowellsSetup) {
  const SwegleScene s = make_swegle_scene({});
  const Discretisation<2>& d = *s.discretisation;
  EXPECT_EQ(d.free_count(), 21 * 21);
  EXPECT_EQ(d.size(), 25 * 25);  // 2 fixed layers: support 2.6 dx
  EXPECT_NEAR(s.material.lambda(), 2.1 * 0.3 / (1.3 * 0.4), 1e-15);
  EXPECT_NEAR(s.material.mu(), 2.1 / 2.6, 1e-15);
  EXPECT_NEAR(s.wave_speed, std::sqrt((s.material.lambda() + 2 * s.material.mu()) / 7.8), 1e-15);
  EXPECT_NEAR(d.particles.x(s.centre, 0), 0.105, 1e-15);
  EXPECT_NEAR(d.particles.x(s.centre, 1), 0.105, 1e-15);
  EXPECT_NEAR(s.initial_kinetic_energy(), 0.5 * 7.8 * 1e-4 * 1e-20, 1e-36);
  const SwegleScene t = make_swegle_scene({.area_ratio = 1.04});
  EXPECT_NEAR(t.prestrain.strain, std::sqrt(1.04) - 1, 1e-15);
  EXPECT_THROW(make_swegle_scene({.n = 2}), std::invalid_argument);
  EXPECT_THROW(make_swegle_scene({.area_ratio = -1}), std::invalid_argument);
  EXPECT_THROW(make_swegle_scene({.velocity = 0}), std::invalid_argument);
  EXPECT_THROW(make_swegle_scene({.poisson_ratio = 0.5}), std::invalid_argument);
}

TEST(Swegle, BasicSphInTensionGrowsAtTheLinearTheoryRate) {
  const SwegleScene s = make_swegle_scene({.area_ratio = 1.04});
  auto force = std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Plus, s.prestrain);
  const GrowthRun run = run_swegle(s, force, {.t_end = 3.0});
  EXPECT_EQ(run.status, RunStatus::DisplacementLimit);  // blows up: a result, not an exception
  ASSERT_TRUE(run.fit.grew);
  // Linear theory in the symmetry class excited by the centre particle moving along +x.
  const MirrorSymmetry sym = mirror_symmetry(s.free_positions(), Eigen::Vector2d(0.105, 0.105), 1e-8);
  const Eigen::MatrixXd Q = symmetry_basis(sym, -1, 1);
  const Eigen::MatrixXd A(jacobian(*force, Eigen::VectorXd::Zero(force->dofs())));
  const double gamma = matrix_growth(Q.transpose() * A * Q).gamma;
  EXPECT_NEAR(gamma, 12.50, 0.01);
  // The fit window starts once the fastest mode carries 100x the initial energy; the next-fastest modes of the class
  // still bias the slope there (measured 2 % low), hence 5 %.
  EXPECT_NEAR(run.fit.gamma / gamma, 1.0, 0.05);
  EXPECT_GT(run.fit.fit.r2, 0.999);
}

TEST(Swegle, ConservativeFormConservesEnergyWithSecondOrderError) {
  // Small block, no pre-stress (stable), a finite perturbation so that the kernel really moves.
  const SwegleScene s = make_swegle_scene({.n = 9, .velocity = 0.01});
  auto force = std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Conservative, s.prestrain);
  SecondOrderSystem sys;
  sys.acceleration = acceleration_function(force);
  sys.strain_energy = [force](const Eigen::VectorXd& u) { return force->strain_energy(u); };
  sys.dofs_per_particle = 2;
  sys.mass = Eigen::VectorXd::Constant(s.discretisation->free_count(), 7.8e-4);
  const double dt0 = 0.3 * s.h / s.wave_speed, T = 2000 * dt0;
  double previous = 0;
  for (double dt : {dt0, dt0 / 2}) {
    LeapfrogOptions o;
    o.dt = dt;
    o.t_end = T;
    o.record_every = 10;
    const LeapfrogResult r = run_leapfrog(sys, Eigen::VectorXd::Zero(force->dofs()), s.v0, o);
    ASSERT_TRUE(r.completed());
    const double e0 = r.history.front().total;
    double dev = 0, st = 0, se = 0, stt = 0, ste = 0;
    for (const Diagnostics& h : r.history) {
      const double e = (h.total - e0) / e0;
      dev = std::max(dev, std::abs(e));
      st += h.time, se += e, stt += h.time * h.time, ste += h.time * e;
    }
    const double n = static_cast<double>(r.history.size());
    const double slope = (ste / n - st / n * se / n) / (stt / n - st / n * st / n);
    EXPECT_LT(dev, 1e-2);                       // bounded O(dt^2) oscillation (4.4e-3 at the CFL step)
    EXPECT_LT(std::abs(slope * T), 0.2 * dev);  // no secular drift beyond a fraction of the oscillation
    // Halving dt divides the error by 4; +-15 % because the kick excites the fastest lattice modes, for which
    // omega dt ~ 0.6 at the CFL step is not yet asymptotic (measured 3.67).
    if (previous > 0) EXPECT_NEAR(previous / dev, 4.0, 0.6);
    previous = dev;
  }
}

}  // namespace
}  // namespace sphstab
