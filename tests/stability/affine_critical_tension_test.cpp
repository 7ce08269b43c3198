// Critical load of A(T) = A0 + T A1 for any force function: the nonsymmetric spectrum criterion on a constructed
// case with known answers, and the pd route against the analytic 1D machinery (Powell 3.40) for the plain forms.
#include "sphstab/stability/affine_critical_tension.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>  // EigenSolver: an eigen route independent of LAPACK
#include <cmath>

#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace {

AffineJacobian pair(const Eigen::MatrixXd& a0, const Eigen::MatrixXd& a1) { return {a0.sparseView(), a1.sparseView()}; }

TEST(AffineCriticalTension, ConstructedNonsymmetricTwoByTwo) {
  // A(T) = [[2, 1], [-T, 1]]: trace 3, det 2 + T, discriminant 1 - 4T.
  //  spectrum: a complex pair for T > 1/4 (flutter), an eigenvalue through 0 at T = -2 (divergence);
  //  symmetric part [[2, (1-T)/2], [(1-T)/2, 1]] positive definite iff |1 - T| < 2 sqrt 2.
  Eigen::MatrixXd a0(2, 2), a1(2, 2);
  a0 << 2, 1, 0, 1;
  a1 << 0, 0, -1, 0;
  const AffineJacobian j = pair(a0, a1);
  const Eigen::VectorXd x = Eigen::Vector2d(0.5, 1.5);
  const auto tension = affine_critical_tension(j, LoadDirection::Tension, x);
  ASSERT_EQ(tension.size(), 2u);  // nonsymmetric: spectrum + symmetric part
  EXPECT_EQ(tension[0].criterion, StabilityCriterion::RealPositiveSpectrum);
  EXPECT_EQ(tension[0].status, Status::Successful);
  EXPECT_NEAR(tension[0].tcrit, 0.25, 1e-9);  // bisection to rtol 1e-10
  EXPECT_NE(tension[0].reason.find("flutter"), std::string::npos) << tension[0].reason;
  // gamma at 2 T_crit = 1/2: mu = (3 +- i)/2, Re sqrt(-mu) = sqrt((|mu| - 3/2)/2)
  EXPECT_NEAR(tension[0].growth_load, 0.5, 1e-9);
  EXPECT_NEAR(tension[0].growth_rate, std::sqrt((std::sqrt(2.5) - 1.5) / 2), 1e-8);
  EXPECT_EQ(tension[1].criterion, StabilityCriterion::SymmetricPartPositiveDefinite);
  EXPECT_NEAR(tension[1].tcrit, 1 + 2 * std::sqrt(2.0), 1e-8);
  const auto compression = affine_critical_tension(j, LoadDirection::Compression, x);
  EXPECT_NEAR(compression[0].tcrit, -2.0, 1e-9);
  EXPECT_NE(compression[0].reason.find("divergence"), std::string::npos) << compression[0].reason;
  EXPECT_NEAR(compression[1].tcrit, 1 - 2 * std::sqrt(2.0), 1e-8);
  // The pd criterion needs a symmetric pair.
  EXPECT_THROW(affine_critical_load(j, StabilityCriterion::PositiveDefinite, LoadDirection::Tension, x),
               std::invalid_argument);
}

TEST(AffineCriticalTension, FailsAtZeroAndLoadIndependent) {
  Eigen::MatrixXd a0(2, 2), a1 = Eigen::MatrixXd::Zero(2, 2);
  a0 << 1, 2, -2, 1;  // eigenvalues 1 +- 2i: the spectrum criterion fails at T = 0
  const Eigen::VectorXd x = Eigen::Vector2d(0, 1);
  auto r = affine_critical_load(pair(a0, a1), StabilityCriterion::RealPositiveSpectrum, LoadDirection::Tension, x);
  EXPECT_EQ(r.tcrit, 0.0);
  auto s =
      affine_critical_load(pair(a0, a1), StabilityCriterion::SymmetricPartPositiveDefinite, LoadDirection::Tension, x);
  EXPECT_TRUE(std::isinf(s.tcrit) && s.tcrit > 0) << s.reason;  // symmetric part I, no T dependence
  EXPECT_TRUE(s.info.load_independent);
  a0 << 3, 1, 1, 2;
  auto c = affine_critical_tension(pair(a0, a1), LoadDirection::Compression, x);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].criterion, StabilityCriterion::PositiveDefinite);
  EXPECT_TRUE(std::isinf(c[0].tcrit) && c[0].tcrit < 0);
  EXPECT_THROW(affine_critical_tension(pair(a0, Eigen::MatrixXd::Zero(3, 3)), LoadDirection::Tension, x),
               std::invalid_argument);
  EXPECT_THROW(affine_critical_tension(pair(a0, a1), LoadDirection::Tension, Eigen::VectorXd::Zero(3)),
               std::invalid_argument);
}

