// Kernel corrections as gradient providers of the 1D forms: reproduction of the operator-level corrections, exact
// Jacobians through every correction (complex step, and dual numbers for the corrected conservative form) against
// finite differences, and the stability claims of Powell ch. 3 §4 / ch. 4 §2 at the lattice equilibrium.
#include "sphstab/forms/correction_gradient.hpp"

#include <gtest/gtest.h>

#include <random>

#include "forms_fixture.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/operators/shepard.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace correction_gradient_test {

/// Line lattice of n free particles, dx = 1, with fixed layers `supports` kernel supports thick (strictly inside,
/// as tension_lattice_1d), optionally perturbed (free particles) or periodic.
std::shared_ptr<const Discretisation<1>> line(int n, KernelType type, double h, int supports = 1,
                                              double perturbation = 0.0, bool periodic = false) {
  return test::lattice_discretisation<1>({.n = n,
                                          .kernel = type,
                                          .h = h,
                                          .periodic = periodic,
                                          .perturbation = perturbation,
                                          .seed = 11,
                                          .support_scale = supports * (1 - 1e-9)});
}

using test::random_vector;

using test::max_abs;

/// Every correction, plus the local polish with the Fig. 4.3 counting and the (4.18) first-step Shepard means.
std::vector<std::shared_ptr<const GradientProvider<1>>> all_providers() {
  std::vector<std::shared_ptr<const GradientProvider<1>>> out;
  for (Correction c : all_corrections())
    if (c != Correction::None) out.push_back(make_gradient_provider<1>(c));
  out.push_back(make_gradient_provider<1>(Correction::LocalPolish,
                                          {.counting = NeighbourCounting::BoundaryLevel, .first_step_shepard = true}));
  return out;
}

/// Positions x0 + u of every particle (fixed ones at rest).
Positions<1> positions(const Discretisation<1>& d, const Eigen::VectorXd& u) {
  Positions<1> x = d.particles.x;
  for (int f = 0; f < d.free_count(); ++f) x(d.free[f], 0) += u[f];
  return x;
}

TEST(CorrectionGradient, ReproducesOperatorLevelCorrections) {
  // At the reference configuration and at a displaced one, the provider's Ghat equals apply_correction of the
  // operators assembled at the same positions (with the (4.18) sums frozen at x0, and the Fig. 4.3 counts).
  auto d = line(14, KernelType::QuinticSpline, 1.4, 1, 0.1);
  for (double amplitude : {0.0, 0.08}) {
    const Eigen::VectorXd u = random_vector(d->dofs(), amplitude, 4);
    const Positions<1> x = positions(*d, u);
    const Operators<1> ops = assemble_operators<1, double>(d->particles, d->neighbours, d->kernel, d->h,
                                                           {.kernel = true, .gradient = true}, &x);
    const Operators<1> ops0 =
        assemble_operators<1, double>(d->particles, d->neighbours, d->kernel, d->h, {.kernel = true, .gradient = true});
    const std::array<ShepardReference, 1> ref{shepard_reference(ops0.W, ops0.G[0])};
    for (const auto& p : all_providers()) {
      const auto& cg = dynamic_cast<const CorrectionGradient<1>&>(*p);
      CorrectionOptions<1> opt;
      opt.counting = cg.options().counting;
      if (cg.options().first_step_shepard) opt.reference = &ref;
      const SparseMatrix<> expected =
          apply_correction<1, double>(cg.correction(), d->particles, d->neighbours, ops, opt, &x)[0];
      const Operators<1> own =
          assemble_operators<1, double>(d->particles, d->neighbours, d->kernel, d->h, p->requirements(), &x);
      std::array<SparseMatrix<>, 1> g{own.G[0]};
      p->correct(GradientContext<1, double>{*d, x, own}, g);
      const Eigen::MatrixXd diff = Eigen::MatrixXd(g[0]) - Eigen::MatrixXd(expected);
      EXPECT_LE(max_abs(diff), 1e-13 * max_abs(Eigen::MatrixXd(expected))) << p->name() << " a=" << amplitude;
      if (p->keeps_pattern()) {
        EXPECT_EQ(g[0].nonZeros(), d->neighbours.nonzeros()) << p->name();
      } else {
        EXPECT_EQ(g[0].nonZeros(), static_cast<long>(d->size()) * d->size()) << p->name();
      }
    }
  }
}

