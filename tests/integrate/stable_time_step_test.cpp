// The leap-frog limit dt = 2 / sqrt(lambda_max(M^-1 K)) of a linearised force function
// (integrate/stable_time_step.hpp): LAPACK against Spectra, the periodic lattice against the von Neumann symbol of
// the kernel, the limit itself by stepping just below and above it, and bad input.
#include "sphstab/integrate/stable_time_step.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace stable_time_step_test {

const ElasticMaterial kLame = ElasticMaterial::from_lame(1.2, 0.8, 1.0);

std::shared_ptr<const Discretisation<1>> bar(int n, double h_over_dx, KernelType type, bool periodic = false) {
  const Kernel<1> kernel(type);
  const ParticleSet<1> set = make_lattice<1>(
      LatticeType::Line, n, {.spacing = 1.0, .support_radius = kernel.support_radius(h_over_dx), .periodic = periodic});
  return make_discretisation(set, kernel, h_over_dx);
}

Eigen::VectorXd random_vector(int n, double amp, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-amp, amp);
  Eigen::VectorXd v(n);
  for (int k = 0; k < n; ++k) v[k] = dist(gen);
  return v;
}

TEST(StableTimeStep, DiagonalSystemIsTwoOverTheLargestFrequency) {
  SparseMatrix<> a(2, 2);
  a.insert(0, 0) = 4;
  a.insert(1, 1) = 9;
  const StableTimeStep r = stable_time_step(a, Eigen::Vector2d(1.0, 3.0));
  EXPECT_EQ(r.status, Status::Successful);
  EXPECT_NEAR(r.lambda_max, 9.0, 1e-12);
  EXPECT_NEAR(r.dt, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(r.asymmetry, 0.0, 1e-15);
}

TEST(StableTimeStep, SpectraAgreesWithLapackOnADeformedNeoHookeanBar) {
  // Unequal volumes (perturbed stretch) and a finite deformation: M A is symmetric (variational pair), A is not.
  auto d = bar(160, 1.6, KernelType::ModifiedMollifier);
  FiniteStrainTotalLagrangian<1> tl(d, std::make_shared<NeoHookean<1>>(kLame),
                                    Eigen::VectorXd::LinSpaced(d->size(), 2.0, 5.0));
  Eigen::VectorXd fixed(d->size() - d->free_count());
  for (int i = 0, k = 0; i < d->size(); ++i)
    if (d->free_slot[i] < 0) fixed[k++] = 0.3 * d->particles.x(i, 0);
  tl.set_fixed_displacement(fixed);  // a 30 % stretch, perturbed
  Eigen::VectorXd u = 0.3 * d->free_positions().col(0) + random_vector(tl.dofs(), 0.05, 7);
  const StableTimeStep dense = stable_time_step(tl, u, {.route = EigenRoute::Dense});
  const StableTimeStep spectra = stable_time_step(tl, u, {.route = EigenRoute::Spectra});
  ASSERT_EQ(dense.status, Status::Successful);
  ASSERT_EQ(spectra.status, Status::Successful);
  EXPECT_EQ(dense.route, "dense");
  EXPECT_EQ(spectra.route, "spectra");
  EXPECT_LT(dense.asymmetry, 1e-12);  // S = M^1/2 A M^-1/2 is symmetric for the variational pair (round-off only)
  EXPECT_NEAR(spectra.lambda_max / dense.lambda_max, 1.0, 1e-10);
  EXPECT_NEAR(spectra.dt / dense.dt, 1.0, 1e-10);
}

TEST(StableTimeStep, PeriodicLatticeIsTheVonNeumannLimitOfTheKernel) {
  // Periodic Hooke bar (c = sqrt(E / rho)): A = c^2 X^T X, eigenvalues c^2 |X(k)|^2 with
  // X(k) = 2 sum_{j > 0} W'(j dx) dx sin(k j dx) at k = 2 pi m / (N dx) (a von Neumann check of [Ismail2009, (4.46)]).
  const int n = 64;
  const double rho = 3.0;
  for (const auto type : {KernelType::ModifiedMollifier, KernelType::CubicSpline}) {
    for (const double hdx : {1.0, 1.5, 2.75}) {
      auto d = bar(n, hdx, type, true);
      const Hooke<1> hooke(kLame, UniaxialState::Stress);
      const double e_young = kLame.mu() * (3 * kLame.lambda() + 2 * kLame.mu()) / (kLame.lambda() + kLame.mu());
      FiniteStrainTotalLagrangian<1> tl(d, std::make_shared<Hooke<1>>(kLame, UniaxialState::Stress), rho);
      const StableTimeStep r = stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs()));
      double xmax = 0;
      for (int m = 0; m <= n / 2; ++m) {
        const double k = 2 * std::numbers::pi * m / n;
        double s = 0;
        for (int j = 1; j <= n / 2 && j < d->kernel.support_radius(hdx) + 1; ++j)
          s += d->kernel.d1(static_cast<double>(j), hdx) * std::sin(k * j);
        xmax = std::max(xmax, std::abs(2 * s));
      }
      const double c = std::sqrt(e_young / rho);
      ASSERT_EQ(r.status, Status::Successful);
      EXPECT_NEAR(r.dt * c * xmax / 2, 1.0, 1e-9) << kernel_name(type) << " h/dx " << hdx;
    }
  }
}

