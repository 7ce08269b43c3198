#include "sphstab/spectral/tension_estimates.hpp"

#include <gtest/gtest.h>

#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace sphstab {
namespace tension_estimates_test {

TEST(TensionEstimates1D, CubicByHandAtHEqualsOnePointTwoFive) {
  // Cubic B-spline, support 2h, h = 1.25, dx = 1: neighbours at q = 0.8 and 1.6.
  // f'(0.8) = -0.96, f'(1.6) = -0.12, f''(0.8) = f''(1.6) = 0.6; W' = (2/3)/h^2 f' = (32/75) f',
  // W'' = (2/3)/h^3 f'' = (128/375) f''. So W'(1) = -0.4096, W'(2) = -0.0512, W''(1) = W''(2) = 0.2048.
  // k_ii = 2 (0.4096^2 + 0.0512^2) = 0.3407872, l_ii = 4 * 0.2048 = 0.8192,
  // k_next = 2 * 0.4096 * 0.0512 = 0.04194304, l_next = -0.2048. With n = 4 (conservative):
  // (3.42) 0.3407872 / 3.2768 = 0.104; (3.49) min(0.29884416 / 4.096, 0.38273024 / 2.4576) = 0.07296;
  // (3.43) 0.4096^2 / (4 * 0.2048) = 0.2048; (3.51) 2/3 of it; Swegle: W''(dx) > 0 so 0.
  Kernel<1> cubic(KernelType::CubicSpline);
  TensionEstimates1D e = tension_estimates_1d(cubic, 1.25, 1.0, 4);
  EXPECT_NEAR(e.k_ii, 0.3407872, 1e-15);
  EXPECT_NEAR(e.l_ii, 0.8192, 1e-15);
  EXPECT_NEAR(e.k_next, 0.04194304, 1e-15);
  EXPECT_NEAR(e.l_next, -0.2048, 1e-15);
  EXPECT_NEAR(e.first_minor, 0.104, 1e-15);
  EXPECT_NEAR(e.second_minor, 0.07296, 1e-15);
  EXPECT_NEAR(e.nearest_neighbour, 0.2048, 1e-15);
  EXPECT_NEAR(e.nearest_neighbour_minor, 0.2048 * 2 / 3, 1e-15);
  EXPECT_EQ(e.swegle, 0.0);
  // Forms scale with 1/n; minus (n = 0) gives inf.
  TensionEstimates1D u = tension_estimates_1d(cubic, 1.25, 1.0, 1);
  EXPECT_NEAR(u.first_minor, 4 * 0.104, 1e-14);
  TensionEstimates1D m = tension_estimates_1d(cubic, 1.25, 1.0, 0);
  EXPECT_TRUE(std::isinf(m.first_minor) && std::isinf(m.second_minor) && std::isinf(m.swegle));
}

TEST(TensionEstimates1D, NoNeighbourInsideTheSupportGivesNaNNotInf) {
  const Kernel<1> k(KernelType::CubicSpline);
  const TensionEstimates1D e = tension_estimates_1d(k, 0.5, 1.0, 4);  // support exactly dx: strict, no neighbour
  EXPECT_TRUE(std::isnan(e.first_minor) && std::isnan(e.second_minor) && std::isnan(e.nearest_neighbour) &&
              std::isnan(e.nearest_neighbour_minor) && std::isnan(e.swegle));
  EXPECT_TRUE(std::isnan(critical_tension_infinite_1d(k, 0.5, 1.0, 4).tcrit));
  EXPECT_TRUE(std::isfinite(tension_estimates_1d(k, 0.51, 1.0, 4).first_minor));
}

TEST(TensionEstimates1D, NearestNeighbourCaseReducesToPowell350) {
  // h = dx: only the nearest neighbours interact (q = 1; W' = -1/2, W'' = 1 for h = 1). Then K_{i,i+1} = 0,
  // A_ii = 2 W'^2 - 2nT W'', A_{i,i+1} = nT W'': (3.42) = (3.43) = 1/16 and (3.49) = (3.51) = 1/24 for n = 4.
  Kernel<1> cubic(KernelType::CubicSpline);
  TensionEstimates1D e = tension_estimates_1d(cubic, 1.0, 1.0, 4);
  EXPECT_NEAR(e.first_minor, 1.0 / 16, 1e-15);
  EXPECT_NEAR(e.nearest_neighbour, 1.0 / 16, 1e-15);
  EXPECT_NEAR(e.second_minor, 1.0 / 24, 1e-15);
  EXPECT_NEAR(e.nearest_neighbour_minor, 1.0 / 24, 1e-15);
  EXPECT_EQ(e.k_next, 0.0);
}

TEST(TensionEstimates1D, KernelSumsEqualMatrixEntriesAndBoundTcrit) {
  for (KernelType type : {KernelType::QuinticSpline, KernelType::WendlandC4, KernelType::Gaussian}) {
    Kernel<1> kernel(type);
    for (double h : {0.85, 1.45, 2.7}) {
      auto p = make_lattice<1>(LatticeType::Line, 30, {.spacing = 1.0, .support_radius = 2 * h});
      const Linearisation jac = analytic_jacobian_1d(p, kernel, h);  // uncorrected: the K and L of (3.40)
      TensionEstimates1D a = tension_estimates_1d(kernel, h, 1.0, 4), b = tension_estimates_1d(jac, 14, 4);
      EXPECT_NEAR(a.k_ii, b.k_ii, 1e-14 * a.k_ii);
      EXPECT_NEAR(a.l_ii, b.l_ii, 1e-13 * std::abs(a.l_ii) + 1e-15);
      EXPECT_NEAR(a.k_next, b.k_next, 1e-14 * a.k_ii);
      EXPECT_NEAR(a.l_next, b.l_next, 1e-14 * std::abs(a.l_ii) + 1e-15);
      // Principal minors are necessary conditions: the matrix T_crit never exceeds them.
      const CriticalLoad r = critical_tension_1d(p, kernel, h, MomentumForm::Conservative);
      EXPECT_LE(r.load, a.second_minor * (1 + 1e-12));
      EXPECT_LE(a.second_minor, a.first_minor * (1 + 1e-15));
    }
  }
}

TEST(TensionEstimates1D, RejectsBadInput) {
  Kernel<1> kernel(KernelType::CubicSpline);
  EXPECT_THROW(tension_estimates_1d(kernel, 0.0, 1.0, 4), std::invalid_argument);
  EXPECT_THROW(tension_estimates_1d(kernel, 1.0, -1.0, 4), std::invalid_argument);
  EXPECT_THROW(tension_estimates_1d(kernel, 1.0, 1.0, -4), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