TEST(CorrectionGradient, ForcesUseTheCorrectedOperators) {
  // Independent force evaluation from the operator-level correction at the displaced positions:
  // divergence-corrected uncorrected form a_i = sum_j s_j Ghat_ij (plain strain), and strain-corrected plus form
  // s_i = sum_j (u_j - beta u_i) Ghat_ij + T with the plain divergence.
  auto d = line(12, KernelType::CubicSpline, 1.3, 1, 0.1);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.05, 8);
  const double T = 0.2;
  Eigen::VectorXd uall = Eigen::VectorXd::Zero(d->size());
  for (int f = 0; f < d->free_count(); ++f) uall[d->free[f]] = u[f];
  const Positions<1> x = positions(*d, u);
  const Operators<1> ops = assemble_operators<1, double>(d->particles, d->neighbours, d->kernel, d->h,
                                                         {.kernel = true, .gradient = true}, &x);
  const Eigen::MatrixXd G = ops.G[0];
  const Eigen::VectorXd s_plain =
      G * uall - Eigen::VectorXd(G.rowwise().sum()).cwiseProduct(uall) + Eigen::VectorXd::Constant(d->size(), T);
  for (const auto& p : all_providers()) {
    const auto& cg = dynamic_cast<const CorrectionGradient<1>&>(*p);
    const Operators<1> ops0 =
        assemble_operators<1, double>(d->particles, d->neighbours, d->kernel, d->h, {.kernel = true, .gradient = true});
    const std::array<ShepardReference, 1> ref{shepard_reference(ops0.W, ops0.G[0])};
    CorrectionOptions<1> opt;
    opt.counting = cg.options().counting;
    if (cg.options().first_step_shepard) opt.reference = &ref;
    const Eigen::MatrixXd Gh =
        Eigen::MatrixXd(apply_correction<1, double>(cg.correction(), d->particles, d->neighbours, ops, opt, &x)[0]);
    Eigen::VectorXd a, expected(d->dofs());
    WaveForm1D div(d, MomentumForm::Uncorrected, T, p);
    div.acceleration(u, a);
    const Eigen::VectorXd rows = Gh * s_plain;
    for (int f = 0; f < d->free_count(); ++f) expected[f] = rows[d->free[f]];
    EXPECT_LE((a - expected).cwiseAbs().maxCoeff(), 1e-13 * expected.cwiseAbs().maxCoeff()) << p->name();

    WaveForm1D str(d, MomentumForm::Plus, T, p, {.corrected = CorrectedOperator::Strain});
    const double beta = p->preferred_strain_sum() == StrainSum::Difference ? 1.0 : 0.0;
    const Eigen::VectorXd s = Gh * uall - beta * Eigen::VectorXd(Gh.rowwise().sum()).cwiseProduct(uall) +
                              Eigen::VectorXd::Constant(d->size(), T);
    EXPECT_LE((str.stress(u) - s).cwiseAbs().maxCoeff(), 1e-13 * s.cwiseAbs().maxCoeff()) << p->name();
    str.acceleration(u, a);
    for (int f = 0; f < d->free_count(); ++f) {
      const int i = d->free[f];
      expected[f] = G.row(i).dot(s) + s[i] * G.row(i).sum();
    }
    EXPECT_LE((a - expected).cwiseAbs().maxCoeff(), 1e-13 * expected.cwiseAbs().maxCoeff()) << p->name();
  }
}

TEST(CorrectionGradient, JacobianThroughEveryCorrectionMatchesFiniteDifferences) {
  // Complex-step Jacobian (dual numbers inside for the corrected conservative form) vs central differences, and the
  // coloured Jacobian vs the uncoloured one (validates dof_pattern, i.e. the declared reach of each correction).
  auto d = line(10, KernelType::CubicSpline, 1.3, 1, 0.1);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.05, 3);
  const double step = 1e-6;
  for (const auto& p : all_providers())
    for (MomentumForm form : all_momentum_forms())
      for (CorrectedOperator target : {CorrectedOperator::Auto, CorrectedOperator::Both}) {
        if (form == MomentumForm::Conservative && target == CorrectedOperator::Both) continue;  // = Auto
        WaveForm1D force(d, form, 0.15, p, {.corrected = target});
        const Eigen::MatrixXd A = jacobian(force, u);
        const Eigen::MatrixXd dense = ComplexStepJacobian(force, ColouringStrategy::None).compute(u);
        EXPECT_LE(max_abs(A - dense), 1e-13 * max_abs(dense)) << force.name();
        Eigen::MatrixXd fd(force.dofs(), force.dofs());
        for (int k = 0; k < force.dofs(); ++k) {
          Eigen::VectorXd up = u, um = u, ap, am;
          up[k] += step;
          um[k] -= step;
          force.acceleration(up, ap);
          force.acceleration(um, am);
          fd.col(k) = -(ap - am) / (2 * step);
        }
        // central differences: truncation O(step^2) and rounding O(eps / step), about 1e-10 relative here
        EXPECT_LE(max_abs(A - fd), 1e-7 * max_abs(A)) << force.name();
      }
}

