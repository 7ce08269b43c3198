// The GMS scenes as Scenes (problems/gms_scenes.hpp): each is its geometry (cantilever_plate, colliding_rings,
// plastic_slab) under GMS's scheme at the stated initial state, with its run length and measures.
#include "sphstab/problems/gms_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/forms/rate_form_state.hpp"

namespace sphstab {
namespace gms_scenes_test {

TEST(GmsScenes, RingsMoveTowardsEachOtherAndAreOneFragmentEach) {
  const CollidingRingsOptions geometry{.spacing = 0.2, .speed = 0.059};
  const Scene<2> s = gms_rings_scene(geometry);
  const CollidingRings r = make_colliding_rings(geometry);
  ASSERT_EQ(s.scheme->discretisation().size(), r.size());
  EXPECT_EQ(s.spacing, 0.2);
  EXPECT_DOUBLE_EQ(s.scheme->discretisation().h, 0.3);  // 1.5 dp
  EXPECT_EQ(s.t_end, 100);
  EXPECT_TRUE(std::isinf(s.yield_stress));
  EXPECT_DOUBLE_EQ(s.neighbour_skin, 0.1);
  for (int i = 0; i < r.size(); ++i) {
    EXPECT_EQ(s.y0[s.scheme->velocity_offset(i)], r.ring[i] == 0 ? 0.059 : -0.059) << i;
    EXPECT_EQ(s.y0[s.scheme->velocity_offset(i) + 1], 0.0) << i;
  }
  // Kinetic energy 1/2 sum m v^2 with m = rho0 dp^2.
  EXPECT_NEAR(s.scheme->kinetic_energy(s.y0), 0.5 * r.size() * 0.04 * 0.059 * 0.059, 1e-15);
  const Eigen::Matrix2Xd x = rate_form_positions(*s.scheme, s.y0);
  EXPECT_EQ(s.measure("ring_fragments").value(x, s.y0), 1.0);
  Eigen::Matrix2Xd torn = x;
  torn.col(0) += Eigen::Vector2d(0, -10);  // one particle of ring 0 far away: two fragments
  EXPECT_EQ(s.measures.front().value(torn, s.y0), 2.0);
  // GMS's scheme: the options of gms_scheme_options(0.3).
  const RateFormOptions& o = s.scheme->options();
  EXPECT_EQ(o.artificial_stress, 0.3);
  EXPECT_EQ(o.xsph, 0.5);
  EXPECT_EQ(o.viscosity, ViscositySwitch::Compression);
  EXPECT_EQ(o.continuity, ContinuityForm::Divergence);
  EXPECT_EQ(gms_scheme_options(0.3, 0, 0).viscosity, ViscositySwitch::Off);
  EXPECT_EQ(o.pair_loop, PairLoop::Pairs);  // the fast loop where it applies (issue 35)
}

TEST(GmsScenes, PlateStartsInItsFirstModeAndMeasuresTheTipDeflection) {
  const CantileverPlateOptions geometry{.length = 10, .thickness = 2, .across = 4};
  const Scene<2> s = gms_plate_scene(geometry, 0.02, {.material = ElasticMaterial::from_bulk_shear(1, 0.3, 1)});
  const ParticleSet<2>& p = s.scheme->discretisation().particles;
  int tip = 0;
  for (int i = 0; i < p.size(); ++i) {
    const double vy = s.y0[s.scheme->velocity_offset(i) + 1];
    if (p.role[i] == Role::Free) {
      EXPECT_DOUBLE_EQ(vy, cantilever_mode_velocity(p.x(i, 0), 10, 0.02)) << i;
      tip += p.x(i, 0) > 10 - s.spacing;
    }
  }
  ASSERT_EQ(tip, 4);  // the last column
  const IsotropicModuli m = isotropic_moduli(1, 0.3);
  EXPECT_DOUBLE_EQ(s.t_end, 1.25 * thin_plate_period(m.youngs, m.poisson, 1, 2, 10));
  Eigen::Matrix2Xd x = rate_form_positions(*s.scheme, s.y0);
  EXPECT_EQ(s.measure("tip_deflection").value(x, s.y0), 0.0);
  for (int i = 0; i < p.size(); ++i)
    if (p.x(i, 0) > 10 - s.spacing) x(1, i) += 0.25;
  EXPECT_DOUBLE_EQ(s.measure("tip_deflection").value(x, s.y0), 0.25);
  EXPECT_DOUBLE_EQ(s.time_step(0.5), 0.5 * s.scheme->discretisation().h / s.scheme->material().p_wave_speed());
}

TEST(GmsScenes, SlabDrivesItsEndZonesAndYields) {
  const PlasticSlabOptions geometry{.spacing = 0.05};
  const Scene<2> s = gms_slab_scene(geometry, 0.03);
  const PlasticSlab slab = make_plastic_slab(geometry);
  EXPECT_EQ(s.scheme->driven_particles(), slab.driven);
  ASSERT_EQ(s.scheme->driven_accelerations().size(), slab.driven.size());
  for (std::size_t k = 0; k < slab.driven.size(); ++k)
    EXPECT_EQ(s.scheme->driven_accelerations()[k], slab.driven_acceleration.col(k)) << k;
  EXPECT_EQ(s.yield_stress, 0.03);
  EXPECT_EQ(s.t_end, 200);
  EXPECT_EQ(s.scheme->kinetic_energy(s.y0), 0.0);
  const double w = s.measure("min_width").value(rate_form_positions(*s.scheme, s.y0), s.y0);
  EXPECT_NEAR(w, 1.0, 0.05);  // the slab's width W = 1 at rest, to a particle
}

TEST(GmsScenes, BadParametersAreOneLineErrors) {
  const Scene<2> s = gms_rings_scene({.spacing = 0.25});
  EXPECT_THROW(s.time_step(0), std::invalid_argument);
  EXPECT_THROW(s.time_step(NAN), std::invalid_argument);
  try {
    (void)s.measure("tip_deflection");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "scene rings: no measure 'tip_deflection' (valid: ring_fragments)");
  }
  EXPECT_THROW(gms_rings_scene({.spacing = -1}), std::invalid_argument);
  EXPECT_THROW(gms_slab_scene({.spacing = 0}), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
