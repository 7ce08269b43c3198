// leapfrog_growth_rate (integrate/time_step.hpp): the leap-frog rate from the eigenvalues of A against the dense
// one-step map of growth/linear_growth.hpp, and the closed forms of the stable and the time-step-unstable mode.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/integrate/time_step.hpp"

namespace sphstab {
namespace leapfrog_growth_rate_test {

TEST(LeapfrogGrowthRate, AgreesWithTheDenseOneStepMapOnANonsymmetricMatrix) {
  // a random non-symmetric A (complex and real eigenvalues of both signs) at two time steps
  std::srand(7);
  const Eigen::MatrixXd A = Eigen::MatrixXd::Random(24, 24) + 3 * Eigen::MatrixXd::Identity(24, 24);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(24, 0, 1);
  const GrowthAnalysis g = growth_rate(A, x);
  for (double dt : {0.05, 0.4}) {
    const double map = leapfrog_map_growth(A, dt, Eigen::MatrixXd(), VelocityHookMode::DriftOnly).gamma;
    EXPECT_NEAR(leapfrog_growth_rate(g.eigenvalues, dt), map, 1e-9 * std::max(1.0, map)) << "dt = " << dt;
  }
}

TEST(LeapfrogGrowthRate, StableBelowTheLimitAndAcoshAboveIt) {
  const double dt = 0.1, limit_mu = 4 / (dt * dt);
  Eigen::VectorXcd mu(3);
  mu << 1.0, 0.5 * limit_mu, 0.99 * limit_mu;
  EXPECT_LT(leapfrog_growth_rate(mu, dt), 1e-6);  // |z| = 1 to round-off
  // mu > 4/dt^2: z = b/2 - sqrt(b^2/4 - 1) with b = 2 - dt^2 mu < -2, |z| = cosh(theta) + sinh(theta), so
  // ln|z| = acosh(dt^2 mu / 2 - 1)
  mu[2] = 1.5 * limit_mu;
  EXPECT_NEAR(leapfrog_growth_rate(mu, dt), std::acosh(dt * dt * mu[2].real() / 2 - 1) / dt, 1e-12);
  EXPECT_THROW(leapfrog_growth_rate(mu, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
