// The variational finite-strain TL form (forms/variational_total_lagrangian.hpp): with the plain gradient it is the
// plus form of FiniteStrainTotalLagrangian (two implementations agree), with NCSPH the force is -M^{-1} dU/du
// (complex step of the energy), a rigid rotation of the CSM3 beam gives zero force (objective) where the plain
// gradient does not, the linearisation at rest of the CSM3 beam has no growing mode, and bad input.
#include "sphstab/forms/variational_total_lagrangian.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "forms_fixture.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

namespace sphstab {
namespace variational_total_lagrangian_test {

using test::kLame;
using test::kRho;

std::shared_ptr<const StVenantKirchhoff<2>> svk(const ElasticMaterial& l = kLame) {
  return std::make_shared<StVenantKirchhoff<2>>(l);
}

TEST(VariationalTotalLagrangian, PlainGradientIsThePlusFormOfFiniteStrainTotalLagrangian) {
  auto d = test::lattice_discretisation<2>({.n = 6, .perturbation = 0.1});  // equal volumes, perturbed positions
  VariationalTotalLagrangian<2> var(d, svk(), kRho);
  FiniteStrainTotalLagrangian<2> plus(d, svk(), kRho);
  const Eigen::VectorXd u = test::random_vector(var.dofs(), 0.05, 21);
  Eigen::VectorXd a, b;
  var.acceleration(u, a);
  plus.acceleration(u, b);
  ASSERT_GT(b.cwiseAbs().maxCoeff(), 1e-3);
  // same sums in another order: rounding only
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12 * b.cwiseAbs().maxCoeff());
  EXPECT_NEAR(var.strain_energy(u), plus.strain_energy(u), 1e-14 * std::abs(plus.strain_energy(u)));
}

TEST(VariationalTotalLagrangian, NcsphForceIsTheNegativeEnergyGradient) {
  auto d = test::lattice_discretisation<2>({.n = 5, .perturbation = 0.15, .seed = 4});
  VariationalTotalLagrangian<2> var(d, svk(), kRho, make_gradient_provider<2>(Correction::Ncsph));
  const Eigen::VectorXd u = test::random_vector(var.dofs(), 0.05, 8);
  Eigen::VectorXd a;
  var.acceleration(u, a);
  const Eigen::VectorXd ma = var.dof_mass().cwiseProduct(a);
  const double worst = test::max_abs(test::energy_gradient(var, u) + ma), scale = test::max_abs(ma);
  ASSERT_GT(scale, 1e-4);
  EXPECT_LT(worst, 1e-11 * scale);  // complex step is exact to rounding; sums of O(100) terms
}

TEST(VariationalTotalLagrangian, RigidRotationOfTheBeamIsForceFreeWithNcsphOnly) {
  const TurekHronBeam beam = turek_hron_beam({.across = 4});
  const auto d = make_discretisation(beam.particles, Kernel<2>(KernelType::WendlandC2), 1.5 * beam.dx);
  const ElasticMaterial lame = ElasticMaterial::from_lame(2e6, 0.5e6, kRho);
  const double theta = 0.3;
  Eigen::Matrix2d R;
  R << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  Eigen::VectorXd u(d->dofs()), fixed(2 * (d->size() - d->free_count()));
  for (int i = 0, k = 0; i < d->size(); ++i) {
    const Eigen::Vector2d w = (R - Eigen::Matrix2d::Identity()) * d->particles.x.row(i).transpose();
    if (d->free_slot[i] >= 0)
      u.segment<2>(2 * d->free_slot[i]) = w;
    else
      fixed.segment<2>(2 * k++) = w;
  }
  VariationalTotalLagrangian<2> ncsph(d, svk(lame), 1000.0, make_gradient_provider<2>(Correction::Ncsph));
  VariationalTotalLagrangian<2> plain(d, svk(lame), 1000.0);
  ncsph.set_fixed_displacement(fixed);
  plain.set_fixed_displacement(fixed);
  Eigen::VectorXd a_n, a_p;
  ncsph.acceleration(u, a_n);
  plain.acceleration(u, a_p);
  // scale: the acceleration of a unit-strain stress over one particle, mu / (rho dx) = 1e5 m/s^2
  const double scale = lame.mu() / (1000.0 * beam.dx);
  EXPECT_LT(a_n.cwiseAbs().maxCoeff(), 1e-10 * scale);  // F = R exactly: P = 0 up to rounding
  EXPECT_GT(a_p.cwiseAbs().maxCoeff(), 1e-3 * scale);   // spurious surface strain ~0.045 (studies/tl-csm3)
}

TEST(VariationalTotalLagrangian, NcsphBeamHasNoGrowingModeAtRest) {
  // FiniteStrainTotalLagrangian with NCSPH strain and the plain-G plus divergence has gamma = 277 1/s here
  // (studies/tl-csm3); the variational pair's A = M^{-1} Hess U is similar to a symmetric matrix: real eigenvalues.
  const TurekHronBeam beam = turek_hron_beam({.across = 4});
  const auto d = make_discretisation(beam.particles, Kernel<2>(KernelType::WendlandC2), 1.5 * beam.dx);
  VariationalTotalLagrangian<2> var(d, svk(ElasticMaterial::from_lame(2e6, 0.5e6, 1.0)), 1000.0,
                                    make_gradient_provider<2>(Correction::Ncsph));
  const Eigen::MatrixXd A = Eigen::MatrixXd(jacobian(var, Eigen::VectorXd::Zero(var.dofs())));
  // equal masses: A itself is symmetric (to complex-step rounding)
  EXPECT_LT((A - A.transpose()).cwiseAbs().maxCoeff(), 1e-9 * A.cwiseAbs().maxCoeff());
  const Eigen::VectorXd mu =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (A + A.transpose()), Eigen::EigenvaluesOnly).eigenvalues();
  // smallest eigenvalue >= -1e-9 max: no growing mode (negative mu would grow like exp(sqrt(-mu) t))
  EXPECT_GT(mu.minCoeff(), -1e-9 * mu.maxCoeff());
}