TEST(CorrectionGradient, CorrectedConservativeForceIsMinusEnergyGradient) {
  // a = -M^{-1} dU/du with dU/du from complex steps of U itself, and the Jacobian symmetric (Powell Thm 3.8).
  auto d = line(10, KernelType::WendlandC2, 1.5, 1, 0.1);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.05, 5);
  const Eigen::VectorXd m = WaveForm1D(d, MomentumForm::Conservative, 0.0).dof_mass();
  for (const auto& p : all_providers()) {
    WaveForm1D force(d, MomentumForm::Conservative, -0.3, p);
    ASSERT_TRUE(force.strain_corrected()) << p->name();
    Eigen::VectorXd a;
    force.acceleration(u, a);
    const Eigen::VectorXd expected = -test::energy_gradient(force, u).cwiseQuotient(m);
    EXPECT_LE((a - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff()) << p->name();
    EXPECT_LE(relative_asymmetry(jacobian(force, u)), 1e-12) << p->name();
    // complex path = real path
    Eigen::VectorXcd ac;
    force.acceleration(Eigen::VectorXcd(u.cast<std::complex<double>>()), ac);
    EXPECT_LE((ac.real() - a).cwiseAbs().maxCoeff(), 1e-13 * a.cwiseAbs().maxCoeff()) << p->name();
    EXPECT_EQ(ac.imag().cwiseAbs().maxCoeff(), 0.0) << p->name();
  }
}

TEST(CorrectionGradient, NoTensionDependenceForNormalisedKernelsAtEquilibrium) {
  // Powell (3.33): with the minus form or a kernel whose rows sum to zero identically, the divergence of a constant
  // stress is exact and A(T) = A0 (no T dependence); the C_ij form (4.11) likewise (property 2 of ch. 4 §2.1).
  // Fixed layers three supports thick, so that every particle the free ones see has a complete neighbourhood (the
  // "regular grid" of Powell's footnote h).
  auto d = line(16, KernelType::CubicSpline, 1.3, 3);
  const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(d->dofs());
  for (Correction c : {Correction::Minus, Correction::Shepard, Correction::Ncsph, Correction::LocalPolish,
                       Correction::MeanPolish, Correction::ShepardColumnPolish})
    for (MomentumForm form : {MomentumForm::Uncorrected, MomentumForm::Plus}) {
      WaveForm1D force(d, form, 0.0, make_gradient_provider<1>(c));
      const Linearisation split = affine_jacobian(force, u0);
      EXPECT_LE(split.A1.norm(), 1e-13 * split.A0.norm()) << force.name();
    }
  const Linearisation minus = affine_jacobian(WaveForm1D(d, MomentumForm::Minus, 0.0), u0);
  EXPECT_LE(minus.A1.norm(), 1e-13 * minus.A0.norm());
  // ... whereas the plain kernel, the column Shepard divergence (rows do not sum to 0) and the conservative Shepard
  // form (3.59: the columns of the Shepard gradient do not sum to 0) do depend on T.
  for (auto [c, form] : {std::pair{Correction::None, MomentumForm::Uncorrected},
                         std::pair{Correction::ColumnShepard, MomentumForm::Plus},
                         std::pair{Correction::Shepard, MomentumForm::Conservative}}) {
    WaveForm1D force(d, form, 0.0, make_gradient_provider<1>(c));
    const Linearisation split = affine_jacobian(force, u0);
    EXPECT_GE(split.A1.norm(), 0.1 * split.A0.norm()) << force.name();
  }
}

TEST(CorrectionGradient, PolishedConservativeFormsArePositiveDefiniteForAllTensions) {
  // Powell ch. 3 §4.1.1 items 2-4: with the columns (item 2, strain sum_j u_j Ghat_ij) or rows and columns
  // (items 3, 4) of Ghat summing to zero, (3.59) vanishes and A(T) = A0 = J^T J is positive definite for every T.
  for (KernelType type : {KernelType::CubicSpline, KernelType::WendlandC2})
    for (double h : {1.2, 1.7}) {
      auto d = line(14, type, h, 3);
      const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(d->dofs());
      for (Correction c : {Correction::MeanPolish, Correction::ShepardColumnPolish, Correction::ColumnShepard}) {
        WaveForm1D force(d, MomentumForm::Conservative, 0.0, make_gradient_provider<1>(c));
        const Linearisation split = affine_jacobian(force, u0);
        EXPECT_LE(split.A1.norm(), 1e-12 * split.A0.norm()) << force.name();
        for (double T : {-100.0, -1.0, -0.01, 0.0, 0.01, 1.0, 100.0}) {
          const SparseMatrix<> a = split.at(T);
          EXPECT_TRUE(is_positive_definite(lower_triangle(a))) << force.name() << " T=" << T;
        }
      }
      // The plain conservative form is not: it loses definiteness between T = 0 and T = 1 (T_crit ~ 1e-3..1e-1).
      WaveForm1D plain(d, MomentumForm::Conservative, 0.0);
      const Linearisation split = affine_jacobian(plain, u0);
      EXPECT_TRUE(is_positive_definite(lower_triangle(split.at(0.0))));
      EXPECT_FALSE(is_positive_definite(lower_triangle(split.at(1.0)))) << kernel_name(type) << " h=" << h;
    }
}

