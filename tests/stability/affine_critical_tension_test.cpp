// Critical load of A(T) = A0 + T A1 for any force function (critical_loads / critical_load with the force_function()
// defaults): the nonsymmetric spectrum criterion on a constructed case with known answers, and the definiteness route
// of the complex-step linearisation against the analytic 1D machinery (Powell 3.40) for the plain forms.
#include <gtest/gtest.h>

#include <Eigen/Dense>  // EigenSolver: an eigen route independent of LAPACK
#include <cmath>

#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace sphstab {
namespace affine_critical_tension_test {

/// A hand-made linearisation on 1 dof per particle; `symmetric` measured as affine_jacobian does (tolerance 1e-12).
Linearisation pair(const Eigen::MatrixXd& a0, const Eigen::MatrixXd& a1, const Eigen::VectorXd& x) {
  Linearisation lin;
  lin.A0 = a0.sparseView();
  lin.A1 = a1.sparseView();
  lin.x = x;
  if (a0.rows() == a1.rows() && a0.cols() == a1.cols())
    lin.symmetric = relative_asymmetry(lin.A0) <= 1e-12 && relative_asymmetry(lin.at(1.0)) <= 1e-12;
  return lin;
}

/// The old affine_critical_load(split, criterion, dir, x): the force_function() defaults with the criterion set.
CriticalLoad load_by(const Linearisation& lin, Criterion criterion, LoadDirection dir) {
  CriticalLoadOptions o = CriticalLoadOptions::force_function();
  o.criterion = criterion;
  return critical_load(lin, dir, o);
}

TEST(AffineCriticalTension, ConstructedNonsymmetricTwoByTwo) {
  // A(T) = [[2, 1], [-T, 1]]: trace 3, det 2 + T, discriminant 1 - 4T.
  //  spectrum: a complex pair for T > 1/4 (flutter), an eigenvalue through 0 at T = -2 (divergence);
  //  symmetric part [[2, (1-T)/2], [(1-T)/2, 1]] positive definite iff |1 - T| < 2 sqrt 2.
  Eigen::MatrixXd a0(2, 2), a1(2, 2);
  a0 << 2, 1, 0, 1;
  a1 << 0, 0, -1, 0;
  const Linearisation j = pair(a0, a1, Eigen::Vector2d(0.5, 1.5));
  ASSERT_FALSE(j.symmetric);
  const auto tension = critical_loads(j, LoadDirection::Tension);
  ASSERT_EQ(tension.size(), 2u);  // nonsymmetric: spectrum + symmetric part
  EXPECT_EQ(tension[0].criterion, Criterion::Spectrum);
  EXPECT_EQ(tension[0].status, Status::Successful);
  EXPECT_NEAR(tension[0].load, 0.25, 1e-9);  // bisection to rtol 1e-10
  EXPECT_NE(tension[0].reason.find("flutter"), std::string::npos) << tension[0].reason;
  EXPECT_EQ(tension[0].mechanism, InstabilityMechanism::ComplexPair);
  // gamma at 2 T_crit = 1/2: mu = (3 +- i)/2, Re sqrt(-mu) = sqrt((|mu| - 3/2)/2)
  EXPECT_NEAR(tension[0].growth_load, 0.5, 1e-9);
  EXPECT_NEAR(tension[0].growth_rate, std::sqrt((std::sqrt(2.5) - 1.5) / 2), 1e-8);
  EXPECT_EQ(tension[1].criterion, Criterion::SymmetricPart);
  EXPECT_NEAR(tension[1].load, 1 + 2 * std::sqrt(2.0), 1e-8);
  const auto compression = critical_loads(j, LoadDirection::Compression);
  ASSERT_EQ(compression.size(), 2u);
  EXPECT_NEAR(compression[0].load, -2.0, 1e-9);
  EXPECT_NE(compression[0].reason.find("divergence"), std::string::npos) << compression[0].reason;
  EXPECT_NEAR(compression[1].load, 1 - 2 * std::sqrt(2.0), 1e-8);
  // The definiteness criterion needs a symmetric pair.
  EXPECT_THROW(load_by(j, Criterion::Definiteness, LoadDirection::Tension), std::invalid_argument);
}

TEST(AffineCriticalTension, FailsAtZeroAndLoadIndependent) {
  Eigen::MatrixXd a0(2, 2), a1 = Eigen::MatrixXd::Zero(2, 2);
  a0 << 1, 2, -2, 1;  // eigenvalues 1 +- 2i: the spectrum criterion fails at T = 0
  const Eigen::VectorXd x = Eigen::Vector2d(0, 1);
  auto r = load_by(pair(a0, a1, x), Criterion::Spectrum, LoadDirection::Tension);
  EXPECT_EQ(r.load, 0.0);
  auto s = load_by(pair(a0, a1, x), Criterion::SymmetricPart, LoadDirection::Tension);
  EXPECT_TRUE(std::isinf(s.load) && s.load > 0) << s.reason;  // symmetric part I, no T dependence
  // Old info.load_independent: A1 negligible, decided from A(0) alone (no bisection, load_eigen = load_bisection).
  EXPECT_LE(s.a1_relative, 1e-12);
  EXPECT_EQ(s.evaluations, 0);
  EXPECT_EQ(s.load_eigen, s.load);
  EXPECT_EQ(s.load_bisection, s.load);
  EXPECT_NE(s.reason.find("A1 = 0"), std::string::npos) << s.reason;
  a0 << 3, 1, 1, 2;
  auto c = critical_loads(pair(a0, a1, x), LoadDirection::Compression);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].criterion, Criterion::Definiteness);
  EXPECT_TRUE(std::isinf(c[0].load) && c[0].load < 0);
  EXPECT_THROW(critical_loads(pair(a0, Eigen::MatrixXd::Zero(3, 3), x), LoadDirection::Tension), std::invalid_argument);
  EXPECT_THROW(critical_loads(pair(a0, a1, Eigen::VectorXd::Zero(3)), LoadDirection::Tension), std::invalid_argument);
}