TEST(VariationalTotalLagrangian, ReusedScratchArraysGiveTheResultOfAFreshForm) {
  // acceleration() and strain_energy() reuse the form's scratch arrays: after evaluations at another state, the
  // result at u2 is bit for bit that of a fresh copy (a copy starts with empty arrays).
  auto d = test::lattice_discretisation<2>({.n = 6, .perturbation = 0.1});
  VariationalTotalLagrangian<2> var(d, svk(), kRho, make_gradient_provider<2>(Correction::Ncsph));
  const Eigen::VectorXd u1 = test::random_vector(var.dofs(), 0.05, 11), u2 = test::random_vector(var.dofs(), 0.05, 12);
  Eigen::VectorXd a, b;
  Eigen::VectorXcd ac, bc;
  const Eigen::VectorXcd u1c = u1.cast<std::complex<double>>(), u2c = u2.cast<std::complex<double>>();
  var.acceleration(u1, a);
  var.acceleration(u1c, ac);
  (void)var.strain_energy(u1);
  var.acceleration(u2, a);
  var.acceleration(u2c, ac);
  const double e = var.strain_energy(u2);
  VariationalTotalLagrangian<2> fresh(var);
  fresh.acceleration(u2, b);
  fresh.acceleration(u2c, bc);
  EXPECT_EQ(a, b);
  EXPECT_EQ(ac, bc);
  EXPECT_EQ(e, VariationalTotalLagrangian<2>(var).strain_energy(u2));
}

TEST(VariationalTotalLagrangian, RejectsBadInput) {
  auto d = test::lattice_discretisation<2>({.n = 4});
  EXPECT_THROW(VariationalTotalLagrangian<2>(nullptr, svk(), kRho), std::invalid_argument);
  EXPECT_THROW(VariationalTotalLagrangian<2>(d, nullptr, kRho), std::invalid_argument);
  EXPECT_THROW(VariationalTotalLagrangian<2>(d, svk(), -1.0), std::invalid_argument);
  EXPECT_THROW(VariationalTotalLagrangian<2>(d, svk(), Eigen::VectorXd::Ones(3)), std::invalid_argument);
  EXPECT_THROW(VariationalTotalLagrangian<2>(d, svk(), kRho, make_gradient_provider<2>(Correction::MeanPolish)),
               std::invalid_argument);
  VariationalTotalLagrangian<2> var(d, svk(), kRho);
  EXPECT_THROW(var.set_fixed_displacement(Eigen::VectorXd::Zero(3)), std::invalid_argument);
  EXPECT_THROW(var.with_load(1.0), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