TEST(CorrectionGradient, MomentumConservationOnPeriodicDisplacedSet) {
  // sum_i V_i a_i = 0 when U is translation invariant (difference strain sum: every correction), but not for
  // Powell's column Shepard kernel with the direct strain sum (ch. 3 §4.1.1 item 2: "it does not conserve momentum").
  auto d = line(15, KernelType::CubicSpline, 1.3, 1, 0.0, true);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.1, 6);
  for (const auto& p : all_providers()) {
    WaveForm1D force(d, MomentumForm::Conservative, 0.2, p);
    Eigen::VectorXd a;
    force.acceleration(u, a);
    const double total = force.dof_mass().dot(a), scale = force.dof_mass().dot(a.cwiseAbs());
    if (p->preferred_strain_sum() == StrainSum::Direct)
      EXPECT_GE(std::abs(total), 1e-3 * scale) << p->name();
    else
      EXPECT_LE(std::abs(total), 1e-13 * scale) << p->name();
  }
}

TEST(CorrectionGradient, DeclaredPropertiesAndBadInput) {
  EXPECT_EQ(CorrectionGradient<1>(Correction::Shepard).dependence_radius(), 1);
  EXPECT_EQ(CorrectionGradient<1>(Correction::LocalPolish).dependence_radius(), 2);
  EXPECT_EQ(CorrectionGradient<1>(Correction::ColumnShepard).dependence_radius(), 2);
  EXPECT_EQ(CorrectionGradient<1>(Correction::MeanPolish).dependence_radius(), kFullReach);
  EXPECT_FALSE(CorrectionGradient<1>(Correction::MeanPolish).keeps_pattern());
  EXPECT_TRUE(CorrectionGradient<1>(Correction::Ncsph).keeps_pattern());
  EXPECT_EQ(CorrectionGradient<1>(Correction::ColumnShepard).preferred_strain_sum(), StrainSum::Direct);
  EXPECT_TRUE(CorrectionGradient<1>(Correction::None).is_plain());
  EXPECT_TRUE(CorrectionGradient<1>(Correction::Shepard).requirements().kernel);
  EXPECT_FALSE(CorrectionGradient<1>(Correction::MeanPolish).requirements().kernel);
  EXPECT_EQ(CorrectionGradient<1>(Correction::LocalPolish, {.counting = NeighbourCounting::BoundaryLevel}).name(),
            "local-polish+fig4.3");
  EXPECT_THROW(CorrectionGradient<1>(Correction::Shepard, {.first_step_shepard = true}), std::invalid_argument);
  EXPECT_THROW(CorrectionGradient<1>(Correction::LocalPolish, {.polish_free_only = true}), std::invalid_argument);
  EXPECT_THROW(CorrectionGradient<1>(Correction::Ncsph, {.min_rcond = 2.0}), std::invalid_argument);
  auto d = line(8, KernelType::CubicSpline, 1.3);
  auto shepard = make_gradient_provider<1>(Correction::Shepard);
  EXPECT_THROW(WaveForm1D(d, MomentumForm::Conservative, 0.1, shepard, {.corrected = CorrectedOperator::Divergence}),
               std::invalid_argument);
  EXPECT_EQ(WaveForm1D(d, MomentumForm::Plus, 0.1, shepard).name(), "wave1d/plus/T=0.1/shepard@divergence");
  EXPECT_EQ(WaveForm1D(d, MomentumForm::Conservative, 0.1, make_gradient_provider<1>(Correction::ColumnShepard)).name(),
            "wave1d/conservative/T=0.1/column-shepard@strain(direct)");
  EXPECT_EQ(parse_corrected_operator("both"), CorrectedOperator::Both);
  EXPECT_THROW(parse_corrected_operator("momentum"), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
