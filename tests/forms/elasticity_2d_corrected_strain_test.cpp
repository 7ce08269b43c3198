#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace elasticity_2d_corrected_strain_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2, 0.8, 7.8);

TEST(ElasticForm2DCorrectedStrain, NcsphStrainIsExactForLinearFieldsAndThePatchTestHolds) {
  Kernel<2> k(KernelType::CubicSpline);
  auto set = make_lattice<2>(LatticeType::Square, 6,
                             {.spacing = 1.0, .support_radius = k.support_radius(1.3), .perturbation = 0.1, .seed = 5});
  auto d = make_discretisation(set, k, 1.3);
  ElasticForm2D force(d, kMaterial, MomentumForm::Plus, PreStrain::from_area_ratio(1.02),
                      make_gradient_provider<2>(Correction::Ncsph));
  force.set_corrected_strain(true);
  // u = B x on every particle (free and fixed)
  Eigen::Matrix2d B;
  B << 0.01, -0.004, 0.003, -0.002;
  Eigen::VectorXd u(d->dofs()), fixed(2 * (d->size() - d->free_count()));
  int nf = 0;
  for (int i = 0; i < d->size(); ++i) {
    const Eigen::Vector2d ui = B * d->particles.x.row(i).transpose();
    if (d->free_slot[i] >= 0)
      u.segment<2>(2 * d->free_slot[i]) = ui;
    else
      fixed.segment<2>(2 * nf++) = ui;
  }
  force.set_fixed_displacement(fixed);
  const Eigen::MatrixX3d sig = force.stress(u);
  const Eigen::Matrix2d s0 = force.prestrain().stress(kMaterial);
  // The kernel sits at the current positions x = (I + B) x0, where u = B x0 is linear in x with gradient
  // B (I + B)^{-1}: NCSPH reproduces that gradient exactly at every particle, boundary included.
  const Eigen::Matrix2d Bc = B * (Eigen::Matrix2d::Identity() + B).inverse();
  const Eigen::Matrix2d ec = 0.5 * (Bc + Bc.transpose());
  const double sxx_c = kMaterial.lambda() * ec.trace() + 2 * kMaterial.mu() * ec(0, 0) + s0(0, 0);
  const double sxy_c = 2 * kMaterial.mu() * ec(0, 1);
  for (int i = 0; i < d->size(); ++i) {
    EXPECT_NEAR(sig(i, 0), sxx_c, 1e-12) << i;
    EXPECT_NEAR(sig(i, 2), sxy_c, 1e-12) << i;
  }
  Eigen::VectorXd a;
  force.acceleration(u, a);  // uniform stress and rows of Ghat summing to zero: no force
  EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-12);
  // without the corrected strain the boundary particles see a wrong gradient and the patch test fails
  ElasticForm2D plain_strain(d, kMaterial, MomentumForm::Plus, PreStrain::from_area_ratio(1.02),
                             make_gradient_provider<2>(Correction::Ncsph));
  plain_strain.set_fixed_displacement(fixed);
  plain_strain.acceleration(u, a);
  EXPECT_GT(a.cwiseAbs().maxCoeff(), 1e-6);
}

TEST(ElasticForm2DCorrectedStrain, JacobianPatternCoversTheLongerReach) {
  // local polish (reach 2) in both operators: the complex-step Jacobian on the declared pattern must equal the dense
  // (uncoloured) one, i.e. no dependency falls outside the pattern.
  Kernel<2> k(KernelType::CubicSpline);
  auto set = make_lattice<2>(LatticeType::Square, 5, {.spacing = 1.0, .support_radius = k.support_radius(1.3)});
  auto d = make_discretisation(set, k, 1.3);
  ElasticForm2D force(d, kMaterial, MomentumForm::Uncorrected, PreStrain::from_area_ratio(1.03),
                      make_gradient_provider<2>(Correction::LocalPolish));
  force.set_corrected_strain(true);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> dist(-0.01, 0.01);
  Eigen::VectorXd u(force.dofs());
  for (int i = 0; i < u.size(); ++i) u[i] = dist(rng);
  const Eigen::MatrixXd Jc(ComplexStepJacobian(force).compute(u));
  const Eigen::MatrixXd Jd(ComplexStepJacobian(force, ColouringStrategy::None).compute(u));
  EXPECT_LT((Jc - Jd).cwiseAbs().maxCoeff(), 1e-13 * Jd.cwiseAbs().maxCoeff());
}

TEST(ElasticForm2DCorrectedStrain, CorrectedFormsAreInEquilibriumAtThePreStrainedLattice) {
  // NCSPH (both operators) and the C_ij momentum equation (4.10) with Fig. 4.3 counts and 4.18 means: the rows of
  // Ghat sum to zero on the free particles, so the uniform pre-stress exerts no force (the Swegle starting state).
  Kernel<2> k(KernelType::CubicSpline);
  auto set = make_lattice<2>(LatticeType::Square, 9, {.spacing = 1.0, .support_radius = k.support_radius(1.3)});
  auto d = make_discretisation(set, k, 1.3);
  for (double xi : {0.96, 1.04}) {
    ElasticForm2D ncsph(d, kMaterial, MomentumForm::Plus, PreStrain::from_area_ratio(xi),
                        make_gradient_provider<2>(Correction::Ncsph));
    ncsph.set_corrected_strain(true);
    ElasticForm2D cij(d, kMaterial, MomentumForm::Uncorrected, PreStrain::from_area_ratio(xi),
                      make_gradient_provider<2>(Correction::LocalPolish, {.counting = NeighbourCounting::BoundaryLevel,
                                                                          .first_step_shepard = true}));
    Eigen::VectorXd a;
    ncsph.acceleration(Eigen::VectorXd::Zero(ncsph.dofs()), a);
    EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-14) << "ncsph " << xi;  // sigma0 / rho ~ 0.01, sums of ~20 terms
    cij.acceleration(Eigen::VectorXd::Zero(cij.dofs()), a);
    EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-14) << "cij " << xi;
  }
}

TEST(ElasticForm2DCorrectedStrain, BadInput) {
  Kernel<2> k(KernelType::CubicSpline);
  auto set = make_lattice<2>(LatticeType::Square, 4, {.spacing = 1.0, .support_radius = k.support_radius(1.3)});
  auto d = make_discretisation(set, k, 1.3);
  ElasticForm2D plain(d, kMaterial, MomentumForm::Plus);
  EXPECT_THROW(plain.set_corrected_strain(true), std::invalid_argument);
  ElasticForm2D cons(d, kMaterial, MomentumForm::Conservative, PreStrain{},
                     make_gradient_provider<2>(Correction::None));
  EXPECT_THROW(cons.set_corrected_strain(true), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
