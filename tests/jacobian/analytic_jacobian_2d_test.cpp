// The closed-form 2D Jacobian A(e) = A0 + e A1 against the coloured complex-step Jacobian of the force function
// itself (affine_jacobian): two independent derivations of the same derivative.
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>

#include "sphstab/forms/artificial_stress_term.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace analytic_jacobian_2d_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

std::shared_ptr<const Discretisation<2>> lattice(LatticeType type, int n, KernelType kernel, double h,
                                                 bool periodic = false, double perturbation = 0) {
  Kernel<2> k(kernel);
  auto set = make_lattice<2>(
      type, n,
      {.spacing = 1.0, .support_radius = k.support_radius(h), .periodic = periodic, .perturbation = perturbation});
  return make_discretisation(set, k, h);
}

/// max |A - B| / max |B| over dense copies.
double relative_max_difference(const SparseMatrix<>& a, const SparseMatrix<>& b) {
  const Eigen::MatrixXd da(a), db(b);
  return (da - db).cwiseAbs().maxCoeff() / db.cwiseAbs().maxCoeff();
}

struct Case {
  LatticeType lattice;
  KernelType kernel;
  double h;
};

TEST(AnalyticJacobian2D, MatchesComplexStepOnLattices) {
  const std::vector<Case> cases = {
      {LatticeType::Square, KernelType::CubicSpline, 1.0},   {LatticeType::Square, KernelType::WendlandC2, 1.3},
      {LatticeType::Square, KernelType::QuinticSpline, 1.7}, {LatticeType::Hexagonal, KernelType::CubicSpline, 1.2},
      {LatticeType::Hexagonal, KernelType::WendlandC4, 1.5}, {LatticeType::Hexagonal, KernelType::QuinticSpline, 2.1}};
  double worst = 0;
  for (const Case& c : cases)
    for (bool periodic : {false, true}) {
      // periodic: the box must hold twice the support (even n for hex)
      const int n = periodic ? 2 * static_cast<int>(std::ceil(2 * c.h + 0.5)) : 5;
      auto d = lattice(c.lattice, n, c.kernel, c.h, periodic);
      for (MomentumForm form : all_momentum_forms())
        for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
          ElasticForm2D force(d, kMaterial, form, {kind, 0.0});
          const Linearisation cs = affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
          const Linearisation an = analytic_jacobian_2d(force);
          const std::string what = lattice_name(c.lattice) + " " + kernel_name(c.kernel) + " h=" + std::to_string(c.h) +
                                   " " + force.name() + (periodic ? " periodic" : "");
          // Complex step is exact to round-off; both sides sum O(100) terms of size max|A|.
          EXPECT_LE(relative_max_difference(an.A0, cs.A0), 1e-10) << what;
          worst = std::max(worst, relative_max_difference(an.A0, cs.A0));
          if (form != MomentumForm::Minus) worst = std::max(worst, relative_max_difference(an.A1, cs.A1));
          if (form == MomentumForm::Minus) {
            EXPECT_EQ(an.A1.cwiseAbs().sum(), 0.0) << what;
            EXPECT_LE(Eigen::MatrixXd(cs.A1).cwiseAbs().maxCoeff(),
                      1e-12 * Eigen::MatrixXd(cs.A0).cwiseAbs().maxCoeff())
                << what;
          } else {
            EXPECT_LE(relative_max_difference(an.A1, cs.A1), 1e-10) << what;
          }
          EXPECT_TRUE(an.complete) << what;
          const bool symmetric =
              form == MomentumForm::Conservative || form == MomentumForm::Minus || kind == PreStrainKind::Isotropic;
          EXPECT_EQ(an.symmetric, symmetric) << what;
          const double asym = relative_asymmetry(an.at(0.01));
          if (symmetric)
            EXPECT_LE(asym, 1e-13) << what;
          else
            EXPECT_GT(asym, 1e-6) << what;  // uniaxial plus/uncorrected: s0 L is not symmetric
        }
    }
  std::cout << "largest relative difference analytic vs complex step: " << worst << "\n";
}

