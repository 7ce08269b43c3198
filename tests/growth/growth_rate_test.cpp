#include "sphstab/growth/growth_rate.hpp"

#include <gtest/gtest.h>

namespace sphstab {
namespace growth_rate_test {

TEST(GrowthRate, SymmetricTwoByTwo) {
  // mu = 3 (stable, oscillation frequency sqrt 3) and mu = -1 (growth e^t along (1, -1)).
  Eigen::Matrix2d a;
  a << 1, 2, 2, 1;
  GrowthAnalysis g = growth_rate(a, Eigen::Vector2d(0.5, 1.5));
  ASSERT_EQ(g.status, Status::Successful);
  EXPECT_NEAR(g.growth_rate, 1.0, 1e-14);
  ASSERT_EQ(g.unstable.size(), 1u);
  EXPECT_NEAR(g.unstable[0].mu.real(), -1.0, 1e-14);
  EXPECT_NEAR(std::abs(g.unstable[0].shape[0] + g.unstable[0].shape[1]), 0.0, 1e-14);
  // Two points with fixed ends: sin(2 pi (i+1)/3) is the alternating mode, k dx/pi = 2/3 by both methods.
  EXPECT_NEAR(g.unstable[0].wavenumber.k_projection, 2.0 / 3, 1e-15);
  EXPECT_NEAR(g.unstable[0].wavenumber.k_sign_changes, 2.0 / 3, 1e-15);
}

TEST(GrowthRate, NonsymmetricComplexPair) {
  // mu = +-i: sqrt(-i) = e^{-i pi/4}, growth cos(pi/4) for the pair (flutter-type instability).
  Eigen::Matrix2d a;
  a << 0, 1, -1, 0;
  GrowthAnalysis g = growth_rate(a, Eigen::Vector2d(0.5, 1.5));
  EXPECT_NEAR(g.growth_rate, std::sqrt(0.5), 1e-14);
  ASSERT_EQ(g.unstable.size(), 1u);  // one entry per conjugate pair
  EXPECT_NEAR(g.unstable[0].growth, std::sqrt(0.5), 1e-14);
}

TEST(GrowthRate, PositiveDefiniteIsStable) {
  Eigen::Matrix3d a;
  a << 2, -1, 0, -1, 2, -1, 0, -1, 2;
  GrowthAnalysis g = growth_rate(a, Eigen::Vector3d(0, 1, 2));
  EXPECT_LT(g.growth_rate, 1e-7);
  EXPECT_TRUE(g.unstable.empty());
}

TEST(GrowthRate, RejectsBadInput) {
  EXPECT_THROW(growth_rate(Eigen::MatrixXd(2, 3), Eigen::Vector2d(0, 1)), std::invalid_argument);
  EXPECT_THROW(growth_rate(Eigen::Matrix2d::Identity(), Eigen::Vector3d(0, 1, 2)), std::invalid_argument);
}

TEST(DominantWavenumber, PureModesExact) {
  const int n = 40;
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = n - i;  // reversed order: sorting by x is part of the method
  for (int m : {1, 7, 40}) {
    Eigen::VectorXd v(n);
    for (int i = 0; i < n; ++i) v[i] = std::sin(m * M_PI * (n - i) / (n + 1));
    WavenumberEstimate w = dominant_wavenumber(v, x, false);
    EXPECT_NEAR(w.k_projection, double(m) / (n + 1), 1e-15);
    EXPECT_NEAR(w.projection_fraction, 1.0, 1e-12);
    EXPECT_NEAR(w.k_sign_changes, double(m) / (n + 1), 1e-15);
  }
  Eigen::VectorXd saw(n);
  for (int i = 0; i < n; ++i) saw[i] = (i % 2 == 0) ? 1 : -1;
  WavenumberEstimate p = dominant_wavenumber(saw, x, true);
  EXPECT_NEAR(p.k_projection, 1.0, 1e-15);
  EXPECT_NEAR(p.k_sign_changes, 1.0, 1e-15);
}

}  // namespace
}  // namespace sphstab
