#include "sphstab/stability/rate_form_critical_stress.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace sphstab {
namespace rate_form_critical_stress_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_bulk_shear(1.0, 0.3, 1.0);  // M = 1.4

TEST(RateFormCriticalStress, OneDimensionalSphIsThePlusFormWithTheDensityCoupling) {
  // At rest, 1D plain SPH linearises to rho u'' = -((M + sigma0) K_plus - 2 sigma0 L) u (header note), so
  // sigma0_crit / M = T_plus / (1 - T_plus) with T_plus of the §3.3 plus form (Powell 3.40, n = 2), an independent
  // route (analytic Jacobian, CHOLMOD and dsygv), in both directions.
  for (KernelType type : {KernelType::CubicSpline, KernelType::QuinticSpline})
    for (double h : {1.2, 1.5}) {
      const Kernel<1> kernel(type);
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, 30);
      const auto disc = make_discretisation(set, kernel, h);
      for (LoadDirection dir : {LoadDirection::Tension, LoadDirection::Compression}) {
        const CriticalLoad plus =
            critical_tension_1d(set, kernel, h, MomentumForm::Plus, CriticalLoadOptions::tension_1d(), dir);
        const RateFormCriticalStress r =
            rate_form_critical_stress<1>(disc, kMaterial, {}, {.direction = dir, .max = 0.7});
        ASSERT_EQ(r.status, Status::Successful) << r.reason;
        const double expected = plus.load / (1 - plus.load);
        if (std::isinf(plus.load) || std::abs(expected) > 0.7 * 0.999) {
          EXPECT_TRUE(std::isinf(r.stress_over_modulus)) << r.stress_over_modulus << " vs " << expected;
        } else {
          EXPECT_NEAR(r.stress_over_modulus, expected, 1e-6 * std::abs(expected))
              << kernel_name(type) << " h " << h << " " << load_direction_name(dir);
          EXPECT_GT(r.growth_above, 0);
          EXPECT_NEAR(r.xi, 1 / (1 - r.stress / kMaterial.bulk_modulus()), 1e-12);
        }
      }
    }
}

TEST(RateFormCriticalStress, NcsphRowFormIsStableBothWays) {
  // NCSPH rows sum to zero: no initial-stress term, and the density couplings of (1.36) leave the modulus M - sigma0
  // > 0 for every sigma0 < K < M: stable in tension up to xi -> inf and in compression.
  const Kernel<1> kernel(KernelType::CubicSpline);
  const auto disc = make_discretisation(tension_lattice_1d(kernel, 1.3, 20, false, 3), kernel, 1.3);
  for (LoadDirection dir : {LoadDirection::Tension, LoadDirection::Compression}) {
    const RateFormCriticalStress r = rate_form_critical_stress<1>(
        disc, kMaterial, {.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph},
        {.direction = dir, .max = 2.0});
    ASSERT_EQ(r.status, Status::Successful) << r.reason;
    EXPECT_TRUE(std::isinf(r.stress_over_modulus)) << load_direction_name(dir) << " " << r.stress_over_modulus;
  }
  EXPECT_THROW(rate_form_critical_stress<1>(nullptr, kMaterial, {}), std::invalid_argument);
  EXPECT_THROW(rate_form_critical_stress<1>(disc, kMaterial, {}, {.step = 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