TEST(AnalyticJacobian2D, MatchesComplexStepOffLattice) {
  // Perturbed positions and unequal volumes: no lattice identity helps; the closed form holds for any set at rest.
  Kernel<2> k(KernelType::WendlandC2);
  auto set = make_lattice<2>(LatticeType::Square, 5, {.spacing = 1.0, .support_radius = 2.8, .perturbation = 0.1});
  for (int i = 0; i < set.size(); i += 3) set.volume[i] *= 1.2;
  auto d = make_discretisation(set, k, 1.4);
  for (MomentumForm form : all_momentum_forms())
    for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
      ElasticForm2D force(d, kMaterial, form, {kind, 0.0});
      const Linearisation cs = affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
      const Linearisation an = analytic_jacobian_2d(force);
      EXPECT_LE(relative_max_difference(an.A0, cs.A0), 1e-10) << force.name();
      if (form != MomentumForm::Minus) EXPECT_LE(relative_max_difference(an.A1, cs.A1), 1e-10) << force.name();
      EXPECT_FALSE(an.symmetric) << force.name();
    }
}

TEST(AnalyticJacobian2D, LatticeIdentities) {
  auto d = lattice(LatticeType::Square, 6, KernelType::CubicSpline, 1.3);
  const auto cons = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const auto plus = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic);
  const auto unc = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Uncorrected, PreStrainKind::UniaxialX);
  const auto plus_u = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Plus, PreStrainKind::UniaxialX);
  const auto minus = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Minus, PreStrainKind::UniaxialX);
  const Eigen::MatrixXd a0(cons.A0);
  // Complete neighbourhoods: the same A0 for every form (to round-off of the row sums g_i ~ 1e-16).
  for (const auto* j : {&plus, &unc, &minus}) EXPECT_LE((Eigen::MatrixXd(j->A0) - a0).cwiseAbs().maxCoeff(), 1e-14);
  // Isotropic: conservative A1 = 2 x plus A1 (1D ratio n = 4 : 2); plus A1 = 2 x uncorrected A1 for any pre-strain.
  EXPECT_LE((Eigen::MatrixXd(cons.A1) - 2 * Eigen::MatrixXd(plus.A1)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((Eigen::MatrixXd(plus_u.A1) - 2 * Eigen::MatrixXd(unc.A1)).cwiseAbs().maxCoeff(), 1e-15);
  // A0 is symmetric positive definite with fixed layers (smallest eigenvalue well above round-off).
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (a0 + a0.transpose()));
  EXPECT_GT(es.eigenvalues()[0], 1e-6 * es.eigenvalues().maxCoeff());
}

TEST(AnalyticJacobian2D, TranslationIsNullOnPeriodicSets) {
  for (LatticeType type : {LatticeType::Square, LatticeType::Hexagonal}) {
    auto d = lattice(type, 10, KernelType::QuinticSpline, 1.6, true);
    for (MomentumForm form : all_momentum_forms())
      for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
        const auto j = analytic_jacobian_2d(*d, kMaterial, form, kind);
        const SparseMatrix<> a = j.at(0.3);
        for (int c = 0; c < 2; ++c) {
          Eigen::VectorXd t = Eigen::VectorXd::Zero(j.dofs());
          for (int f = 0; f < d->free_count(); ++f) t[2 * f + c] = 1.0;
          // Row sums of O(50) terms of size max|A|: round-off only.
          EXPECT_LE((a * t).cwiseAbs().maxCoeff(), 1e-13 * a.coeffs().cwiseAbs().maxCoeff())
              << lattice_name(type) << " " << momentum_form_name(form);
        }
      }
  }
}

TEST(AnalyticJacobian2D, RejectsWhatTheClosedFormDoesNotCover) {
  auto d = lattice(LatticeType::Square, 4, KernelType::CubicSpline, 1.2);
  ElasticForm2D minus_gradient(d, kMaterial, MomentumForm::Uncorrected, {}, std::make_shared<MinusGradient<2>>());
  EXPECT_THROW(analytic_jacobian_2d(minus_gradient), std::invalid_argument);
  ElasticForm2D clamped(d, kMaterial, MomentumForm::Plus);
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(2 * (d->size() - d->free_count()));
  fixed[0] = 0.01;
  clamped.set_fixed_displacement(fixed);
  EXPECT_THROW(analytic_jacobian_2d(clamped), std::invalid_argument);
  ElasticForm2D with_term(d, kMaterial, MomentumForm::Plus);
  with_term.add_term(std::make_shared<ArtificialStressTerm>(d));
  EXPECT_THROW(analytic_jacobian_2d(with_term), std::invalid_argument);
  EXPECT_THROW(
      analytic_jacobian_2d(*d, ElasticMaterial::from_lame(1, -1, 1), MomentumForm::Plus, PreStrainKind::Isotropic),
      std::invalid_argument);
  Operators<2> no_hessian = assemble_operators<2>(d->particles, d->neighbours, d->kernel, d->h, {});
  EXPECT_THROW(analytic_jacobian_2d(*d, no_hessian, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic),
               std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
