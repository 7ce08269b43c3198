// The rate-form Swegle block as a Scene (problems/rate_form_block.hpp): the uniform state is an equilibrium of every
// formulation with its fixed-layer thickness, the kick sits on the centre particle (block) or is the shortest sine
// the box holds (periodic), and bad options are refused.
#include <gtest/gtest.h>

#include <cmath>

#include "sphstab/problems/rate_form_block.hpp"

namespace sphstab {
namespace rate_form_block_test {

TEST(RateFormBlock, UniformStateIsAnEquilibriumOfEveryFormulation) {
  const std::vector<RateFormOptions> forms = {
      {},
      {.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph,
       .momentum = RateFormMomentum::Antisymmetric},
      {.momentum = RateFormMomentum::Cij},
      {.momentum = RateFormMomentum::StabilisedSph},
      {.momentum = RateFormMomentum::StabilisedSph, .counting = NeighbourCounting::BoundaryLevel,
       .first_step_shepard = true}};
  for (const RateFormOptions& o : forms) {
    const Scene<2> s = rate_form_block_scene<2>({.n = 7, .xi = 1.02, .scheme = o, .kick = 0.0});
    Eigen::VectorXd f;
    s.scheme->rate(s.y0, f);
    // Accelerations of a pre-stressed block (sigma ~ K (1/xi - 1) ~ 3e-2): zero to rounding, relative to the scale of
    // one pair's force sigma / (rho dx).
    const double scale = 0.04 / (7.8 * 0.01);
    EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-11 * scale) << s.scheme->name();
    const int layers = rate_form_layer_supports(o);
    EXPECT_EQ(s.scheme->discretisation().size(),
              static_cast<int>(std::pow(7 + 2 * fixed_layers_needed(layers * 2.6 * 0.01, 0.01), 2)))
        << s.scheme->name();
  }
}

TEST(RateFormBlock, KickOnTheCentreParticleOrTheShortestSine) {
  const Scene<2> b = rate_form_block_scene<2>({.n = 9, .kick = 2e-3});
  const RateFormScheme<2>& scheme = *b.scheme;
  int kicked = -1, count = 0;
  for (int i = 0; i < scheme.discretisation().size(); ++i)
    if (scheme.velocity_offset(i) >= 0 && b.y0.segment<2>(scheme.velocity_offset(i)).norm() > 0) kicked = i, ++count;
  ASSERT_EQ(count, 1);
  EXPECT_EQ(b.y0[scheme.velocity_offset(kicked)], 2e-3);
  const auto& x = scheme.discretisation().particles.x;
  EXPECT_NEAR(x(kicked, 0), 4.5 * 0.01, 1e-15);  // the middle of the 9 x 9 free block [0, 9 dx]^2
  EXPECT_NEAR(x(kicked, 1), 4.5 * 0.01, 1e-15);
  EXPECT_EQ(b.name, "swegle-block");

  // Periodic 1D lattice of 16: m = 8, the sawtooth +-V0.
  const Scene<1> p = rate_form_block_scene<1>({.lattice = LatticeType::Line, .n = 16, .periodic = true, .kick = 1.0});
  for (int i = 0; i < 16; ++i) {
    const double v = p.y0[p.scheme->velocity_offset(i)];
    EXPECT_NEAR(v, std::sin(M_PI * (i + 0.5)), 1e-12) << i;
  }
  EXPECT_EQ(p.name, "periodic-lattice");
}

TEST(RateFormBlock, BadOptionsAreRefused) {
  EXPECT_THROW(rate_form_block_scene<2>({.xi = 0}), std::invalid_argument);
  EXPECT_THROW(rate_form_block_scene<2>({.xi = NAN}), std::invalid_argument);
  EXPECT_THROW(rate_form_block_scene<1>({.lattice = LatticeType::Square}), std::invalid_argument);
  EXPECT_THROW(rate_form_block_scene<2>({.lattice = LatticeType::Line}), std::invalid_argument);
  EXPECT_THROW(rate_form_block_scene<2>({.n = 0}), std::invalid_argument);
}

}  // namespace rate_form_block_test
}  // namespace sphstab
