// The finite-strain total-Lagrangian form [Ismail2009, ch. 5] (forms/finite_strain_total_lagrangian.hpp): the
// small-strain limit against TotalLagrangianForm2D and the analytic 1D Jacobian, linear momentum, the variational
// pair, homogeneous deformations, and bad input.
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"

#include <gtest/gtest.h>

#include <random>
#include <utility>

#include "forms_fixture.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"

namespace sphstab {
namespace finite_strain_total_lagrangian_test {

using test::random_vector;
using test::kLame;
using test::kRho;

using test::max_abs;

template <int Dim>
std::vector<std::shared_ptr<const HyperelasticModel<Dim>>> models() {
  return {std::make_shared<Hooke<Dim>>(kLame), std::make_shared<StVenantKirchhoff<Dim>>(kLame),
          std::make_shared<NeoHookean<Dim>>(kLame)};
}

/// A perturbed 2D lattice whose volumes and densities (rho0 = kRho) are scaled by factors uniform in [0.7, 1.3].
std::pair<std::shared_ptr<const Discretisation<2>>, Eigen::VectorXd> unequal_masses(const test::LatticeSpec& spec,
                                                                                    unsigned seed) {
  auto base = test::lattice_discretisation<2>(spec);
  ParticleSet<2> set = base->particles;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.7, 1.3);
  Eigen::VectorXd rho(set.size());
  for (int i = 0; i < set.size(); ++i) {
    set.volume[i] *= U(rng);
    rho[i] = kRho * U(rng);
  }
  return {make_discretisation(set, base->kernel, base->h), rho};
}

TEST(FiniteStrainTotalLagrangian, HookeIsTheSmallStrainTotalLagrangianForm) {
  // Minus strain + Plus divergence with Hooke's law is TotalLagrangianForm2D at ANY displacement (both linear).
  auto d = test::lattice_discretisation<2>({.n = 6, .perturbation = 0.1});
  TotalLagrangianForm2D small(d, kLame);
  FiniteStrainTotalLagrangian<2> tl(d, std::make_shared<Hooke<2>>(kLame), kRho);
  for (double amp : {1e-6, 1e-3, 0.1}) {
    const Eigen::VectorXd u = random_vector(tl.dofs(), amp, 3);
    Eigen::VectorXd a_small, a;
    small.acceleration(u, a_small);
    tl.acceleration(u, a);
    // Round-off: F = I + Grad u is formed first, so Grad u = F - I carries the rounding of I, a relative error of
    // ~ 1e-16 / |Grad u| (the small-strain form differentiates u directly). 3e-15 / amp covers it with margin.
    EXPECT_LT(max_abs(a - a_small), std::max(1e-13, 3e-15 / amp) * max_abs(a_small)) << amp;
  }
}

TEST(FiniteStrainTotalLagrangian, HyperelasticModelsApproachTheSmallStrainFormLinearly) {
  // |a_NH - a_small| / |a_small| = O(strain): 1e-3 of it at amplitude 1e-3 and 1e-6 at 1e-6 (ratio ~ 1000).
  auto d = test::lattice_discretisation<2>({.n = 6});
  TotalLagrangianForm2D small(d, kLame);
  for (const auto& m : models<2>()) {
    FiniteStrainTotalLagrangian<2> tl(d, m, kRho);
    std::array<double, 2> rel{};
    int k = 0;
    for (double amp : {1e-3, 1e-6}) {
      const Eigen::VectorXd u = random_vector(tl.dofs(), amp, 9);
      Eigen::VectorXd a_small, a;
      small.acceleration(u, a_small);
      tl.acceleration(u, a);
      rel[k++] = max_abs(a - a_small) / max_abs(a_small);
    }
    if (m->name().rfind("hooke", 0) == 0) {  // linear: round-off of F - I only (see above)
      EXPECT_LT(rel[0], 3e-15 / 1e-3);
      EXPECT_LT(rel[1], 3e-15 / 1e-6);
      continue;
    }
    EXPECT_LT(rel[0], 1e-2) << m->name();
    EXPECT_GT(rel[0], 1e-5) << m->name();  // the nonlinearity is there
    EXPECT_NEAR(rel[0] / rel[1], 1e3, 0.2e3) << m->name();
  }
}

TEST(FiniteStrainTotalLagrangian, JacobianAtRestIsTheSmallStrainStiffness2D) {
  auto d = test::lattice_discretisation<2>({.n = 6});
  TotalLagrangianForm2D small(d, kLame);
  const Eigen::MatrixXd K(jacobian(small, Eigen::VectorXd::Zero(small.dofs())));
  for (const auto& m : models<2>()) {
    FiniteStrainTotalLagrangian<2> tl(d, m, kRho);
    const Eigen::MatrixXd A(jacobian(tl, Eigen::VectorXd::Zero(tl.dofs())));
    EXPECT_LT(max_abs(A - K), 1e-12 * max_abs(K)) << m->name();
  }
}

TEST(FiniteStrainTotalLagrangian, JacobianAtRestIsTheAnalytic1DStiffness) {
  // 1D: A = (M / rho) G_f G_f^T [Powell2012, (3.40)] at T = 0, M = lambda + 2 mu (1D strain) or E (1D stress).
  auto d = test::lattice_discretisation<1>({.n = 30, .kernel = KernelType::ModifiedMollifier, .h = 2.5});
  const Eigen::MatrixXd K(analytic_jacobian_1d(d->particles, d->kernel, d->h, MomentumForm::Plus).A0);
  for (UniaxialState s : {UniaxialState::Strain, UniaxialState::Stress}) {
    for (const std::shared_ptr<const HyperelasticModel<1>>& m :
         std::vector<std::shared_ptr<const HyperelasticModel<1>>>{std::make_shared<Hooke<1>>(kLame, s),
                                                                  std::make_shared<StVenantKirchhoff<1>>(kLame, s),
                                                                  std::make_shared<NeoHookean<1>>(kLame, s)}) {
      FiniteStrainTotalLagrangian<1> tl(d, m, kRho);
      const Eigen::MatrixXd A(jacobian(tl, Eigen::VectorXd::Zero(tl.dofs())));
      const double M = kLame.uniaxial_modulus(s);
      EXPECT_LT(max_abs(A - (M / kRho) * K), 1e-12 * max_abs(A)) << m->name();
    }
  }
}

TEST(FiniteStrainTotalLagrangian, JacobianAtAHomogeneousStretchIsTheTangentTimesTheUnitStiffness) {
  // 1D Neo-Hookean (1D strain), fixed layers two supports deep carrying u = (lambda - 1) X: every active particle has
  // F = 1 + m1 (lambda - 1), so A(lambda) = (dP/dF(F) / rho) G_f G_f^T [Powell2012, (3.40)] exactly. It changes sign
  // with the tangent: nu = 0.49 loses positive definiteness where dP/dF = 0 (tests/models: F = 3.6307).
  auto d = test::lattice_discretisation<1>(
      {.n = 40, .kernel = KernelType::ModifiedMollifier, .h = 2.75, .support_scale = 2.0});
  const Eigen::MatrixXd K(analytic_jacobian_1d(d->particles, d->kernel, d->h, MomentumForm::Plus).A0);
  auto nh = std::make_shared<NeoHookean<1>>(ElasticMaterial::from_young_poisson(2 * 1.49, 0.49, kRho));
  FiniteStrainTotalLagrangian<1> tl(d, nh, kRho);
  Eigen::VectorXd x_fixed(d->size() - d->free_count());
  for (int i = 0, k = 0; i < d->size(); ++i)
    if (d->free_slot[i] < 0) x_fixed[k++] = d->particles.x(i, 0);
  const Eigen::VectorXd x_free = d->free_positions().col(0);
  for (double lambda : {1.5, 3.0, 4.5, 7.0}) {
    tl.set_fixed_displacement((lambda - 1) * x_fixed);
    const Eigen::VectorXd u = (lambda - 1) * x_free;
    Eigen::VectorXd a;
    tl.acceleration(u, a);
    const double F = tl.deformation_gradients(u)(d->free[0], 0);
    const double tangent = nh->tangent(Deformation<double, 1>(Deformation<double, 1>::Constant(F)))(0, 0);
    EXPECT_LT(max_abs(a), 1e-12 * nh->material().lambda() / d->h) << lambda;  // an equilibrium
    const Eigen::MatrixXd A(jacobian(tl, u));
    EXPECT_LT(max_abs(A - (tangent / kRho) * K), 1e-11 * max_abs(A)) << lambda;
    EXPECT_EQ(tangent > 0, lambda < 3.6 || lambda > 6.4) << lambda;
  }
}

TEST(FiniteStrainTotalLagrangian, PlusDivergenceConservesLinearMomentumIsmailsPlainDoesNot) {
  // No fixed particles, perturbed lattice, unequal volumes and densities, large deformation.
  const auto [d, rho] = unequal_masses({.n = 6, .perturbation = 0.2, .fixed_layers = 0}, 3);
  auto nh = std::make_shared<NeoHookean<2>>(kLame);
  const Eigen::VectorXd u = random_vector(2 * d->size(), 0.15, 4);
  auto momentum = [&](const FiniteStrainTotalLagrangian<2>& tl) {
    Eigen::VectorXd a;
    tl.acceleration(u, a);
    const Eigen::VectorXd ma = tl.dof_mass().cwiseProduct(a);
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (int f = 0; f < tl.discretisation().free_count(); ++f) sum += ma.segment<2>(2 * f);
    return sum.cwiseAbs().maxCoeff() / ma.cwiseAbs().maxCoeff();
  };
  for (StrainSum sum : {StrainSum::Difference, StrainSum::Direct}) {
    for (auto grad : {std::shared_ptr<const GradientProvider<2>>(), make_gradient_provider<2>(Correction::Ncsph)}) {
      FiniteStrainOptions<2> opt{.strain_sum = sum, .gradient = grad, .divergence = StressDivergence::Plus};
      EXPECT_LT(momentum(FiniteStrainTotalLagrangian<2>(d, nh, rho, opt)), 1e-14);
      opt.divergence = StressDivergence::Plain;  // [Ismail2009, (5.8)]
      EXPECT_GT(momentum(FiniteStrainTotalLagrangian<2>(d, nh, rho, opt)), 1e-3);
    }
  }
}

TEST(FiniteStrainTotalLagrangian, VariationalPairIsConservative) {
  // M a = -dU/du (complex step of U) and M A symmetric, for unequal volumes and densities, at a large deformation.
  const auto [d, rho] = unequal_masses({.n = 5, .perturbation = 0.2}, 8);
  for (const auto& m : models<2>()) {
    FiniteStrainTotalLagrangian<2> tl(d, m, rho);
    ASSERT_TRUE(tl.conservative());
    const Eigen::VectorXd u = random_vector(tl.dofs(), 0.1, 6);
    Eigen::VectorXd a;
    tl.acceleration(u, a);
    const Eigen::VectorXd ma = tl.dof_mass().cwiseProduct(a);
    EXPECT_LT(max_abs(ma + test::energy_gradient(tl, u)), 1e-12 * max_abs(ma)) << m->name();
    const Eigen::MatrixXd MA = tl.dof_mass().asDiagonal() * Eigen::MatrixXd(jacobian(tl, u));
    EXPECT_LT(max_abs(MA - MA.transpose()), 1e-12 * max_abs(MA)) << m->name();
    // Ismail's plain pair is not variational
    FiniteStrainTotalLagrangian<2> ismail(
        d, m, rho, {.strain_sum = StrainSum::Direct, .gradient = nullptr, .divergence = StressDivergence::Plain});
    EXPECT_FALSE(ismail.conservative());
  }
}

TEST(FiniteStrainTotalLagrangian, HomogeneousDeformationIsAnExactEquilibriumWithTheCorrectedGradient) {
  // Fixed layers two supports deep carry u = (F0 - I) X: with the first-order corrected (NCSPH) reference gradient
  // every active F_i is F0 and a = 0; the plain gradient gives F = I + m1 (F0 - I) in the complete interior.
  auto d = test::lattice_discretisation<2>({.n = 6, .support_scale = 2.0});
  Eigen::Matrix2d F0;
  F0 << 1.8, 0.3, -0.2, 1.1;
  Eigen::VectorXd u(d->dofs()), fixed(2 * (d->size() - d->free_count()));
  long next = 0;
  for (int i = 0; i < d->size(); ++i) {
    const Eigen::Vector2d ui = (F0 - Eigen::Matrix2d::Identity()) * d->particles.x.row(i).transpose();
    if (d->free_slot[i] >= 0)
      u.segment<2>(2 * d->free_slot[i]) = ui;
    else
      fixed.segment<2>(2 * next++) = ui;
  }
  auto nh = std::make_shared<NeoHookean<2>>(kLame);
  FiniteStrainTotalLagrangian<2> tl(d, nh, kRho, {.gradient = make_gradient_provider<2>(Correction::Ncsph)});
  tl.set_fixed_displacement(fixed);
  const Eigen::MatrixXd F = tl.deformation_gradients(u);
  for (int i : tl.active())
    EXPECT_LT((F.row(i) - Eigen::RowVector4d(F0(0, 0), F0(0, 1), F0(1, 0), F0(1, 1))).cwiseAbs().maxCoeff(), 1e-12)
        << i;
  Eigen::VectorXd a;
  tl.acceleration(u, a);
  EXPECT_LT(max_abs(a), 1e-12 * max_abs(nh->stress(F0)) / d->h);
  // plain gradient: F - I = m1 (F0 - I) at free particles, with the lattice's first moment
  // m1 = sum_j (x_j - x_i) G^x_ij (!= 1 for the cubic B-spline at h = 1.3 dx), computed here from the operators
  const auto ops = assemble_operators<2, double>(d->particles, d->neighbours, d->kernel, d->h);
  double m1 = 0;
  for (SparseMatrix<>::InnerIterator it(ops.G[0], d->free[0]); it; ++it)
    m1 += (d->particles.x(it.col(), 0) - d->particles.x(d->free[0], 0)) * it.value();
  EXPECT_GT(std::abs(m1 - 1), 1e-3);
  FiniteStrainTotalLagrangian<2> plain(d, nh, kRho);
  plain.set_fixed_displacement(fixed);
  const Eigen::MatrixXd Fp = plain.deformation_gradients(u);
  for (int f = 0; f < d->free_count(); ++f)
    EXPECT_LT((Fp.row(d->free[f]) -
               Eigen::RowVector4d(1 + m1 * (F0(0, 0) - 1), m1 * F0(0, 1), m1 * F0(1, 0), 1 + m1 * (F0(1, 1) - 1)))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12);
}

TEST(FiniteStrainTotalLagrangian, IsmailsPlainPairIsAlgorithm51WithSparseMatrices) {
  // [Ismail2009] algorithm 5.1: F = X u + 1, P = mu (F - 1/F) + lambda ln F / F, a = X P / rho, with X = G (all
  // particles, fixed ones at their prescribed displacement), written here with the sparse matrix directly.
  auto d = test::lattice_discretisation<1>({.n = 25, .kernel = KernelType::ModifiedMollifier, .h = 2.75});
  auto nh = std::make_shared<NeoHookean<1>>(kLame);
  FiniteStrainTotalLagrangian<1> tl(
      d, nh, kRho, {.strain_sum = StrainSum::Direct, .gradient = nullptr, .divergence = StressDivergence::Plain});
  const Eigen::VectorXd fixed = random_vector(d->size() - d->free_count(), 0.05, 2);
  tl.set_fixed_displacement(fixed);
  const Eigen::VectorXd u = random_vector(tl.dofs(), 0.05, 3);
  Eigen::VectorXd uall(d->size());
  for (int i = 0, k = 0; i < d->size(); ++i) uall[i] = d->free_slot[i] >= 0 ? u[d->free_slot[i]] : fixed[k++];
  const auto ops = assemble_operators<1, double>(d->particles, d->neighbours, d->kernel, d->h);
  const Eigen::VectorXd F = (ops.G[0] * uall).array() + 1.0;
  Eigen::VectorXd P(d->size());
  for (int i = 0; i < d->size(); ++i)
    P[i] = kLame.mu() * (F[i] - 1 / F[i]) + kLame.lambda() * std::log(F[i]) / F[i];  // line 15
  const Eigen::VectorXd aall = ops.G[0] * P / kRho;  // lines 16-17 (rows of inactive particles unused)
  Eigen::VectorXd a;
  tl.acceleration(u, a);
  for (int f = 0; f < tl.dofs(); ++f) EXPECT_NEAR(a[f], aall[d->free[f]], 1e-12 * aall.cwiseAbs().maxCoeff()) << f;
}

TEST(FiniteStrainTotalLagrangian, RigidRotationIsStressAndForceFreeForObjectiveMaterialsOnly) {
  // u = (Q - I) X on every particle with the first-order corrected reference gradient: F_i = Q exactly, so P = 0 for
  // Neo-Hookean and St Venant-Kirchhoff, while Hooke's small-strain law gives a (uniform) stress.
  auto d = test::lattice_discretisation<2>({.n = 6, .support_scale = 2.0});
  const double angle = 0.7;
  Eigen::Matrix2d Q;
  Q << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  Eigen::VectorXd u(d->dofs()), fixed(2 * (d->size() - d->free_count()));
  long next = 0;
  for (int i = 0; i < d->size(); ++i) {
    const Eigen::Vector2d ui = (Q - Eigen::Matrix2d::Identity()) * d->particles.x.row(i).transpose();
    if (d->free_slot[i] >= 0)
      u.segment<2>(2 * d->free_slot[i]) = ui;
    else
      fixed.segment<2>(2 * next++) = ui;
  }
  for (const auto& m : models<2>()) {
    FiniteStrainTotalLagrangian<2> tl(d, m, kRho, {.gradient = make_gradient_provider<2>(Correction::Ncsph)});
    tl.set_fixed_displacement(fixed);
    double stress = 0;
    const Eigen::MatrixXd P = tl.stresses(u);
    for (int i : tl.active()) stress = std::max(stress, P.row(i).cwiseAbs().maxCoeff());
    Eigen::VectorXd a;
    tl.acceleration(u, a);
    if (m->name().rfind("hooke", 0) == 0) {
      // eps = sym(Q - I) = (cos - 1) I: a uniform (hence force-free) but non-zero stress 2 (lambda + mu)(cos - 1)
      EXPECT_NEAR(stress, 2 * (kLame.lambda() + kLame.mu()) * (1 - std::cos(angle)), 1e-12) << m->name();
    } else {
      EXPECT_LT(stress, 1e-13 * kLame.lambda()) << m->name();
      EXPECT_LT(max_abs(a), 1e-12 * (kLame.lambda() + 2 * kLame.mu()) / (kRho * d->h)) << m->name();
    }
  }
}

TEST(FiniteStrainTotalLagrangian, LeapfrogConservesTheEnergyOfTheVariationalPairToSecondOrder) {
  // A large-amplitude Neo-Hookean run (strains ~ 0.2): the energy error of leap-frog is O(dt^2) without drift, so
  // halving dt divides the largest |E(t) - E(0)| by about 4.
  auto d = test::lattice_discretisation<2>({.n = 6});
  auto tl = std::make_shared<FiniteStrainTotalLagrangian<2>>(d, std::make_shared<NeoHookean<2>>(kLame), kRho);
  const Eigen::VectorXd u0 = random_vector(tl->dofs(), 0.1, 12);
  const double period = d->h / std::sqrt((kLame.lambda() + 2 * kLame.mu()) / kRho);  // ~ h / c
  std::array<double, 2> worst{};
  for (int k = 0; k < 2; ++k) {
    const double dt = 0.05 * period / (1 << k);
    SecondOrderSystem sys;
    sys.acceleration = acceleration_function(tl);
    sys.mass.resize(tl->dofs() / 2);  // per particle
    for (int f = 0; f < tl->dofs() / 2; ++f) sys.mass[f] = tl->dof_mass()[2 * f];
    sys.dofs_per_particle = 2;
    LeapfrogStepper stepper(sys, u0, Eigen::VectorXd::Zero(tl->dofs()));
    const double e0 = total_energy(*tl, stepper.u(), stepper.v());
    while (stepper.time() < 20 * period - 1e-12) {
      stepper.step(dt);
      worst[k] = std::max(worst[k], std::abs(total_energy(*tl, stepper.u(), stepper.v()) - e0) / e0);
    }
  }
  EXPECT_LT(worst[0], 1e-2);
  EXPECT_NEAR(worst[0] / worst[1], 4.0, 0.8);
}

TEST(FiniteStrainTotalLagrangian, ComplexOverloadIsTheRealForceOnTheRealPart) {
  auto d = test::lattice_discretisation<1>({.n = 12});
  FiniteStrainTotalLagrangian<1> tl(d, std::make_shared<NeoHookean<1>>(kLame), kRho);
  const Eigen::VectorXd u = random_vector(tl.dofs(), 0.2, 1);
  Eigen::VectorXd a;
  Eigen::VectorXcd ac;
  tl.acceleration(u, a);
  tl.acceleration(Eigen::VectorXcd(u.cast<std::complex<double>>()), ac);
  EXPECT_LT(max_abs(ac.real() - a), 1e-15 * max_abs(a));
  EXPECT_EQ(max_abs(ac.imag()), 0.0);
}

TEST(FiniteStrainTotalLagrangian, ReusedScratchArraysGiveTheResultOfAFreshForm) {
  // acceleration() and strain_energy() reuse the form's scratch arrays (F, P, full displacement): after evaluations at
  // other states (real, complex, energy), the result at u2 is bit for bit that of a fresh copy (a copy starts empty).
  auto d = test::lattice_discretisation<2>({.n = 6, .perturbation = 0.1});
  FiniteStrainTotalLagrangian<2> tl(d, std::make_shared<NeoHookean<2>>(kLame), kRho,
                                    {.gradient = make_gradient_provider<2>(Correction::Ncsph), .hourglass = 0.1});
  tl.set_fixed_displacement(random_vector(static_cast<int>(tl.fixed_displacement().size()), 0.01, 5));
  const Eigen::VectorXd u1 = random_vector(tl.dofs(), 0.05, 11), u2 = random_vector(tl.dofs(), 0.05, 12);
  Eigen::VectorXd a, b;
  Eigen::VectorXcd ac, bc;
  const Eigen::VectorXcd u1c = u1.cast<std::complex<double>>(), u2c = u2.cast<std::complex<double>>();
  tl.acceleration(u1, a);
  tl.acceleration(u1c, ac);
  (void)tl.strain_energy(u1);
  tl.acceleration(u2, a);
  tl.acceleration(u2c, ac);
  const double e = tl.strain_energy(u2);
  FiniteStrainTotalLagrangian<2> fresh(tl);
  fresh.acceleration(u2, b);
  fresh.acceleration(u2c, bc);
  EXPECT_EQ(a, b);
  EXPECT_EQ(ac, bc);
  EXPECT_EQ(e, FiniteStrainTotalLagrangian<2>(tl).strain_energy(u2));
}

TEST(FiniteStrainTotalLagrangian, BadInputIsOneLineInvalidArgument) {
  auto d = test::lattice_discretisation<1>({.n = 8});
  auto nh = std::make_shared<NeoHookean<1>>(kLame);
  auto one_line = [](auto&& f, const std::string& expect) {
    try {
      f();
      ADD_FAILURE() << "no throw: " << expect;
    } catch (const std::invalid_argument& e) {
      const std::string w = e.what();
      EXPECT_EQ(w.find('\n'), std::string::npos) << w;
      EXPECT_NE(w.find(expect), std::string::npos) << w;
    }
  };
  one_line([&] { FiniteStrainTotalLagrangian<1>(nullptr, nh, kRho); }, "discretisation is null");
  one_line([&] { FiniteStrainTotalLagrangian<1>(d, nullptr, kRho); }, "material is null");
  one_line([&] { FiniteStrainTotalLagrangian<1>(d, nh, -1.0); }, "density of particle 0");
  one_line([&] { FiniteStrainTotalLagrangian<1>(d, nh, Eigen::VectorXd::Ones(3)); }, "density has 3 entries");
  one_line(
      [&] {
        FiniteStrainTotalLagrangian<1>(d, nh, kRho, {.gradient = nullptr, .divergence = StressDivergence::Adjoint});
      },
      "adjoint");
  auto bad_h = std::make_shared<Discretisation<1>>(*d);
  bad_h->h = 0;
  one_line([&] { FiniteStrainTotalLagrangian<1>(bad_h, nh, kRho); }, "smoothing length h");
  one_line([&] { NeoHookean<1>(ElasticMaterial::from_young_poisson(1.0, 0.5, kRho)); }, "Poisson's ratio");
  one_line([&] { NeoHookean<1>(ElasticMaterial::from_lame(-2, 1, kRho)); }, "outside (-1, 0.5)");
  FiniteStrainTotalLagrangian<1> tl(d, nh, kRho);
  one_line([&] { tl.with_load(1.0); }, "no affine load");
  EXPECT_NO_THROW(tl.with_load(0.0));
  one_line([&] { tl.set_fixed_displacement(Eigen::VectorXd::Zero(1)); }, "expected");
  // a compression that inverts particles: J <= 0
  Eigen::VectorXd u(tl.dofs());
  for (int f = 0; f < tl.dofs(); ++f) u[f] = -1.5 * d->particles.x(d->free[f], 0);
  Eigen::VectorXd a;
  one_line([&] { tl.acceleration(u, a); }, "J = det F");
}

}  // namespace
}  // namespace sphstab
