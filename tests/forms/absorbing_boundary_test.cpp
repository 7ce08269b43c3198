// Boundary-particle accelerations of the first-order absorbing conditions (forms/absorbing_boundary.hpp): the
// Sochaki law equals (2.45) written out for n = +x, every law is rotation covariant and independent of the tangent's
// orientation, and outgoing P and S plane waves at normal incidence satisfy them exactly.
#include "sphstab/forms/absorbing_boundary.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>

namespace sphstab {
namespace absorbing_boundary_test {

const double kCp = 1.8708, kCs = 1.0;

TEST(AbsorbingBoundary, SochakiIsEquation245AlongX) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Matrix2d L = Eigen::Matrix2d::NullaryExpr([&] { return u(rng); });
    const Eigen::Vector2d a = absorbing_acceleration(AbsorbingCondition::Sochaki, kCp, kCs, Eigen::Vector2d(1, 0), L,
                                                     Eigen::Vector2d::Zero());
    // (2.45) in velocity form: v_t = -diag(c_p, c_s) v_x - [[0, d], [d, 0]] v_y, d = c_p - c_s, v_x = L.col(0).
    const double d = kCp - kCs;
    EXPECT_NEAR(a[0], -kCp * L(0, 0) - d * L(1, 1), 1e-14);
    EXPECT_NEAR(a[1], -kCs * L(1, 0) - d * L(0, 1), 1e-14);
    const Eigen::Vector2d p = absorbing_acceleration(AbsorbingCondition::ClaytonEngquist, kCp, kCs,
                                                     Eigen::Vector2d(1, 0), L, Eigen::Vector2d::Zero());
    EXPECT_NEAR(p[0], -kCp * L(0, 0), 1e-14);
    EXPECT_NEAR(p[1], -kCs * L(1, 0), 1e-14);
  }
}

TEST(AbsorbingBoundary, RotationCovariantWithConvection) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (AbsorbingCondition c : {AbsorbingCondition::ClaytonEngquist, AbsorbingCondition::Sochaki})
    for (int k = 0; k < 20; ++k) {
      const Eigen::Matrix2d L = Eigen::Matrix2d::NullaryExpr([&] { return u(rng); });
      const Eigen::Vector2d v(u(rng), u(rng));
      const Eigen::Matrix2d R = Eigen::Rotation2Dd(M_PI * u(rng)).toRotationMatrix();
      const Eigen::Vector2d a = absorbing_acceleration(c, kCp, kCs, Eigen::Vector2d(1, 0), L, v, true);
      const Eigen::Vector2d b = absorbing_acceleration(c, kCp, kCs, R.col(0), R * L * R.transpose(), R * v, true);
      EXPECT_LT((b - R * a).norm(), 1e-13);
      EXPECT_LT((absorbing_acceleration(c, kCp, kCs, Eigen::Vector2d(1, 0), L, v, true) -
                 absorbing_acceleration(c, kCp, kCs, Eigen::Vector2d(1, 0), L, Eigen::Vector2d::Zero()) - L * v)
                    .norm(),
                1e-14);
    }
}

TEST(AbsorbingBoundary, OutgoingPlaneWavesAtNormalIncidenceAreExact) {
  // v = f(n . x - c t) d: L = f' d n^T, dv/dt = -c f' d, for (d, c) = (n, c_p) and (t, c_s); any n.
  for (double phi : {0.0, 0.7, 2.5}) {
    const Eigen::Vector2d n(std::cos(phi), std::sin(phi)), t(n[1], -n[0]);
    const double fp = 0.37;
    for (AbsorbingCondition c : {AbsorbingCondition::ClaytonEngquist, AbsorbingCondition::Sochaki}) {
      const Eigen::Vector2d ap =
          absorbing_acceleration(c, kCp, kCs, n, fp * n * n.transpose(), Eigen::Vector2d::Zero());
      EXPECT_LT((ap + kCp * fp * n).norm(), 1e-14);
      const Eigen::Vector2d as =
          absorbing_acceleration(c, kCp, kCs, n, fp * t * n.transpose(), Eigen::Vector2d::Zero());
      EXPECT_LT((as + kCs * fp * t).norm(), 1e-14);
    }
  }
  EXPECT_EQ(absorbing_acceleration_1d(2.0, 1.0, 0.5, 0.0), -1.0);
  EXPECT_EQ(absorbing_acceleration_1d(2.0, -1.0, 0.5, 0.1, true), 1.0 + 0.05);
  EXPECT_THROW(absorbing_acceleration(AbsorbingCondition::Higdon, kCp, kCs, Eigen::Vector2d(1, 0),
                                      Eigen::Matrix2d::Zero(), Eigen::Vector2d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(absorbing_acceleration(AbsorbingCondition::Sochaki, kCp, kCs, Eigen::Vector2d(1, 1),
                                      Eigen::Matrix2d::Zero(), Eigen::Vector2d::Zero()),
               std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