TEST(AffineCriticalTension, PlainFormsAgreeWithAnalyticRoute) {
  // Complex-step A0, A1 of the force functions + the definiteness route vs analytic_jacobian_1d + critical_tension_1d
  // (both with eigen and bisection cross-checked inside): 1e-8 relative, in tension and in compression.
  int finite = 0;
  for (KernelType type : {KernelType::CubicSpline, KernelType::QuinticSpline, KernelType::WendlandC2}) {
    Kernel<1> kernel(type);
    for (double h : {1.0, 1.3, 1.7, 2.2}) {
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, 30);
      auto d = make_discretisation(set, kernel, h);
      for (MomentumForm form : {MomentumForm::Uncorrected, MomentumForm::Plus, MomentumForm::Conservative}) {
        WaveForm1D force(d, form, 0.0);
        Linearisation j = affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
        j.x = d->free_positions();
        for (LoadDirection dir : {LoadDirection::Tension, LoadDirection::Compression}) {
          const auto r = critical_loads(j, dir);
          ASSERT_EQ(r.size(), 1u);
          ASSERT_EQ(r[0].criterion, Criterion::Definiteness);
          const CriticalLoad ref = critical_tension_1d(set, kernel, h, form, CriticalLoadOptions::tension_1d(), dir);
          ASSERT_EQ(ref.status, Status::Successful) << ref.reason;
          if (std::isinf(ref.load)) {
            EXPECT_TRUE(std::isinf(r[0].load)) << kernel_name(type) << " h=" << h << " " << r[0].reason;
            EXPECT_EQ(r[0].load, ref.load);  // same sign
            continue;
          }
          EXPECT_EQ(ref.load > 0, dir == LoadDirection::Tension);
          EXPECT_NEAR(r[0].load / ref.load, 1.0, 1e-8)
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

TEST(AffineCriticalTension, ForceCriticalLoadsMatchesTheLinearisation) {
  // The old critical_load(force, dir, x): split, residual and results in one call.
  Kernel<1> kernel(KernelType::WendlandC2);
  auto d = make_discretisation(tension_lattice_1d(kernel, 1.3, 20, false, 3), kernel, 1.3);
  WaveForm1D force(d, MomentumForm::Conservative, 0.0);
  const ForceCriticalLoad f = force_critical_loads(force, LoadDirection::Tension, d->free_positions());
  Linearisation j = affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
  j.x = d->free_positions();
  const auto r = critical_loads(j, LoadDirection::Tension);
  ASSERT_EQ(f.results.size(), r.size());
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(f.jacobian.symmetric);
  EXPECT_LE(f.residual_relative, 1e-12);  // u = 0 is an equilibrium of the plain form on a complete lattice
  ASSERT_TRUE(std::isfinite(r[0].load));
  EXPECT_EQ(f.results[0].load, r[0].load);
  // The wavenumber of the instability: the fastest-growing mode at 2 T_crit.
  ASSERT_GT(f.results[0].unstable_modes, 0);
  EXPECT_EQ(f.results[0].reported_wavenumber().k_projection, f.results[0].growth_wavenumber.k_projection);
  EXPECT_TRUE(std::isfinite(f.results[0].reported_wavenumber().k_projection));
}

TEST(AffineCriticalTension, NonsymmetricCorrectedFormOnThinLayers) {
  // Column Shepard divergence with fixed layers only one support thick: A(T) is not symmetric (the fixed particles'
  // incomplete neighbourhoods enter the column sums), so the two nonsymmetric criteria apply. Both must give a
  // finite T_crit with a positive growth rate beyond it; the spectrum just below T_crit is real and positive.
  Kernel<1> kernel(KernelType::CubicSpline);
  auto d = make_discretisation(tension_lattice_1d(kernel, 1.3, 20), kernel, 1.3);
  WaveForm1D force(d, MomentumForm::Plus, 0.0, make_gradient_provider<1>(Correction::ColumnShepard));
  Linearisation j = affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
  j.x = d->free_positions();
  const auto r = critical_loads(j, LoadDirection::Tension);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_GT(r[0].asymmetry0, 1e-6);
  for (const auto& c : r) {
    EXPECT_EQ(c.status, Status::Successful) << c.reason;
    EXPECT_TRUE(std::isfinite(c.load) && c.load > 0) << criterion_name(c.criterion) << " " << c.reason;
    EXPECT_GT(c.growth_rate, 0.0);
  }
  const Eigen::MatrixXd below = Eigen::MatrixXd(j.at(r[0].load * (1 - 1e-6)));
  const Eigen::VectorXcd mu = below.eigenvalues();
  for (Eigen::Index k = 0; k < mu.size(); ++k) {
    EXPECT_GT(mu[k].real(), 0.0);
    EXPECT_LE(std::abs(mu[k].imag()), 1e-10 * mu.cwiseAbs().maxCoeff());
  }
}

}  // namespace
}  // namespace sphstab
