#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace sphstab {
namespace critical_tension_test {

ParticleSet<1> line(int nfree, double h, bool periodic = false) {
  return make_lattice<1>(LatticeType::Line, nfree, {.spacing = 1.0, .support_radius = 2 * h, .periodic = periodic});
}

CriticalLoadOptions tension_options() { return CriticalLoadOptions::tension_1d(); }

/// A hand-made symmetric linearisation A(T) = K - n T L on free particles at 0.5, 1.5, ...
Linearisation hand_made(const Eigen::MatrixXd& k, const Eigen::MatrixXd& l, int n) {
  Linearisation lin;
  const int m = static_cast<int>(k.rows());
  lin.free_index.resize(m);
  lin.x.resize(m, 1);
  for (int i = 0; i < m; ++i) {
    lin.free_index[i] = i;
    lin.x(i, 0) = i + 0.5;
  }
  lin.A0 = k.sparseView();
  lin.A1 = Eigen::MatrixXd(-n * l).sparseView();
  lin.symmetric = true;
  return lin;
}

TEST(CriticalTension, BisectionAgreesWithEigenRoutes) {
  // Several kernels, h and forms; both eigen backends. 1e-8 relative (the bisection runs to 1e-13).
  int finite = 0;
  for (KernelType type : {KernelType::CubicSpline, KernelType::QuinticSpline, KernelType::WendlandC2,
                          KernelType::WendlandC4, KernelType::Gaussian}) {
    Kernel<1> kernel(type);
    for (double h : {0.9, 1.3, 1.75, 2.4}) {
      const ParticleSet<1> set = line(30, h);
      for (MomentumForm form : {MomentumForm::Uncorrected, MomentumForm::Plus, MomentumForm::Conservative}) {
        for (EigenBackend backend : {EigenBackend::Dense, EigenBackend::Spectra}) {
          CriticalLoadOptions o = tension_options();
          o.backend = backend;
          CriticalLoad r = critical_tension_1d(set, kernel, h, form, o);
          ASSERT_EQ(r.status, Status::Successful) << r.reason;
          ASSERT_TRUE(std::isfinite(r.load)) << kernel_name(type) << " h " << h << ": " << r.reason;
          EXPECT_GT(r.load, 0);
          EXPECT_EQ(r.direction, LoadDirection::Tension);
          EXPECT_EQ(r.criterion, Criterion::Definiteness);
          EXPECT_LT(r.relative_difference, 1e-8) << kernel_name(type) << " h " << h;
          EXPECT_LE(r.lo, r.load_eigen * (1 + 1e-10));
          EXPECT_GE(r.hi, r.load_eigen * (1 - 1e-10));
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
  CriticalLoad r = critical_tension_1d(line(600, 1.3), kernel, 1.3, MomentumForm::Conservative, tension_options());
  EXPECT_EQ(r.eigen_backend, "spectra");
  ASSERT_EQ(r.status, Status::Successful) << r.reason;
  EXPECT_LT(r.relative_difference, 1e-8);
}

TEST(CriticalTension, FormsScaleExactlyOneTwoFour) {
  Kernel<1> kernel(KernelType::QuarticSpline);
  for (double h : {1.1, 1.6}) {
    const ParticleSet<1> set = line(30, h);
    CriticalLoad u = critical_tension_1d(set, kernel, h, MomentumForm::Uncorrected, tension_options());
    CriticalLoad p = critical_tension_1d(set, kernel, h, MomentumForm::Plus, tension_options());
    CriticalLoad c = critical_tension_1d(set, kernel, h, MomentumForm::Conservative, tension_options());
    CriticalLoad m = critical_tension_1d(set, kernel, h, MomentumForm::Minus, tension_options());
    EXPECT_NEAR(u.load_eigen / c.load_eigen, 4.0, 4e-12);
    EXPECT_NEAR(p.load_eigen / c.load_eigen, 2.0, 2e-12);
    EXPECT_NEAR(u.load_bisection / c.load_bisection, 4.0, 4e-12);
    EXPECT_NEAR(p.load_bisection / c.load_bisection, 2.0, 2e-12);
    EXPECT_TRUE(std::isinf(m.load));
    EXPECT_GT(m.load, 0);
  }
}

TEST(CriticalTension, ExplicitLinearisationMatchesConvenience) {
  // critical_load of the uncorrected linearisation (n = 1, bracket in units of T) is critical_tension_1d.
  Kernel<1> kernel(KernelType::CubicSpline);
  const ParticleSet<1> set = line(25, 1.2);
  CriticalLoadOptions o = tension_options();
  o.criterion = Criterion::Definiteness;
  CriticalLoad a = critical_load(analytic_jacobian_1d(set, kernel, 1.2), LoadDirection::Tension, o);
  CriticalLoad b = critical_tension_1d(set, kernel, 1.2, MomentumForm::Uncorrected, tension_options());
  ASSERT_EQ(a.status, Status::Successful) << a.reason;
  ASSERT_TRUE(std::isfinite(a.load));
  EXPECT_EQ(a.load, b.load);
  EXPECT_EQ(a.load_bisection, b.load_bisection);
}

TEST(CriticalTension, CompressionIsSignedAndMatchesNegatedL) {
  // Old API: compression by negating L. New: LoadDirection::Compression, result signed (negative).
  for (KernelType type : {KernelType::CubicSpline, KernelType::QuinticSpline, KernelType::WendlandC2,
                          KernelType::WendlandC4, KernelType::Gaussian}) {
    Kernel<1> kernel(type);
    for (double h : {0.9, 1.0, 1.3, 1.75, 2.2, 2.4}) {
      Linearisation lin = analytic_jacobian_1d(line(30, h), kernel, h);
      Linearisation neg = lin;
      neg.A1 = SparseMatrix<>(-lin.A1);
      CriticalLoad c = critical_load(lin, LoadDirection::Compression, tension_options());
      CriticalLoad t = critical_load(neg, LoadDirection::Tension, tension_options());
      ASSERT_EQ(c.status, Status::Successful) << c.reason;
      ASSERT_EQ(t.status, Status::Successful) << t.reason;
      EXPECT_EQ(c.direction, LoadDirection::Compression);
      // Compression on A is tension on the negated A1: the same matrices, the same value with the opposite sign.
      EXPECT_EQ(c.load, -t.load) << kernel_name(type) << " h " << h;
      EXPECT_EQ(c.load_bisection, -t.load_bisection) << kernel_name(type) << " h " << h;
      EXPECT_EQ(c.relative_difference, t.relative_difference);
      // On these fixed-layer lines compression never destabilises up to max.
      EXPECT_TRUE(std::isinf(c.load) && c.load < 0) << kernel_name(type) << " h " << h << ": " << c.reason;
    }
  }
  // A finite compression by hand: K = [[2, 1], [1, 2]], L = -I, n = 4: A(T) = K + 4 T I loses definiteness at
  // T = -1/4 (eigenvalue 1 of K) and never in tension.
  Eigen::MatrixXd k(2, 2);
  k << 2, 1, 1, 2;
  Linearisation lin = hand_made(k, -Eigen::MatrixXd::Identity(2, 2), 4);
  CriticalLoad c = critical_load(lin, LoadDirection::Compression, tension_options());
  ASSERT_EQ(c.status, Status::Successful) << c.reason;
  EXPECT_NEAR(c.load_eigen, -0.25, 1e-15);
  EXPECT_NEAR(c.load_bisection, -0.25, 0.25 * 1e-12);
  EXPECT_GE(c.lo, c.load_bisection);
  EXPECT_LE(c.hi, c.load_bisection);
  EXPECT_LT(c.hi, 0);
  CriticalLoad t = critical_load(lin, LoadDirection::Tension, tension_options());
  EXPECT_TRUE(std::isinf(t.load) && t.load > 0);
}

TEST(CriticalTension, DefinitionHoldsAroundTcrit) {
  // A(T) positive definite just below T_crit (smallest eigenvalue > 0) and indefinite just above: checked with
  // dense eigenvalues, independent of both routes.
  Kernel<1> kernel(KernelType::CubicSpline);
  const ParticleSet<1> set = line(25, 1.2);
  Linearisation lin = analytic_jacobian_1d(set, kernel, 1.2, MomentumForm::Conservative);
  CriticalLoad r = critical_tension_1d(set, kernel, 1.2, MomentumForm::Conservative, tension_options());
  ASSERT_TRUE(std::isfinite(r.load));
  auto lmin = [&](double t) { return symmetric_eigen(Eigen::MatrixXd(lin.at(t))).values[0]; };
  EXPECT_GT(lmin(r.load * (1 - 1e-6)), 0);
  EXPECT_LT(lmin(r.load * (1 + 1e-6)), 0);
  EXPECT_NEAR(lmin(r.load), 0.0, 1e-10);
}

TEST(CriticalTension, GrowthRateAboveTcritOnlyAndModeMatches) {
  Kernel<1> kernel(KernelType::QuinticSpline);
  const ParticleSet<1> set = line(30, 1.4);
  Linearisation lin = analytic_jacobian_1d(set, kernel, 1.4, MomentumForm::Conservative);
  CriticalLoadOptions o = tension_options();
  o.want_mode = true;
  CriticalLoad r = critical_tension_1d(set, kernel, 1.4, MomentumForm::Conservative, o);
  ASSERT_TRUE(std::isfinite(r.load));
  ASSERT_EQ(r.mode.size(), lin.dofs());
  EXPECT_EQ(r.mode.imag().cwiseAbs().maxCoeff(), 0.0);  // definiteness: a real eigenvector
  const Eigen::VectorXd x = lin.x.col(0);
  GrowthAnalysis below = growth_rate(Eigen::MatrixXd(lin.at(0.9 * r.load)), x);
  EXPECT_TRUE(below.unstable.empty());
  GrowthAnalysis above = growth_rate(Eigen::MatrixXd(lin.at(1.1 * r.load)), x);
  ASSERT_FALSE(above.unstable.empty());
  EXPECT_GT(above.growth_rate, 0);
  // Just above T_crit the fastest unstable mode is the critical mode.
  GrowthAnalysis just = growth_rate(Eigen::MatrixXd(lin.at(1.001 * r.load)), x);
  ASSERT_EQ(just.unstable.size(), 1u);
  EXPECT_NEAR(std::abs(just.unstable[0].shape.dot(Eigen::VectorXd(r.mode.real()))), 1.0, 1e-4);
  EXPECT_EQ(just.unstable[0].wavenumber.k_projection, r.mode_wavenumber.k_projection);
}

TEST(CriticalTension, PeriodicOddMatchesFourierSymbol) {
  // Odd N: only the translation is singular; the deflated matrix T_crit equals the symbol minimum over k_m.
  for (KernelType type : {KernelType::CubicSpline, KernelType::WendlandC2, KernelType::Gaussian}) {
    Kernel<1> kernel(type);
    for (double h : {1.0, 1.6, 2.3}) {
      const int n = 41;
      CriticalLoad r = critical_tension_1d(line(n, h, true), kernel, h, MomentumForm::Conservative, tension_options());
      SymbolCriticalTension s = critical_tension_periodic_symbol_1d(kernel, h, 1.0, n, 4);
      ASSERT_EQ(r.status, Status::Successful) << r.reason;
      EXPECT_NE(r.reason.find("translation mode projected out"), std::string::npos);
      if (std::isinf(s.tcrit)) {
        EXPECT_TRUE(std::isinf(r.load));
      } else {
        EXPECT_NEAR(r.load / s.tcrit, 1.0, 1e-9) << kernel_name(type) << " h " << h;
        EXPECT_LT(r.relative_difference, 1e-8);
      }
    }
  }
}

TEST(CriticalTension, PeriodicEvenSawtoothReported) {
  // Cubic, h = dx: L^(pi) = 4 W''(dx) dx > 0, so the sawtooth (G s = 0) makes A(T) indefinite for every T > 0.
  Kernel<1> kernel(KernelType::CubicSpline);
  const ParticleSet<1> set = line(40, 1.0, true);
  CriticalLoad r = critical_tension_1d(set, kernel, 1.0, MomentumForm::Conservative, tension_options());
  EXPECT_EQ(r.load, 0.0);
  EXPECT_EQ(r.status, Status::Successful);
  EXPECT_NE(r.reason.find("sawtooth"), std::string::npos);
  // Cubic, 1.5 < h/dx < 2.5: L^(pi) = 0 exactly (W'' at odd multiples cancels): A singular for every T.
  CriticalLoad r2 =
      critical_tension_1d(line(40, 2.0, true), kernel, 2.0, MomentumForm::Conservative, tension_options());
  EXPECT_EQ(r2.load, 0.0);
  EXPECT_NE(r2.reason.find("singular for every load"), std::string::npos);
  // Without deflation K is singular: reported, not a number.
  CriticalLoadOptions o = tension_options();
  o.deflate_periodic = false;
  CriticalLoad r3 = critical_tension_1d(set, kernel, 1.0, MomentumForm::Conservative, o);
  EXPECT_EQ(r3.status, Status::NumericalIssue);
  EXPECT_TRUE(std::isnan(r3.load));
  EXPECT_NE(r3.reason.find("not positive definite"), std::string::npos);
}

TEST(CriticalTension, SingularKIsReportedNotComputed) {
  Eigen::MatrixXd k = Eigen::Vector3d(1, 0, 1).asDiagonal();
  Linearisation lin = hand_made(k, Eigen::MatrixXd::Identity(3, 3), 1);
  for (CriticalLoadMethod m : {CriticalLoadMethod::Eigen, CriticalLoadMethod::Bisection, CriticalLoadMethod::Both}) {
    CriticalLoadOptions o = tension_options();
    o.method = m;
    CriticalLoad r = critical_load(lin, LoadDirection::Tension, o);
    EXPECT_EQ(r.status, Status::NumericalIssue);
    EXPECT_TRUE(std::isnan(r.load));
    EXPECT_NE(r.reason.find("A0 is not positive definite"), std::string::npos) << r.reason;
  }
}

TEST(CriticalTension, NegativeDefiniteLNeverUnstable) {
  // n = 2; the old bound tau_max = n T = 1e6 is max = 5e5 in units of T.
  Linearisation lin = hand_made(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd(-Eigen::MatrixXd::Identity(2, 2)), 2);
  CriticalLoadOptions o = tension_options();
  o.max = 5e5;
  CriticalLoad r = critical_load(lin, LoadDirection::Tension, o);
  EXPECT_TRUE(std::isinf(r.load_eigen));
  EXPECT_GT(r.load_eigen, 0);
  EXPECT_TRUE(std::isinf(r.load_bisection));
  EXPECT_GT(r.load_bisection, 0);
  EXPECT_EQ(r.relative_difference, 0.0);
  EXPECT_EQ(r.status, Status::Successful);
}

TEST(CriticalTension, TwoByTwoByHand) {
  // K = [[2, 1], [1, 2]], L = I: A = K - tau I loses definiteness at tau = 1 (eigenvalue 1 of K); n = 4.
  Eigen::MatrixXd k(2, 2);
  k << 2, 1, 1, 2;
  Linearisation lin = hand_made(k, Eigen::MatrixXd::Identity(2, 2), 4);
  CriticalLoad r = critical_load(lin, LoadDirection::Tension, tension_options());
  EXPECT_NEAR(r.load_eigen, 0.25, 1e-15);
  EXPECT_NEAR(r.load_bisection, 0.25, 0.25 * 1e-12);
}

TEST(CriticalTension, RejectsBadInput) {
  Kernel<1> kernel(KernelType::CubicSpline);
  const ParticleSet<1> set = line(10, 1.2);
  Linearisation lin = analytic_jacobian_1d(set, kernel, 1.2, MomentumForm::Conservative);
  // Old: n < 0 and mismatched K, L. New: the load multiplier is part of the form; mismatched A0, A1 still throw.
  Linearisation mismatched = lin;
  mismatched.A1 = SparseMatrix<>(lin.dofs() - 1, lin.dofs() - 1);
  EXPECT_THROW(critical_load(mismatched, LoadDirection::Tension, tension_options()), std::invalid_argument);
  CriticalLoadOptions start0 = tension_options();
  start0.start = 0;
  EXPECT_THROW(critical_load(lin, LoadDirection::Tension, start0), std::invalid_argument);
  EXPECT_THROW(critical_tension_1d(set, kernel, 1.2, MomentumForm::Conservative, start0), std::invalid_argument);
  CriticalLoadOptions rtol = tension_options();
  rtol.rtol = -1;
  EXPECT_THROW(critical_load(lin, LoadDirection::Tension, rtol), std::invalid_argument);
  Linearisation empty;
  EXPECT_THROW(critical_load(empty, LoadDirection::Tension, tension_options()), std::invalid_argument);
  EXPECT_THROW(parse_critical_load_method("fast"), std::invalid_argument);
  EXPECT_THROW(parse_eigen_backend("arpack"), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
