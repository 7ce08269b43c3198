// The one isotropic elastic material (models/elastic_material.hpp): the conversions E, nu <-> lambda, mu <-> K, mu
// against closed-form values, the given constant kept bit-exact (what keeps every form's results unchanged), the wave
// speeds, and the one-line validation errors.
#include "sphstab/models/elastic_material.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>

namespace sphstab {
namespace elastic_material_test {

// lambda = 3, mu = 1.5: K = 3 + 1 = 4, E = 1.5 * 12 / 4.5 = 4, nu = 3 / 9 = 1/3, lambda + 2 mu = 6: all exact in
// binary but nu, so the identities below are checked to the last bit where the arithmetic is exact.
TEST(ElasticMaterial, ConversionsAgreeWithTheClosedForms) {
  const ElasticMaterial m = ElasticMaterial::from_lame(3.0, 1.5, 2.0);
  EXPECT_EQ(m.lambda(), 3.0);
  EXPECT_EQ(m.mu(), 1.5);
  EXPECT_EQ(m.bulk_modulus(), 4.0);
  EXPECT_EQ(m.density(), 2.0);
  EXPECT_EQ(m.young(), 4.0);
  EXPECT_NEAR(m.poisson(), 1.0 / 3.0, 1e-16);
  EXPECT_EQ(m.uniaxial_modulus(UniaxialState::Strain), 6.0);
  EXPECT_EQ(m.uniaxial_modulus(UniaxialState::Stress), 4.0);
  EXPECT_EQ(m.sound_speed(), std::sqrt(2.0));   // sqrt(K / rho0) = sqrt(4 / 2)
  EXPECT_EQ(m.p_wave_speed(), std::sqrt(3.0));  // sqrt((4 + 2) / 2)
  EXPECT_EQ(m.p_wave_speed(), std::sqrt(m.uniaxial_modulus(UniaxialState::Strain) / m.density()));

  // The same material from (K, mu) and from (E, nu): a second route to the same constants.
  const ElasticMaterial k = ElasticMaterial::from_bulk_shear(4.0, 1.5, 2.0);
  EXPECT_EQ(k.lambda(), 3.0);
  EXPECT_EQ(k.bulk_modulus(), 4.0);
  const ElasticMaterial e = ElasticMaterial::from_young_poisson(4.0, 1.0 / 3.0, 2.0);
  EXPECT_NEAR(e.lambda(), 3.0, 1e-14);
  EXPECT_NEAR(e.mu(), 1.5, 1e-15);
  EXPECT_NEAR(e.bulk_modulus(), 4.0, 1e-14);
  EXPECT_NEAR(e.young(), 4.0, 1e-14);
  EXPECT_NEAR(e.poisson(), 1.0 / 3.0, 1e-15);
}

// Powell's steel (E = 2.1, nu = 0.3): lambda = 0.63 / 0.52, mu = 2.1 / 2.6, K = 2.1 / 1.2, each in the operation order
// the elastic forms (lambda) and the rate form (K) have always used, so both see the doubles they saw before.
TEST(ElasticMaterial, YoungPoissonComputesEachConstantDirectly) {
  const double E = 2.1, nu = 0.3;
  const ElasticMaterial m = ElasticMaterial::from_young_poisson(E, nu, 7.8);
  EXPECT_EQ(m.lambda(), E * nu / ((1 + nu) * (1 - 2 * nu)));
  EXPECT_EQ(m.mu(), E / (2 * (1 + nu)));
  EXPECT_EQ(m.bulk_modulus(), E / (3 * (1 - 2 * nu)));
  EXPECT_EQ(m.density(), 7.8);
  EXPECT_NEAR(m.lambda(), 1.2115384615384615, 1e-15);
  EXPECT_NEAR(m.mu(), 0.8076923076923077, 1e-15);
  EXPECT_NEAR(m.bulk_modulus(), 1.75, 1e-15);
  EXPECT_NEAR(m.young(), E, 1e-15);
  EXPECT_NEAR(m.poisson(), nu, 1e-15);
  EXPECT_NEAR(m.bulk_modulus(), m.lambda() + 2 * m.mu() / 3, 1e-15);
}

// The constant given is kept bit for bit and the other derived once. Recomputing the given one from the derived one
// would round: the count below shows that it does for ordinary values, which is why both are stored.
TEST(ElasticMaterial, TheGivenConstantIsKeptBitExact) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.1, 10.0);
  int round_trip_differs = 0;
  for (int i = 0; i < 1000; ++i) {
    const double a = u(rng), mu = u(rng);  // the named constructors do not validate: any sign of lambda
    const ElasticMaterial from_k = ElasticMaterial::from_bulk_shear(a, mu, 1.0);
    ASSERT_EQ(from_k.bulk_modulus(), a);
    ASSERT_EQ(from_k.mu(), mu);
    ASSERT_EQ(from_k.lambda(), a - 2 * mu / 3);
    const ElasticMaterial from_lame = ElasticMaterial::from_lame(a, mu, 1.0);
    ASSERT_EQ(from_lame.lambda(), a);
    ASSERT_EQ(from_lame.bulk_modulus(), a + 2 * mu / 3);
    round_trip_differs += ElasticMaterial::from_lame(from_k.lambda(), mu, 1.0).bulk_modulus() != a;
  }
  EXPECT_GT(round_trip_differs, 50);  // about one in eight
}

