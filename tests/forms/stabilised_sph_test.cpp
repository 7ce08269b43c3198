#include "sphstab/forms/stabilised_sph.hpp"

#include <gtest/gtest.h>

#include <random>

#include "forms_fixture.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace stabilised_sph_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2, 0.8, 7.8);

std::shared_ptr<const Discretisation<2>> block(int n, bool periodic = false, double perturbation = 0) {
  return test::lattice_discretisation<2>({.n = n, .periodic = periodic, .perturbation = perturbation, .seed = 7});
}

using test::random_vector;

double max_abs(const Eigen::VectorXd& v) { return v.cwiseAbs().maxCoeff(); }

TEST(StabilisedSph, FusedMeansEqualLocalPolishMeansOfTheFirstStepShepardGradient) {
  auto d = block(6, false, 0.1);
  for (bool shepard : {true, false}) {
    StabilisedSphTerm term(d, {.first_step_shepard = shepard});
    // operators at displaced positions: the reference sums stay those of x0
    const Eigen::VectorXd u = random_vector(d->dofs(), 0.05, 3);
    Positions<2> x = d->particles.x;
    for (int f = 0; f < d->free_count(); ++f) x.row(d->free[f]) += Eigen::RowVector2d(u[2 * f], u[2 * f + 1]);
    auto ops = assemble_operators<2, double>(d->particles, d->neighbours, d->kernel, d->h, {}, &x);
    auto ops0 = assemble_operators<2, double>(d->particles, d->neighbours, d->kernel, d->h);
    const auto fused = term.local_means_of<double>(ops);
    for (int b = 0; b < 2; ++b) {
      const SparseMatrix<> gt =
          shepard ? reference_shepard_gradient<double>(ops.W, ops.G[b], shepard_reference(ops0.W, ops0.G[b]))
                  : ops.G[b];
      const LocalMeans<double> ref = local_means<double>(gt, term.counts());
      EXPECT_LT((fused[b].row - ref.row).cwiseAbs().maxCoeff(), 1e-14);
      EXPECT_LT((fused[b].column - ref.column).cwiseAbs().maxCoeff(), 1e-14);
      EXPECT_LT((fused[b].mean_of_columns - ref.mean_of_columns).cwiseAbs().maxCoeff(), 1e-14);
    }
  }
}

TEST(StabilisedSph, SwitchNeverAndEqualVolumesIsBasicSph) {
  // With the correction off everywhere the symmetrised f-part reduces to the Plus form exactly (G_ji = -G_ij).
  auto d = block(6);
  const PreStrain pre = PreStrain::from_area_ratio(1.03);
  ElasticForm2D plus(d, kMaterial, MomentumForm::Plus, pre);
  auto never = make_stabilised_sph(d, kMaterial, pre, {.rule = SwitchRule::Never});
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.02, 5);
  Eigen::VectorXd a1, a2;
  plus.acceleration(u, a1);
  never->acceleration(u, a2);
  EXPECT_LT(max_abs(a1 - a2), 1e-13 * max_abs(a1));
}

TEST(StabilisedSph, SwitchFollowsTheSignOfTheNeighbourStressSums) {
  auto d = block(5);
  for (double xi : {1.02, 0.98}) {
    auto force = make_stabilised_sph(d, kMaterial, PreStrain::from_area_ratio(xi));
    const StabilisedSphTerm* term = find_stabilised_sph_term(*force);
    ASSERT_NE(term, nullptr);
    const SwitchState on = term->switch_state(force->stress(Eigen::VectorXd::Zero(force->dofs())));
    for (int i = 0; i < d->size(); ++i)
      for (int a = 0; a < 2; ++a) {
        const bool expected = xi > 1 && d->particles.depth[i] > 0;  // tension, outer layer excluded
        EXPECT_EQ(on[i][a], expected) << "particle " << i << " xi " << xi;
      }
    auto printed = make_stabilised_sph(d, kMaterial, PreStrain::from_area_ratio(xi), {.rule = SwitchRule::AsPrinted});
    const SwitchState on2 =
        find_stabilised_sph_term(*printed)->switch_state(printed->stress(Eigen::VectorXd::Zero(printed->dofs())));
    for (int i = 0; i < d->size(); ++i) EXPECT_EQ(on2[i][0], xi < 1 && d->particles.depth[i] > 0);
  }
}

TEST(StabilisedSph, PerParticleFormIsInEquilibriumAtThePreStrainedLattice) {
  // (4.14)-(4.17) per particle: sum_j g_ij = -S (sum_j c_j - n_i m_i) = 0 for uniform stress and n_i = |N(i)|.
  auto d = block(9);
  for (double xi : {1.04, 0.96}) {
    auto force = make_stabilised_sph(d, kMaterial, PreStrain::from_area_ratio(xi), {.symmetrise = false});
    Eigen::VectorXd a;
    force->acceleration(Eigen::VectorXd::Zero(force->dofs()), a);
    // scale: sigma0 / (rho dx) ~ 0.01; round-off of sums of ~20 terms
    EXPECT_LT(max_abs(a), 1e-14) << "xi " << xi;
  }
}

