// scene_run_options (integrate/scene_run.hpp): each scene's default run is its integrator, step rule and XSPH — GMS's
// plate and rings with one rate evaluation per step (results/gms-pc1), the slab (yield stress) with two, Powell's
// impacts on the leap-frog with XSPH 0.1 at cfl 0.8 — and running with them is running with those fields by hand.
#include "sphstab/integrate/scene_run.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "sphstab/integrate/linear_step_map.hpp"
#include "sphstab/problems/gms_scenes.hpp"
#include "sphstab/problems/powell_impact.hpp"

namespace sphstab {
namespace scene_run_test {

TEST(SceneRun, EachSceneRunsWithItsOwnIntegratorAndStep) {
  const Scene<2> plate = gms_plate_scene({.length = 8, .thickness = 2, .across = 4}, 0.02);
  const Scene<2> rings = gms_rings_scene({.inner_radius = 1, .outer_radius = 2, .spacing = 0.5});
  const Scene<2> slab = gms_slab_scene({.spacing = 0.25}, 0.03);
  const Scene<2> bar = powell_impact_scene({.problem = ImpactProblem::Bar, .spacing = 0.1});
  for (const Scene<2>* s : {&plate, &rings, &slab, &bar}) {
    const RateFormRunOptions o = scene_run_options(*s);
    EXPECT_EQ(o.dt, s->time_step(s->cfl)) << s->name;
    EXPECT_EQ(o.t_end, s->t_end) << s->name;
    EXPECT_EQ(o.yield_stress, s->yield_stress) << s->name;
    EXPECT_EQ(o.neighbour_skin, s->neighbour_skin) << s->name;
  }
  EXPECT_EQ(rate_form_integrator_name(scene_run_options(plate)), "pc1");
  EXPECT_EQ(rate_form_integrator_name(scene_run_options(rings)), "pc1");
  EXPECT_EQ(rate_form_integrator_name(scene_run_options(slab)), "pc");  // the radial return: PC1 is refused
  const RateFormRunOptions b = scene_run_options(bar);
  EXPECT_EQ(rate_form_integrator_name(b), "leapfrog");
  EXPECT_EQ(b.leapfrog_xsph, 0.1);
  EXPECT_EQ(b.dt, 0.8 * bar.scheme->discretisation().h / bar.scheme->material().p_wave_speed());
  // a chosen integrator overrides the scene's; Powell's XSPH goes with the leap-frog
  EXPECT_EQ(rate_form_integrator_name(scene_run_options(plate, "pc")), "pc");
  const RateFormRunOptions bp = scene_run_options(bar, "pc1");
  EXPECT_EQ(rate_form_integrator_name(bp), "pc1");
  EXPECT_EQ(bp.leapfrog_xsph, 0.0);
  EXPECT_EQ(scene_run_options(bar, "leapfrog").leapfrog_xsph, 0.1);
  EXPECT_EQ(rate_form_integrator_name(scene_run_options(slab, "auto")), "pc");
}

TEST(SceneRun, TheDefaultRunIsTheRunWithThoseFieldsByHand) {
  const Scene<2> rings = gms_rings_scene({.inner_radius = 1, .outer_radius = 2, .spacing = 0.5});
  RateFormRunOptions o = scene_run_options(rings);
  o.t_end = 20 * o.dt;
  const RateFormRunResult a = run_rate_form(*rings.scheme, rings.y0, o);
  const RateFormRunResult b =
      run_rate_form(*rings.scheme, rings.y0,
                    {.dt = rings.time_step(0.5), .t_end = 20 * o.dt, .reuse_corrector_rate = true,
                     .neighbour_skin = rings.neighbour_skin});
  ASSERT_TRUE(a.completed() && b.completed());
  EXPECT_EQ(a.y, b.y);
  const RateFormRunResult two = run_rate_form(*rings.scheme, rings.y0,
                                              {.dt = o.dt, .t_end = o.t_end, .neighbour_skin = rings.neighbour_skin});
  EXPECT_NE(a.y, two.y);  // PC1 is a different integrator: the comparison above can fail
}

TEST(SceneRun, AnUnknownIntegratorIsOneLine) {
  Scene<2> rings = gms_rings_scene({.inner_radius = 1, .outer_radius = 2, .spacing = 0.5});
  rings.integrator = "euler";
  try {
    scene_run_options(rings);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown integrator 'euler'"), std::string::npos) << e.what();
  }
}

}  // namespace scene_run_test
}  // namespace sphstab
