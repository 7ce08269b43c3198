#include "sphstab/growth/linear_growth.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace linear_growth_test {

TEST(LinearGrowth, MatrixGrowthOfKnownSpectra) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3, 3);
  A.diagonal() << 4.0, -2.25, 1.0;  // mu = -2.25: growth 1.5
  LinearGrowth g = matrix_growth(A, true);
  EXPECT_NEAR(g.gamma, 1.5, 1e-14);
  EXPECT_NEAR(g.mu.real(), -2.25, 1e-14);
  EXPECT_NEAR(std::abs(g.mode[1]), 1.0, 1e-14);
  EXPECT_NEAR(g.min_real, -2.25, 1e-14);
  // a rotation-like block: mu = 1 +- 2i, growth Re sqrt(-1 - 2i)
  Eigen::MatrixXd B(2, 2);
  B << 1, 2, -2, 1;
  g = matrix_growth(B);
  EXPECT_NEAR(
      g.gamma,
      std::sqrt(std::complex<double>(-1, -2)).real() > 0 ? std::abs(std::sqrt(std::complex<double>(-1, -2)).real()) : 0,
      1e-14);
  EXPECT_THROW(matrix_growth(Eigen::MatrixXd(2, 3)), std::invalid_argument);
}

TEST(LinearGrowth, ComplexStepJacobianAgreesWithTheAnalytic1dJacobian) {
  Kernel<1> k(KernelType::CubicSpline);
  auto set = make_lattice<1>(LatticeType::Line, 21, {.spacing = 1.0, .support_radius = k.support_radius(1.3)});
  auto d = make_discretisation(set, k, 1.3);
  const double T = 0.02;
  WaveForm1D plus(d, MomentumForm::Plus, T);
  const LinearGrowth g = linear_growth(plus, Eigen::VectorXd::Zero(plus.dofs()));
  const Linearisation tj = analytic_jacobian_1d(set, k, 1.3, MomentumForm::Plus);
  const LinearGrowth ga = matrix_growth(Eigen::MatrixXd(tj.at(T)));
  EXPECT_GT(g.gamma, 0.1);
  EXPECT_NEAR(g.gamma, ga.gamma, 1e-10 * ga.gamma);
  EXPECT_LT(g.asymmetry, 1e-14);
}

TEST(LinearGrowth, LeapfrogMapWithoutHookMatchesTheSemiDiscreteRate) {
  // Scalar u'' = gamma^2 u: leap-frog amplification lambda = 1 + x/2 + sqrt(x + x^2/4), x = (gamma dt)^2.
  Eigen::MatrixXd A(1, 1);
  A(0, 0) = -4.0;
  const double dt = 0.01, x = 4.0 * dt * dt;
  const MapGrowth m = leapfrog_map_growth(A, dt, Eigen::MatrixXd(), VelocityHookMode::Replace);
  EXPECT_NEAR(m.spectral_radius, 1 + x / 2 + std::sqrt(x + x * x / 4), 1e-14);
  EXPECT_NEAR(m.gamma, 2.0, 1e-4);  // O((gamma dt)^2) below the semi-discrete rate
  // A stable oscillator is neutral (|lambda| = 1).
  A(0, 0) = 9.0;
  EXPECT_NEAR(leapfrog_map_growth(A, dt, Eigen::MatrixXd(), VelocityHookMode::Replace).spectral_radius, 1.0, 1e-14);
  Eigen::MatrixXd S(1, 1);
  S(0, 0) = 0.9;
  EXPECT_LT(leapfrog_map_growth(A, dt, S, VelocityHookMode::Replace).spectral_radius, 1.0);
  EXPECT_THROW(leapfrog_map_growth(A, 0.0, S, VelocityHookMode::Replace), std::invalid_argument);
  EXPECT_THROW(leapfrog_map_growth(A, dt, Eigen::MatrixXd::Zero(2, 2), VelocityHookMode::Replace),
               std::invalid_argument);
}

}  // namespace
}  // namespace sphstab

namespace sphstab {
namespace linear_growth_test {

TEST(LinearGrowth, LeapfrogMapMatchesTheSteppedAlgorithmWithAHook) {
  // 2 DOFs, one unstable direction, a symmetric smoothing S; the growth per step of the leap-frog stepper with the
  // hook (power iteration of the actual algorithm) must equal the map's spectral radius.
  Eigen::MatrixXd A(2, 2), S(2, 2);
  A << 2.0, -3.0, -3.0, 1.0;  // eigenvalues 1.5 +- sqrt(9.25): one negative
  S << 0.92, 0.05, 0.05, 0.92;
  const double dt = 0.05;
  for (VelocityHookMode mode : {VelocityHookMode::Replace, VelocityHookMode::DriftOnly}) {
    const MapGrowth m = leapfrog_map_growth(A, dt, S, mode);
    SecondOrderSystem sys;
    sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { a = -A * u; };
    sys.velocity_hook = [&](const Eigen::VectorXd&, const Eigen::VectorXd& v, Eigen::VectorXd& w) { w = S * v; };
    sys.hook_mode = mode;
    LeapfrogStepper st(sys, Eigen::Vector2d(1.0, 0.3), Eigen::Vector2d(0.0, 0.1));
    for (int k = 0; k < 400; ++k) st.step(dt);
    Eigen::VectorXd x0(4);
    x0 << st.u(), st.v();
    for (int k = 0; k < 100; ++k) st.step(dt);
    Eigen::VectorXd x1(4);
    x1 << st.u(), st.v();
    EXPECT_NEAR(std::pow(x1.norm() / x0.norm(), 1.0 / 100), m.spectral_radius, 1e-10);
  }
}

}  // namespace
}  // namespace sphstab
