#include "sphstab/spectral/fourier_symbol.hpp"

#include <gtest/gtest.h>

#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace sphstab {
namespace fourier_symbol_test {

TEST(FourierSymbol1D, SawtoothIsInvisibleToTheGradient) {
  for (KernelType type : all_kernel_types()) {
    Kernel<1> kernel(type);
    for (double h : {0.8, 1.3, 2.9}) {
      FourierSymbol1D s = fourier_symbol_1d(kernel, h, 1.0, M_PI);
      EXPECT_LT(s.g_abs2, 1e-28) << kernel_name(type);
    }
  }
}

TEST(FourierSymbol1D, MatchesCirculantEigenvalues) {
  // Periodic N: exp(i k_m x) is an eigenvector of K and L with eigenvalues |g^|^2 and L^.
  Kernel<1> kernel(KernelType::WendlandC4);
  const double h = 1.7;
  const int n = 24;
  auto p = make_lattice<1>(LatticeType::Line, n, {.spacing = 1.0, .periodic = true});
  const Linearisation jac = analytic_jacobian_1d(p, kernel, h);  // uncorrected: A0 = K, A1 = -L
  for (int m = 0; m <= n / 2; ++m) {
    const double k = 2 * M_PI * m / n;
    Eigen::VectorXd c(n);
    for (int i = 0; i < n; ++i) c[i] = std::cos(k * jac.x(i, 0));
    FourierSymbol1D s = fourier_symbol_1d(kernel, h, 1.0, k);
    EXPECT_LT((jac.A0 * c - s.g_abs2 * c).norm(), 1e-13);
    EXPECT_LT((-(jac.A1 * c) - s.l_hat * c).norm(), 1e-13);
  }
}

TEST(FourierSymbol1D, InfiniteLimitZeroWhenSawtoothLHatPositive) {
  Kernel<1> cubic(KernelType::CubicSpline);
  // h = dx: L^(pi) = 4 W''(dx) dx = 4 > 0.
  SymbolCriticalTension a = critical_tension_infinite_1d(cubic, 1.0, 1.0, 4);
  EXPECT_EQ(a.tcrit, 0.0);
  EXPECT_NEAR(a.l_hat_sawtooth, 4.0, 1e-14);
  // Cubic, 1.5 < h < 2.5: W'' at odd multiples of dx cancels, L^(pi) = 0 (piecewise-polynomial identity).
  SymbolCriticalTension b = critical_tension_infinite_1d(cubic, 2.0, 1.0, 4);
  EXPECT_NEAR(b.l_hat_sawtooth, 0.0, 1e-15);
}

TEST(FourierSymbol1D, FixedLayerTcritApproachesInfiniteLimit) {
  // Where T_crit,inf > 0 the fixed-layer T_crit(N) converges to it; where it is 0 T_crit(N) decays.
  for (KernelType type : {KernelType::WendlandC2, KernelType::Gaussian, KernelType::CubicSpline}) {
    Kernel<1> kernel(type);
    for (double h : {1.3, 1.9}) {
      SymbolCriticalTension inf = critical_tension_infinite_1d(kernel, h, 1.0, 4);
      double prev = std::numeric_limits<double>::infinity();
      for (int n : {30, 120, 480}) {
        auto p = make_lattice<1>(LatticeType::Line, n, {.spacing = 1.0, .support_radius = 2 * h});
        CriticalLoadOptions o = CriticalLoadOptions::tension_1d();
        o.method = CriticalLoadMethod::Eigen;
        const CriticalLoad r = critical_tension_1d(p, kernel, h, MomentumForm::Conservative, o);
        ASSERT_EQ(r.status, Status::Successful) << r.reason;
        // The infinite lattice has every mode of the finite one available in the limit: T_crit(N) >= limit
        // up to discretisation; allow 1e-9 relative for the symbol's refinement.
        EXPECT_GE(r.load, inf.tcrit * (1 - 1e-9)) << kernel_name(type) << " h " << h << " N " << n;
        EXPECT_LE(r.load, prev * (1 + 1e-9));
        prev = r.load;
      }
      if (inf.tcrit > 0) EXPECT_LT(prev / inf.tcrit - 1, 0.05) << kernel_name(type) << " h " << h;
    }
  }
}

TEST(FourierSymbol1D, RejectsBadInput) {
  Kernel<1> kernel(KernelType::CubicSpline);
  EXPECT_THROW(fourier_symbol_1d(kernel, -1.0, 1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(critical_tension_infinite_1d(kernel, 1.0, 1.0, 4, 8), std::invalid_argument);
  EXPECT_THROW(critical_tension_periodic_symbol_1d(kernel, 1.0, 1.0, 1, 4), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