TEST(StableTimeStep, LeapfrogIsBoundedJustBelowTheLimitAndGrowsJustAbove) {
  auto d = bar(60, 2.75, KernelType::ModifiedMollifier);
  FiniteStrainTotalLagrangian<1> tl(d, std::make_shared<Hooke<1>>(kLame, UniaxialState::Stress), 2.0);
  const StableTimeStep r = stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs()));
  const Eigen::VectorXd m = tl.dof_mass(), u0 = random_vector(tl.dofs(), 1e-12, 3);
  auto energy_growth = [&](double dt) {
    SecondOrderSystem sys;
    sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { tl.acceleration(u, a); };
    sys.mass = m;
    LeapfrogStepper s(sys, u0, Eigen::VectorXd::Zero(tl.dofs()));
    const double e0 = tl.strain_energy(u0);
    double worst = 1;
    for (int k = 0; k < 2000; ++k) {
      s.step(dt);
      const double e = 0.5 * s.v().dot(m.cwiseProduct(s.v())) + tl.strain_energy(s.u());
      worst = std::max(worst, e / e0);
      if (worst > 1e20) break;  // strain ~1e-2: stop before the growing mode inverts a particle
    }
    return worst;
  };
  // Below the limit the leap-frog energy oscillates within a bounded factor (<= 1 / (1 - (w dt / 2)^2) ~ 50 at
  // 0.99) ; 1 % above it the top mode grows by ~ 1 + sqrt(8 * 0.01) per step.
  EXPECT_LT(energy_growth(0.99 * r.dt), 100.0);
  EXPECT_GT(energy_growth(1.01 * r.dt), 1e20);
  EXPECT_EQ(r.route, "dense");
}

TEST(StableTimeStep, BadInputIsOneLineInvalidArgument) {
  SparseMatrix<> a(2, 2);
  a.insert(0, 0) = 1;
  EXPECT_THROW(stable_time_step(a, Eigen::VectorXd::Ones(3)), std::invalid_argument);
  EXPECT_THROW(stable_time_step(a, Eigen::Vector2d(1.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(stable_time_step(SparseMatrix<>(2, 3), Eigen::VectorXd::Ones(2)), std::invalid_argument);
  try {
    stable_time_step(a, Eigen::VectorXd::Ones(3));
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_EQ(std::string(e.what()).rfind("stable_time_step:", 0), 0u);
  }
}

}  // namespace
}  // namespace sphstab