/// Runs f, expects std::invalid_argument with a one-line message starting "who:" and containing `what`.
void expect_error(const std::function<void()>& f, const std::string& who, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected " << what;
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(who + ":", 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(ElasticMaterial, ValidationNamesTheProblemOnOneLine) {
  const auto check = [](double l, double mu, double rho, ShearModulusRule r = ShearModulusRule::Positive) {
    return [=] { ElasticMaterial::from_lame(l, mu, rho).validate("caller", r); };
  };
  expect_error(check(1, 0, 1), "caller", "shear modulus mu must be > 0 (got 0)");
  expect_error(check(1, -0.5, 1, ShearModulusRule::NonNegative), "caller", "shear modulus mu must be >= 0");
  expect_error(check(-2, 1, 1), "caller", "bulk modulus K = -1.333");
  expect_error(check(-2, 1, 1), "caller", "outside (-1, 0.5)");
  expect_error(check(1, 1, 0), "caller", "density must be > 0 (got 0)");
  expect_error(check(NAN, 1, 1), "caller", "must be finite");
  expect_error(check(1, INFINITY, 1), "caller", "must be finite");
  expect_error([] { ElasticMaterial::from_bulk_shear(0, 0, 1).validate("caller", ShearModulusRule::NonNegative); },
               "caller", "bulk modulus K = 0");
  // A fluid (mu = 0) passes only where the caller allows it (the rate form); valid solids pass either way.
  EXPECT_NO_THROW(ElasticMaterial::from_bulk_shear(2.1, 0, 7.8).validate("caller", ShearModulusRule::NonNegative));
  EXPECT_NO_THROW(check(1.2, 0.8, 7.8)());
  EXPECT_NO_THROW(check(-0.5, 0.8, 7.8)());  // nu = -0.5 / 0.6 < 0 but > -1: K > 0

  expect_error([] { ElasticMaterial::from_young_poisson(0, 0.3, 1); }, "ElasticMaterial", "Young's modulus");
  expect_error([] { ElasticMaterial::from_young_poisson(1, 0.5, 1); }, "ElasticMaterial", "Poisson's ratio");
  expect_error([] { ElasticMaterial::from_young_poisson(1, -1, 1); }, "ElasticMaterial", "Poisson's ratio");
  expect_error([] { ElasticMaterial::from_young_poisson(1, 0.3, -7.8); }, "ElasticMaterial", "density");
  expect_error([] { ElasticMaterial::from_young_poisson(NAN, 0.3, 1); }, "ElasticMaterial", "Young's modulus");
}

}  // namespace elastic_material_test
}  // namespace sphstab