TEST(StabilisedSph, SymmetrisedFormIsInEquilibriumOnAPeriodicLatticeButNotNearFixedLayers) {
  auto periodic = block(8, true);
  auto force = make_stabilised_sph(periodic, kMaterial, PreStrain::from_area_ratio(1.04));
  Eigen::VectorXd a;
  force->acceleration(Eigen::VectorXd::Zero(force->dofs()), a);
  EXPECT_LT(max_abs(a), 1e-14);
  // With fixed layers algorithm 4.2's symmetrisation adds -1/2 sum_j g_ji, which does not vanish near the boundary
  // (columns of the first-step Shepard gradient do not sum to zero there): the lattice is not an equilibrium.
  auto fixed = block(9);
  auto sym = make_stabilised_sph(fixed, kMaterial, PreStrain::from_area_ratio(1.04));
  sym->acceleration(Eigen::VectorXd::Zero(sym->dofs()), a);
  const double scale = sym->prestrain().stress(kMaterial)(0, 0) / kMaterial.density();  // sigma0 / (rho dx), dx = 1
  EXPECT_GT(max_abs(a), 0.1 * scale);
  // ... and in compression the switch is off: basic SPH, in equilibrium.
  auto comp = make_stabilised_sph(fixed, kMaterial, PreStrain::from_area_ratio(0.96));
  comp->acceleration(Eigen::VectorXd::Zero(comp->dofs()), a);
  EXPECT_LT(max_abs(a), 1e-14);
}

TEST(StabilisedSph, SymmetrisedFormConservesMomentum) {
  auto d = block(8, true, 0.05);  // periodic: every particle free; equal masses
  auto force =
      make_stabilised_sph(d, kMaterial, PreStrain::from_area_ratio(1.03), {.counting = NeighbourCounting::Actual});
  const Eigen::VectorXd u = random_vector(force->dofs(), 0.03, 11);
  Eigen::VectorXd a;
  force->acceleration(u, a);
  double px = 0, py = 0;
  for (int f = 0; f < d->free_count(); ++f) {
    px += a[2 * f];
    py += a[2 * f + 1];
  }
  EXPECT_LT(std::abs(px) + std::abs(py), 1e-12 * max_abs(a) * d->free_count());
  // the unsymmetrised form does not conserve momentum in general
  auto pp = make_stabilised_sph(d, kMaterial, PreStrain::from_area_ratio(1.03),
                                {.counting = NeighbourCounting::Actual, .symmetrise = false});
  pp->acceleration(u, a);
  px = py = 0;
  for (int f = 0; f < d->free_count(); ++f) {
    px += a[2 * f];
    py += a[2 * f + 1];
  }
  EXPECT_GT(std::abs(px) + std::abs(py), 1e-6 * max_abs(a));
}

TEST(StabilisedSph, ComplexStepJacobianMatchesFiniteDifferencesWithFrozenSwitch) {
  auto d = block(6, false, 0.05);
  auto force = make_stabilised_sph(d, kMaterial, PreStrain::from_area_ratio(1.02));
  const Eigen::VectorXd u = random_vector(force->dofs(), 1e-3, 13);
  auto frozen = freeze_switch(*force, u);
  ASSERT_TRUE(find_stabilised_sph_term(*frozen)->is_frozen());
  const SparseMatrix<> J = jacobian(*force, u);    // complex step: branch of the real point
  const SparseMatrix<> Jf = jacobian(*frozen, u);  // explicitly frozen
  EXPECT_LT(Eigen::MatrixXd(J - Jf).cwiseAbs().maxCoeff(), 1e-14 * Eigen::MatrixXd(J).cwiseAbs().maxCoeff());
  // central differences of the frozen force, step 1e-6 (truncation ~1e-12 |a'''|, round-off ~1e-16 |a| / 1e-6)
  const double h = 1e-6;
  const Eigen::MatrixXd Jd(J);
  double worst = 0;
  for (int k = 0; k < force->dofs(); k += 3) {
    Eigen::VectorXd up = u, um = u, ap, am;
    up[k] += h;
    um[k] -= h;
    frozen->acceleration(up, ap);
    frozen->acceleration(um, am);
    const Eigen::VectorXd col = -(ap - am) / (2 * h);
    worst = std::max(worst, (col - Jd.col(k)).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-7 * Jd.cwiseAbs().maxCoeff());  // FD accuracy, not complex-step accuracy
}

TEST(StabilisedSph, BadInput) {
  auto d = block(4);
  EXPECT_THROW(StabilisedSphTerm(nullptr), std::invalid_argument);
  EXPECT_THROW(StabilisedSphTerm(d, {.excluded_depth = -2}), std::invalid_argument);
  EXPECT_THROW(parse_switch_rule("sometimes"), std::invalid_argument);
  EXPECT_EQ(parse_switch_rule("as-printed"), SwitchRule::AsPrinted);
  StabilisedSphTerm term(d);
  EXPECT_THROW(term.frozen(SwitchState(3)), std::invalid_argument);
  EXPECT_THROW(term.switch_state(Eigen::MatrixX3d::Zero(2, 3)), std::invalid_argument);
  ElasticForm2D plain(d, kMaterial, MomentumForm::Plus);
  EXPECT_THROW(freeze_switch(plain, Eigen::VectorXd::Zero(plain.dofs())), std::invalid_argument);
  EXPECT_THROW(plain.add_term(nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
