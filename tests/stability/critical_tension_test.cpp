#include "sphstab/stability/critical_tension.hpp"

#include <gtest/gtest.h>

#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/fourier_symbol.hpp"
#include "sphstab/stability/growth_rate.hpp"

namespace sphstab {
namespace {

ParticleSet<1> line(int nfree, double h, bool periodic = false) {
  return make_lattice<1>(LatticeType::Line, nfree, {.spacing = 1.0, .support_radius = 2 * h, .periodic = periodic});
}

TEST(CriticalTension, BisectionAgreesWithEigenRoutes) {
  // Several kernels, h and forms; both eigen backends. 1e-8 relative (the bisection runs to 1e-13).
  int finite = 0;
  for (KernelType type : {KernelType::CubicSpline, KernelType::QuinticSpline, KernelType::WendlandC2,
                          KernelType::WendlandC4, KernelType::Gaussian}) {
    Kernel<1> kernel(type);
    for (double h : {0.9, 1.3, 1.75, 2.4}) {
      TensionJacobian1d jac = analytic_jacobian_1d(line(30, h), kernel, h);
      for (MomentumForm form : {MomentumForm::Uncorrected, MomentumForm::Plus, MomentumForm::Conservative}) {
        for (EigenBackend backend : {EigenBackend::Dense, EigenBackend::Spectra}) {
          CriticalTension r = critical_tension(jac, initial_stress_multiplier(form), {.backend = backend});
          ASSERT_EQ(r.status, Status::Successful) << r.reason;
          ASSERT_TRUE(std::isfinite(r.tcrit)) << kernel_name(type) << " h " << h << ": " << r.reason;
          EXPECT_LT(r.relative_difference, 1e-8) << kernel_name(type) << " h " << h;
          EXPECT_LE(r.bisection_lo, r.tcrit_eigen * (1 + 1e-10));
          EXPECT_GE(r.bisection_hi, r.tcrit_eigen * (1 - 1e-10));
          EXPECT_EQ(r.eigen_backend, backend == EigenBackend::Dense ? "dense" : "spectra");
          ++finite;
        }
      }
    }
  }
  EXPECT_EQ(finite, 5 * 4 * 3 * 2);
}

TEST(CriticalTension, LargerSystemSpectraAgreesWithBisection) {
  Kernel<1> kernel(KernelType::WendlandC2);
  TensionJacobian1d jac = analytic_jacobian_1d(line(600, 1.3), kernel, 1.3);
  CriticalTension r = critical_tension(jac, 4);
  EXPECT_EQ(r.eigen_backend, "spectra");
  ASSERT_EQ(r.status, Status::Successful) << r.reason;
  EXPECT_LT(r.relative_difference, 1e-8);
}

TEST(CriticalTension, FormsScaleExactlyOneTwoFour) {
  Kernel<1> kernel(KernelType::QuarticSpline);
  for (double h : {1.1, 1.6}) {
    TensionJacobian1d jac = analytic_jacobian_1d(line(30, h), kernel, h);
    CriticalTension u = critical_tension(jac, initial_stress_multiplier(MomentumForm::Uncorrected));
    CriticalTension p = critical_tension(jac, initial_stress_multiplier(MomentumForm::Plus));
    CriticalTension c = critical_tension(jac, initial_stress_multiplier(MomentumForm::Conservative));
    CriticalTension m = critical_tension(jac, initial_stress_multiplier(MomentumForm::Minus));
    EXPECT_NEAR(u.tcrit_eigen / c.tcrit_eigen, 4.0, 4e-12);
    EXPECT_NEAR(p.tcrit_eigen / c.tcrit_eigen, 2.0, 2e-12);
    EXPECT_NEAR(u.tcrit_bisection / c.tcrit_bisection, 4.0, 4e-12);
    EXPECT_NEAR(p.tcrit_bisection / c.tcrit_bisection, 2.0, 2e-12);
    EXPECT_TRUE(std::isinf(m.tcrit));
  }
}

TEST(CriticalTension, DefinitionHoldsAroundTcrit) {
  // A(T) positive definite just below T_crit (smallest eigenvalue > 0) and indefinite just above: checked with
  // dense eigenvalues, independent of both routes.
  Kernel<1> kernel(KernelType::CubicSpline);
  TensionJacobian1d jac = analytic_jacobian_1d(line(25, 1.2), kernel, 1.2);
  CriticalTension r = critical_tension(jac, 4);
  ASSERT_TRUE(std::isfinite(r.tcrit));
  auto lmin = [&](double t) {
    return symmetric_eigen(Eigen::MatrixXd(jac.matrix(MomentumForm::Conservative, t))).values[0];
  };
  EXPECT_GT(lmin(r.tcrit * (1 - 1e-6)), 0);
  EXPECT_LT(lmin(r.tcrit * (1 + 1e-6)), 0);
  EXPECT_NEAR(lmin(r.tcrit), 0.0, 1e-10);
}

TEST(CriticalTension, GrowthRateAboveTcritOnlyAndModeMatches) {
  Kernel<1> kernel(KernelType::QuinticSpline);
  TensionJacobian1d jac = analytic_jacobian_1d(line(30, 1.4), kernel, 1.4);
  CriticalTension r = critical_tension(jac, 4, {.want_mode = true});
  ASSERT_TRUE(std::isfinite(r.tcrit));
  GrowthAnalysis below = growth_rate(Eigen::MatrixXd(jac.matrix(MomentumForm::Conservative, 0.9 * r.tcrit)), jac.x);
  EXPECT_TRUE(below.unstable.empty());
  GrowthAnalysis above = growth_rate(Eigen::MatrixXd(jac.matrix(MomentumForm::Conservative, 1.1 * r.tcrit)), jac.x);
  ASSERT_FALSE(above.unstable.empty());
  EXPECT_GT(above.growth_rate, 0);
  // Just above T_crit the fastest unstable mode is the critical mode.
  GrowthAnalysis just = growth_rate(Eigen::MatrixXd(jac.matrix(MomentumForm::Conservative, 1.001 * r.tcrit)), jac.x);
  ASSERT_EQ(just.unstable.size(), 1u);
  EXPECT_NEAR(std::abs(just.unstable[0].shape.dot(r.mode)), 1.0, 1e-4);
  EXPECT_EQ(just.unstable[0].wavenumber.k_projection, r.mode_wavenumber.k_projection);
}

TEST(CriticalTension, PeriodicOddMatchesFourierSymbol) {
  // Odd N: only the translation is singular; the deflated matrix T_crit equals the symbol minimum over k_m.
  for (KernelType type : {KernelType::CubicSpline, KernelType::WendlandC2, KernelType::Gaussian}) {
    Kernel<1> kernel(type);
    for (double h : {1.0, 1.6, 2.3}) {
      const int n = 41;
      TensionJacobian1d jac = analytic_jacobian_1d(line(n, h, true), kernel, h);
      CriticalTension r = critical_tension(jac, 4);
      SymbolCriticalTension s = critical_tension_periodic_symbol_1d(kernel, h, 1.0, n, 4);
      ASSERT_EQ(r.status, Status::Successful) << r.reason;
      EXPECT_NE(r.reason.find("translation mode projected out"), std::string::npos);
      if (std::isinf(s.tcrit)) {
        EXPECT_TRUE(std::isinf(r.tcrit));
      } else {
        EXPECT_NEAR(r.tcrit / s.tcrit, 1.0, 1e-9) << kernel_name(type) << " h " << h;
        EXPECT_LT(r.relative_difference, 1e-8);
      }
    }
  }
}

TEST(CriticalTension, PeriodicEvenSawtoothReported) {
  // Cubic, h = dx: L^(pi) = 4 W''(dx) dx > 0, so the sawtooth (G s = 0) makes A(T) indefinite for every T > 0.
  Kernel<1> kernel(KernelType::CubicSpline);
  TensionJacobian1d jac = analytic_jacobian_1d(line(40, 1.0, true), kernel, 1.0);
  CriticalTension r = critical_tension(jac, 4);
  EXPECT_EQ(r.tcrit, 0.0);
  EXPECT_EQ(r.status, Status::Successful);
  EXPECT_NE(r.reason.find("sawtooth"), std::string::npos);
  // Cubic, 1.5 < h/dx < 2.5: L^(pi) = 0 exactly (W'' at odd multiples cancels): A singular for every T.
  TensionJacobian1d jac2 = analytic_jacobian_1d(line(40, 2.0, true), kernel, 2.0);
  CriticalTension r2 = critical_tension(jac2, 4);
  EXPECT_EQ(r2.tcrit, 0.0);
  EXPECT_NE(r2.reason.find("singular for every T"), std::string::npos);
  // Without deflation K is singular: reported, not a number.
  CriticalTension r3 = critical_tension(jac, 4, {.deflate_periodic = false});
  EXPECT_EQ(r3.status, Status::NumericalIssue);
  EXPECT_TRUE(std::isnan(r3.tcrit));
  EXPECT_NE(r3.reason.find("not positive definite"), std::string::npos);
}

TEST(CriticalTension, SingularKIsReportedNotComputed) {
  TensionJacobian1d jac;
  jac.free_index = {0, 1, 2};
  jac.x = Eigen::Vector3d(0.5, 1.5, 2.5);
  Eigen::MatrixXd k = Eigen::Vector3d(1, 0, 1).asDiagonal();
  jac.K = k.sparseView();
  jac.L = Eigen::MatrixXd::Identity(3, 3).sparseView();
  for (TcritMethod m : {TcritMethod::Eigen, TcritMethod::Bisection, TcritMethod::Both}) {
    CriticalTension r = critical_tension(jac, 1, {.method = m});
    EXPECT_EQ(r.status, Status::NumericalIssue);
    EXPECT_TRUE(std::isnan(r.tcrit));
    EXPECT_NE(r.reason.find("K = G_f G_f^T is not positive definite"), std::string::npos);
  }
}

TEST(CriticalTension, NegativeDefiniteLNeverUnstable) {
  TensionJacobian1d jac;
  jac.free_index = {0, 1};
  jac.x = Eigen::Vector2d(0.5, 1.5);
  jac.K = Eigen::MatrixXd::Identity(2, 2).sparseView();
  jac.L = Eigen::MatrixXd(-Eigen::MatrixXd::Identity(2, 2)).sparseView();
  CriticalTension r = critical_tension(jac, 2, {.tau_max = 1e6});
  EXPECT_TRUE(std::isinf(r.tcrit_eigen));
  EXPECT_TRUE(std::isinf(r.tcrit_bisection));
  EXPECT_EQ(r.relative_difference, 0.0);
  EXPECT_EQ(r.status, Status::Successful);
}

TEST(CriticalTension, TwoByTwoByHand) {
  // K = [[2, 1], [1, 2]], L = I: A = K - tau I loses definiteness at tau = 1 (eigenvalue 1 of K).
  TensionJacobian1d jac;
  jac.free_index = {0, 1};
  jac.x = Eigen::Vector2d(0.5, 1.5);
  Eigen::MatrixXd k(2, 2);
  k << 2, 1, 1, 2;
  jac.K = k.sparseView();
  jac.L = Eigen::MatrixXd::Identity(2, 2).sparseView();
  CriticalTension r = critical_tension(jac, 4);
  EXPECT_NEAR(r.tcrit_eigen, 0.25, 1e-15);
  EXPECT_NEAR(r.tcrit_bisection, 0.25, 0.25 * 1e-12);
}

TEST(CriticalTension, RejectsBadInput) {
  Kernel<1> kernel(KernelType::CubicSpline);
  TensionJacobian1d jac = analytic_jacobian_1d(line(10, 1.2), kernel, 1.2);
  EXPECT_THROW(critical_tension(jac, -1), std::invalid_argument);
  EXPECT_THROW(critical_tension(jac, 4, {.tau_start = 0}), std::invalid_argument);
  EXPECT_THROW(critical_tension(jac, 4, {.rtol = -1}), std::invalid_argument);
  TensionJacobian1d empty;
  EXPECT_THROW(critical_tension(empty, 4), std::invalid_argument);
  EXPECT_THROW(parse_tcrit_method("fast"), std::invalid_argument);
  EXPECT_THROW(parse_eigen_backend("arpack"), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
