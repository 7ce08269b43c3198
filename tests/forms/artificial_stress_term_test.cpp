#include "sphstab/forms/artificial_stress_term.hpp"

#include <gtest/gtest.h>

#include <random>

#include "forms_fixture.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace artificial_stress_term_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2, 0.8, 7.8);

std::shared_ptr<const Discretisation<2>> block(int n) { return test::lattice_discretisation<2>({.n = n}); }

using test::random_vector;

TEST(ArtificialStressTerm, EquilibriumAndCompressionLimit) {
  auto d = block(7);
  Eigen::VectorXd a, b;
  for (double xi : {1.04, 0.96}) {
    auto f = make_artificial_stress_sph(d, kMaterial, PreStrain::from_area_ratio(xi));
    f->acceleration(Eigen::VectorXd::Zero(f->dofs()), a);
    EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-14) << xi;  // uniform R, complete neighbourhoods
  }
  // Uniform compression with a small perturbation: every principal stress negative, R = 0, basic SPH exactly.
  auto gms = make_artificial_stress_sph(d, kMaterial, PreStrain::from_area_ratio(0.96));
  ElasticForm2D plus(d, kMaterial, MomentumForm::Plus, PreStrain::from_area_ratio(0.96));
  const Eigen::VectorXd u = random_vector(plus.dofs(), 1e-4, 3);
  gms->acceleration(u, a);
  plus.acceleration(u, b);
  EXPECT_EQ((a - b).cwiseAbs().maxCoeff(), 0.0);
  // In tension the term is active and repulsive: it changes the force.
  auto gms_t = make_artificial_stress_sph(d, kMaterial, PreStrain::from_area_ratio(1.04));
  ElasticForm2D plus_t(d, kMaterial, MomentumForm::Plus, PreStrain::from_area_ratio(1.04));
  gms_t->acceleration(u, a);
  plus_t.acceleration(u, b);
  EXPECT_GT((a - b).cwiseAbs().maxCoeff(), 1e-3 * b.cwiseAbs().maxCoeff());
}

TEST(ArtificialStressTerm, ComplexStepMatchesFiniteDifferences) {
  auto d = block(5);
  auto f = make_artificial_stress_sph(d, kMaterial, PreStrain::from_area_ratio(1.03));
  const Eigen::VectorXd u = random_vector(f->dofs(), 1e-3, 9);
  const Eigen::MatrixXd J(jacobian(*f, u));
  const double h = 1e-6;
  double worst = 0;
  for (int k = 0; k < f->dofs(); k += 2) {
    Eigen::VectorXd up = u, um = u, ap, am;
    up[k] += h;
    um[k] -= h;
    f->acceleration(up, ap);
    f->acceleration(um, am);
    worst = std::max(worst, (-(ap - am) / (2 * h) - J.col(k)).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-7 * J.cwiseAbs().maxCoeff());  // central-difference accuracy
}

TEST(ArtificialStressTerm, BadInput) {
  auto d = block(4);
  EXPECT_THROW(ArtificialStressTerm(nullptr), std::invalid_argument);
  EXPECT_THROW(ArtificialStressTerm(d, {.epsilon = -0.1}), std::invalid_argument);
  EXPECT_THROW(ArtificialStressTerm(d, {.epsilon = 0.3, .exponent = -1}), std::invalid_argument);
  EXPECT_THROW(ArtificialStressTerm(d, {}, 10.0), std::invalid_argument);  // dp beyond the support
}

}  // namespace
}  // namespace sphstab
