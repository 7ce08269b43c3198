#include "sphstab/stability/lattice_mode_wavevector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sphstab {
namespace {

TEST(LatticeModeWavevector, RecoversASineModeAndTheSawtooth) {
  const int nx = 9, ny = 7;
  Eigen::MatrixX2d x(nx * ny, 2);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * nx * ny), saw = f;
  int p = 0;
  for (int j = ny - 1; j >= 0; --j)  // any order
    for (int i = 0; i < nx; ++i, ++p) {
      x.row(p) << 0.5 + 2.0 * i, -1.0 + 2.0 * j;
      f[2 * p + 1] =
          std::sin(3 * std::numbers::pi * (i + 1) / (nx + 1)) * std::sin(5 * std::numbers::pi * (j + 1) / (ny + 1));
      saw[2 * p] = ((i + j) % 2 ? -1.0 : 1.0);
    }
  LatticeModeEstimate e = dominant_wavevector_2d(f, x, 2.0);
  EXPECT_EQ(e.nx, nx);
  EXPECT_EQ(e.ny, ny);
  EXPECT_EQ(e.mx, 3);
  EXPECT_EQ(e.my, 5);
  EXPECT_EQ(e.component, 1);
  EXPECT_NEAR(e.fraction, 1.0, 1e-12);
  EXPECT_NEAR(e.kx, 0.3, 1e-15);
  EXPECT_NEAR(e.ky, 5.0 / 8.0, 1e-15);
  e = dominant_wavevector_2d(saw, x, 2.0);
  EXPECT_EQ(e.component, 0);
  EXPECT_EQ(e.mx, nx);  // the sawtooth projects mostly on the highest sine
  EXPECT_EQ(e.my, ny);
}

TEST(LatticeModeWavevector, BadInput) {
  Eigen::MatrixX2d x(3, 2);
  x << 0, 0, 1, 0, 2, 0;
  EXPECT_THROW(dominant_wavevector_2d(Eigen::VectorXd::Zero(5), x, 1.0), std::invalid_argument);
  EXPECT_THROW(dominant_wavevector_2d(Eigen::VectorXd::Zero(6), x, 0.0), std::invalid_argument);
  x(1, 0) = 1.5;  // off the lattice
  EXPECT_THROW(dominant_wavevector_2d(Eigen::VectorXd::Zero(6), x, 1.0), std::invalid_argument);
  x(1, 0) = 2.0;  // duplicate point
  EXPECT_THROW(dominant_wavevector_2d(Eigen::VectorXd::Zero(6), x, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