TEST(AffineCriticalTension, PlainFormsAgreeWithAnalyticRoute) {
  // Complex-step A0, A1 of the force functions + the pd route vs analytic_jacobian_1d + critical_tension (both with
  // eigen and bisection cross-checked inside): 1e-8 relative, in tension and in compression (L -> -L).
  int finite = 0;
  for (KernelType type : {KernelType::CubicSpline, KernelType::QuinticSpline, KernelType::WendlandC2}) {
    Kernel<1> kernel(type);
    for (double h : {1.0, 1.3, 1.7, 2.2}) {
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, 30);
      auto d = make_discretisation(set, kernel, h);
      const TensionJacobian1d analytic = analytic_jacobian_1d(set, kernel, h);
      TensionJacobian1d compressed = analytic;
      compressed.L = SparseMatrix<>(-analytic.L);
      for (MomentumForm form : {MomentumForm::Uncorrected, MomentumForm::Plus, MomentumForm::Conservative}) {
        WaveForm1D force(d, form, 0.0);
        const AffineJacobian j = affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
        for (LoadDirection dir : {LoadDirection::Tension, LoadDirection::Compression}) {
          const auto r = affine_critical_tension(j, dir, analytic.x);
          ASSERT_EQ(r.size(), 1u);
          ASSERT_EQ(r[0].criterion, StabilityCriterion::PositiveDefinite);
          const CriticalTension ref =
              critical_tension(dir == LoadDirection::Tension ? analytic : compressed, initial_stress_multiplier(form));
          const double sign = dir == LoadDirection::Tension ? 1.0 : -1.0;
          if (std::isinf(ref.tcrit)) {
            EXPECT_TRUE(std::isinf(r[0].tcrit)) << kernel_name(type) << " h=" << h << " " << r[0].reason;
            continue;
          }
          EXPECT_NEAR(r[0].tcrit / (sign * ref.tcrit), 1.0, 1e-8)
              << kernel_name(type) << " h=" << h << " " << momentum_form_name(form) << " " << load_direction_name(dir)
              << " " << r[0].reason;
          EXPECT_GT(r[0].growth_rate, 0.0);
          ++finite;
        }
      }
    }
  }
  EXPECT_GE(finite, 36);  // every tension case is finite; compression only for some kernels and h
}

TEST(AffineCriticalTension, NonsymmetricCorrectedFormOnThinLayers) {
  // Column Shepard divergence with fixed layers only one support thick: A(T) is not symmetric (the fixed particles'
  // incomplete neighbourhoods enter the column sums), so the two nonsymmetric criteria apply. Both must give a
  // finite T_crit with a positive growth rate beyond it; the spectrum just below T_crit is real and positive.
  Kernel<1> kernel(KernelType::CubicSpline);
  auto d = make_discretisation(tension_lattice_1d(kernel, 1.3, 20), kernel, 1.3);
  WaveForm1D force(d, MomentumForm::Plus, 0.0, make_gradient_provider<1>(Correction::ColumnShepard));
  const AffineJacobian j = affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
  Eigen::VectorXd x(d->free_count());
  for (int f = 0; f < d->free_count(); ++f) x[f] = d->particles.x(d->free[f], 0);
  const auto r = affine_critical_tension(j, LoadDirection::Tension, x);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_GT(r[0].info.asymmetry0, 1e-6);
  for (const auto& c : r) {
    EXPECT_EQ(c.status, Status::Successful) << c.reason;
    EXPECT_TRUE(std::isfinite(c.tcrit) && c.tcrit > 0) << criterion_name(c.criterion) << " " << c.reason;
    EXPECT_GT(c.growth_rate, 0.0);
  }
  const Eigen::MatrixXd below = Eigen::MatrixXd(j.at(r[0].tcrit * (1 - 1e-6)));
  const Eigen::VectorXcd mu = below.eigenvalues();
  for (Eigen::Index k = 0; k < mu.size(); ++k) {
    EXPECT_GT(mu[k].real(), 0.0);
    EXPECT_LE(std::abs(mu[k].imag()), 1e-10 * mu.cwiseAbs().maxCoeff());
  }
}

}  // namespace
}  // namespace sphstab
