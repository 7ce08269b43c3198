// A pulse in the finite-strain TL bar with a per-particle reference density (forms/finite_strain_total_lagrangian.hpp)
// meets a density step rho2 = 2 rho1 at mid-span: the reflected stress plateau over the incident one is the impedance
// coefficient C_r = (Z2 - Z1)/(Z2 + Z1) = 0.1716 (problems/impedance_step.hpp) and the particle velocity reflects with
// the opposite sign. Same set-up as studies/tl-density-step (Hooke 1D stress, E = 200 GPa, rho1 = 8000, L = 0.3 m,
// modified mollifier h = 2.75 dx), here at n = 600.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/impedance_step.hpp"

namespace sphstab {
namespace density_step_reflection_test {

constexpr double kE = 200e9, kRho1 = 8000, kLength = 0.3, kStep = 0.15, kRise = 2e-6, kDuration = 10e-6;

double shape_integral(double t) {  // integral of the sin^2-ramped unit pulse (rise kRise, total kDuration)
  if (t <= 0) return 0;
  auto ramp_int = [](double x) {
    return 0.5 * x - kRise / (2 * std::numbers::pi) * std::sin(std::numbers::pi * x / kRise);
  };
  if (t < kRise) return ramp_int(t);
  const double rise = ramp_int(kRise);
  if (t < kDuration - kRise) return rise + (t - kRise);
  if (t < kDuration) return rise + (kDuration - 2 * kRise) + (rise - ramp_int(kDuration - t));
  return 2 * rise + kDuration - 2 * kRise;
}

struct Coefficients {
  double stress, velocity;
};

/// Reflected over incident plateau (stress, velocity) at x = 0.05 m for rho2 = ratio rho1 (ratio 1: no step).
Coefficients reflection(double ratio, int n) {
  const double dx = kLength / n, h = 2.75 * dx, c1 = std::sqrt(kE / kRho1);
  const Kernel<1> kernel(KernelType::ModifiedMollifier);
  const auto disc = make_discretisation(
      make_lattice<1>(LatticeType::Line, n, {.spacing = dx, .support_radius = 2 * kernel.support_radius(h)}), kernel,
      h);
  Eigen::VectorXd rho(disc->size());
  for (int i = 0; i < disc->size(); ++i) rho[i] = disc->particles.x(i, 0) < kStep ? kRho1 : ratio * kRho1;
  FiniteStrainTotalLagrangian<1> tl(
      disc, std::make_shared<Hooke<1>>(ElasticMaterial::from_young_poisson(kE, 0.3, 1.0), UniaxialState::Stress), rho);
  std::vector<double> x_fixed;
  for (int i = 0; i < disc->size(); ++i)
    if (disc->free_slot[i] < 0) x_fixed.push_back(disc->particles.x(i, 0));
  const double v0 = 100e3 / (kRho1 * c1);  // the -100 kPa compressive pulse enters from the left
  Eigen::VectorXd d(x_fixed.size());
  SecondOrderSystem sys;
  sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { tl.acceleration(u, a); };
  sys.set_time = [&](double t) {
    for (std::size_t k = 0; k < x_fixed.size(); ++k)
      d[k] = x_fixed[k] < 0 ? v0 * shape_integral(t - x_fixed[k] / c1) : 0;
    tl.set_fixed_displacement(d);
  };
  sys.mass = tl.dof_mass();
  sys.set_time(0);
  const double dt = 0.5 * stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs())).dt;
  LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(tl.dofs()), Eigen::VectorXd::Zero(tl.dofs()));
  int f = 0;
  for (int k = 0; k < disc->free_count(); ++k)
    if (std::abs(disc->particles.x(disc->free[k], 0) - 0.05) < std::abs(disc->particles.x(disc->free[f], 0) - 0.05))
      f = k;
  const double x = disc->particles.x(disc->free[f], 0), ti = x / c1, tr = (2 * kStep - x) / c1;
  double si = 0, vi = 0, sr = 0, vr = 0;
  int ni = 0, nr = 0;
  while (stepper.time() < tr + kDuration) {
    const double t = stepper.time();
    sys.set_time(t);
    const double s = tl.stresses(stepper.u())(disc->free[f], 0), v = stepper.v()[f];
    if (t > ti + kRise && t < ti + kDuration - kRise) si += s, vi += v, ++ni;
    if (t > tr + kRise && t < tr + kDuration - kRise) sr += s, vr += v, ++nr;
    stepper.step(dt);
  }
  EXPECT_GT(ni, 10);
  EXPECT_GT(nr, 10);
  return {(sr / nr) / (si / ni), (vr / nr) / (vi / ni)};
}

TEST(DensityStepReflection, ReflectedStressAmplitudeIsTheImpedanceCoefficient) {
  const double z1 = kRho1 * std::sqrt(kE / kRho1), z2 = 2 * kRho1 * std::sqrt(kE / (2 * kRho1));
  const ImpedanceStep ex = impedance_step(z1, z2);
  ASSERT_NEAR(ex.stress_reflection, (std::sqrt(2.0) - 1) / (std::sqrt(2.0) + 1), 1e-15);
  const Coefficients r = reflection(2.0, 600);
  // Tolerance 0.005 (3 % of C_r): the plateau mean carries the dispersive ringing of the 2 us sin^2 fronts; over
  // n = 300, 600, 1200 (studies/tl-density-step) |R - C_r| = 0.0041, 0.0003, 0.0015 and the velocity ratio agrees with
  // -R_sigma to 0.002. A bar without the step reflects nothing (checked below), so the test can fail.
  EXPECT_NEAR(r.stress, ex.stress_reflection, 5e-3);
  EXPECT_NEAR(r.velocity, ex.velocity_reflection, 5e-3);  // = -C_r: the velocity reflects inverted
  const Coefficients none = reflection(1.0, 600);
  EXPECT_LT(std::abs(none.stress), 5e-3);
}

TEST(ImpedanceStep, ContinuityAndEnergyFlux) {
  for (double z2 : {0.25, 0.5, 1.0, 2.0, 40.0}) {
    const ImpedanceStep c = impedance_step(1.0, z2);
    EXPECT_NEAR(1 + c.stress_reflection, c.stress_transmission, 1e-15);      // stress continuous at the interface
    EXPECT_NEAR(1 + c.velocity_reflection, c.velocity_transmission, 1e-15);  // velocity continuous
    EXPECT_NEAR(c.stress_reflection * c.stress_reflection + c.stress_transmission * c.stress_transmission / z2, 1.0,
                1e-14);  // incident energy flux sigma^2 / Z = reflected + transmitted
    EXPECT_DOUBLE_EQ(c.velocity_reflection, -c.stress_reflection);
  }
  EXPECT_THROW(impedance_step(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(impedance_step(1.0, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
