// The [Ganzenmueller2015] hourglass term in VariationalTotalLagrangian (forms/hourglass_control.hpp, shared with
// FiniteStrainTotalLagrangian): with the plain gradient the variational form equals FiniteStrainTotalLagrangian
// (difference strain, Plus divergence) with the same term, at c_HG = 0 and > 0, at a random state of a perturbed
// block (two assemblies of the same force, agreeing to round-off); coefficient 0 = no term; the term makes the form
// non-conservative; bad coefficients are rejected.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "forms_fixture.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/forms/variational_total_lagrangian.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"

namespace sphstab {
namespace variational_hourglass_test {

constexpr double kRho = 3.1;
const ElasticMaterial kLame = ElasticMaterial::from_lame(1.7, 0.6, kRho);

std::shared_ptr<const Discretisation<2>> block() {
  return test::lattice_discretisation<2>({.n = 6, .perturbation = 0.15, .seed = 5});
}

TEST(VariationalHourglass, PlainGradientEqualsTheFiniteStrainFormWithTheSameTerm) {
  const auto d = block();
  auto svk = std::make_shared<StVenantKirchhoff<2>>(kLame);
  const Eigen::VectorXd u = test::random_vector(d->dofs(), 0.02, 3);
  for (double c : {0.0, 0.05, 0.7})
    for (HourglassProjection p : {HourglassProjection::Bond, HourglassProjection::Full}) {
      VariationalTotalLagrangian<2> v(d, svk, kRho, nullptr, {.coefficient = c, .projection = p});
      FiniteStrainTotalLagrangian<2> f(d, svk, kRho, {.hourglass = c, .hourglass_projection = p});
      Eigen::VectorXd av, af;
      v.acceleration(u, av);
      f.acceleration(u, af);
      // same force, two assemblies (transposed K versus G_ij with equal volumes): round-off only
      EXPECT_LE((av - af).cwiseAbs().maxCoeff(), 1e-12 * af.cwiseAbs().maxCoeff()) << "c_HG = " << c;
      EXPECT_EQ(v.conservative(), c == 0);
    }
}

TEST(VariationalHourglass, TermIsLinearInTheCoefficientAndZeroAtZero) {
  const auto d = block();
  auto svk = std::make_shared<StVenantKirchhoff<2>>(kLame);
  const auto ncsph = make_gradient_provider<2>(Correction::Ncsph);
  const Eigen::VectorXd u = test::random_vector(d->dofs(), 0.02, 9);
  VariationalTotalLagrangian<2> off(d, svk, kRho, ncsph), zero(d, svk, kRho, ncsph, {.coefficient = 0});
  VariationalTotalLagrangian<2> one(d, svk, kRho, ncsph, {.coefficient = 1}),
      third(d, svk, kRho, ncsph, {.coefficient = 0.3});
  Eigen::VectorXd a0, az, a1, a3;
  off.acceleration(u, a0);
  zero.acceleration(u, az);
  one.acceleration(u, a1);
  third.acceleration(u, a3);
  EXPECT_EQ((a0 - az).cwiseAbs().maxCoeff(), 0.0);  // c_HG = 0 is exactly the form without the term
  const double scale = (a1 - a0).cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0);  // a random state is not affine: the term acts
  EXPECT_LE(((a3 - a0) - 0.3 * (a1 - a0)).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_NE(one.name().find("hourglass-1"), std::string::npos) << one.name();
}

TEST(VariationalHourglass, RejectsNegativeOrNonFiniteCoefficient) {
  const auto d = block();
  auto svk = std::make_shared<StVenantKirchhoff<2>>(kLame);
  EXPECT_THROW(VariationalTotalLagrangian<2>(d, svk, kRho, nullptr, {.coefficient = -0.1}), std::invalid_argument);
  EXPECT_THROW(
      VariationalTotalLagrangian<2>(d, svk, kRho, nullptr, {.coefficient = std::numeric_limits<double>::infinity()}),
      std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
