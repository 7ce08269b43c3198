// Powell's impact problems as Scenes (problems/powell_impact.hpp): the block, its initial velocities, particle A,
// the measures, MCM's formulation options, TL-SPH on the same particles, and one-line errors for bad options.
#include "sphstab/problems/powell_impact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/memory_budget.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace sphstab {
namespace powell_impact_test {

std::string error_of(const PowellImpactOptions& o) {
  try {
    powell_impact_scene(o);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

Eigen::Vector2d momentum(const RateFormScheme<2>& s, const Eigen::VectorXd& y) {
  const Eigen::Matrix2Xd v = rate_form_velocities(s, y);
  const Eigen::VectorXd& vol = s.discretisation().particles.volume;
  return v * (vol * s.initial_density());
}

TEST(PowellImpact, SymmetricBlockHalvesApproachWithKineticEnergyHalfRhoV0SquaredArea) {
  const PowellImpactOptions o{.spacing = 0.05};
  const Scene<2> s = powell_impact_scene(o);
  const auto& d = s.scheme->discretisation();
  ASSERT_EQ(d.size(), 400);  // 20 x 20
  EXPECT_EQ(d.free_count(), 400);
  EXPECT_EQ(s.name, "symmetric-impact");
  EXPECT_EQ(s.t_end, 6);
  EXPECT_DOUBLE_EQ(d.h, 0.065);
  for (int i = 0; i < d.size(); ++i) {
    const double vy = s.y0[s.scheme->velocity_offset(i) + 1];
    EXPECT_EQ(vy, d.particles.x(i, 1) > 0.5 ? -0.06 : 0.06) << i;
    EXPECT_EQ(
        d.particles.depth[i],
        std::min({static_cast<int>(d.particles.x(i, 0) / 0.05), 19 - static_cast<int>(d.particles.x(i, 0) / 0.05),
                  static_cast<int>(d.particles.x(i, 1) / 0.05), 19 - static_cast<int>(d.particles.x(i, 1) / 0.05)}));
  }
  EXPECT_NEAR(s.scheme->kinetic_energy(s.y0), 0.5 * 7.8 * 0.06 * 0.06 * 1.0, 1e-15);
  EXPECT_LT(momentum(*s.scheme, s.y0).norm(), 1e-15);
  // A: nearest (0.5, 0.75); four particles tie at 0.025 sqrt(2), the lowest index is (0.475, 0.725).
  const int a = impact_particle_a(o);
  EXPECT_DOUBLE_EQ(d.particles.x(a, 0), 0.475);
  EXPECT_DOUBLE_EQ(d.particles.x(a, 1), 0.725);
  const Eigen::Matrix2Xd x = rate_form_positions(*s.scheme, s.y0);
  EXPECT_EQ(s.measures.front().name, "pressure_A");
  EXPECT_EQ(s.measure("pressure_A").value(x, s.y0), 0.0);
  EXPECT_DOUBLE_EQ(s.measure("speed_A").value(x, s.y0), 0.06);
  EXPECT_DOUBLE_EQ(s.measure("length").value(x, s.y0), 0.95);
  // Expansion: the same block with the velocities reversed.
  const Scene<2> e = powell_impact_scene({.spacing = 0.05, .speed = -0.06});
  EXPECT_TRUE(e.y0.isApprox(-s.y0 + 2 * s.scheme->uniform_state()));
}

TEST(PowellImpact, FormulationsAreMcmsRateForm) {
  for (const std::string f : {"sph", "ncsph", "ssph"}) {
    const RateFormOptions o = powell_formulation_options(f);
    EXPECT_EQ(o.continuity, ContinuityForm::Divergence) << f;
    EXPECT_EQ(o.bulk_viscosity_quadratic, 1.5) << f;
    EXPECT_EQ(o.bulk_viscosity_linear, 0.06) << f;
    EXPECT_EQ(o.xsph, 0.0) << f;  // the leap-frog's (2.71), not the scheme's
    EXPECT_EQ(o.gradient, f == "ncsph" ? RateFormGradient::Ncsph : RateFormGradient::Plain) << f;
    EXPECT_EQ(o.momentum, f == "ssph" ? RateFormMomentum::StabilisedSph : RateFormMomentum::Symmetric) << f;
  }
  EXPECT_EQ(powell_formulation_options("ssph").counting, NeighbourCounting::BoundaryLevel);
  try {
    powell_formulation_options("tl");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown rate-form formulation 'tl' (valid: sph, ncsph, ssph)");
  }
}

TEST(PowellImpact, BarImpactConservesMomentumOverARun) {
  const Scene<2> s = powell_impact_scene(
      {.problem = ImpactProblem::Bar, .spacing = 0.05, .scheme = powell_formulation_options("ssph")});
  const auto& d = s.scheme->discretisation();
  ASSERT_EQ(d.size(), 80 * 8);
  int left = 0;
  for (int i = 0; i < d.size(); ++i) {
    const double vx = s.y0[s.scheme->velocity_offset(i)];
    EXPECT_EQ(vx, d.particles.x(i, 0) < 1.0 ? 0.06 : -0.06) << i;
    left += vx > 0;
  }
  EXPECT_EQ(left, 20 * 8);
  const Eigen::Vector2d p0 = momentum(*s.scheme, s.y0);
  EXPECT_NEAR(p0.x(), 7.8 * 0.0025 * 0.06 * (160 - 480), 1e-13);
  EXPECT_EQ(s.measures.front().name, "length");
  EXPECT_DOUBLE_EQ(s.measures.front().value(rate_form_positions(*s.scheme, s.y0), s.y0), 3.95);
  // S-SPH's pair forces are symmetrised, the bulk viscosity is a pressure and (2.71) conserves momentum for equal
  // masses without fixed neighbours: the total momentum stays p0 to rounding over 30 leap-frog steps.
  const RateFormRunResult r = run_rate_form(*s.scheme, s.y0,
                                            {.dt = s.time_step(0.8),
                                             .t_end = 30 * s.time_step(0.8),
                                             .integrator = RateFormIntegrator::Leapfrog,
                                             .leapfrog_xsph = 0.1});
  ASSERT_TRUE(r.completed()) << r.message;
  EXPECT_NEAR((momentum(*s.scheme, r.y) - p0).norm(), 0.0, 1e-12 * p0.norm());
  EXPECT_LT(s.measures.front().value(rate_form_positions(*s.scheme, r.y), r.y), 3.95);  // the bar is compressed
}

TEST(PowellImpact, ClampedBeamHasFixedEndsLastAndALoadedMidSection) {
  const Scene<2> s = powell_impact_scene({.problem = ImpactProblem::Beam, .spacing = 0.05});
  const auto& d = s.scheme->discretisation();
  ASSERT_EQ(d.size(), 80 * 8);  // the bar's 4 x 0.4 cm (Fig. 4.13)
  ASSERT_EQ(d.free_count(), 70 * 8);
  for (int i = 0; i < d.size(); ++i) {
    const double x = d.particles.x(i, 0);
    const bool clamped = x < 0.25 || x > 3.75;
    EXPECT_EQ(d.particles.role[i] == Role::Fixed, clamped) << i;
    EXPECT_EQ(clamped, i >= 560) << i;  // free particles first
    if (!clamped) EXPECT_EQ(s.y0[s.scheme->velocity_offset(i) + 1], std::abs(x - 2.0) < 0.2 ? -0.3 : 0.0) << i;
  }
  const int a = impact_particle_a({.problem = ImpactProblem::Beam, .spacing = 0.05});
  EXPECT_DOUBLE_EQ(d.particles.x(a, 0), 1.975);
  EXPECT_DOUBLE_EQ(d.particles.x(a, 1), 0.025);
  EXPECT_EQ(s.measures.front().name, "deflection");
  Eigen::Matrix2Xd x = rate_form_positions(*s.scheme, s.y0);
  x(1, a) -= 0.01;
  EXPECT_NEAR(s.measures.front().value(x, s.y0), -0.01, 1e-15);
}

TEST(PowellImpact, TotalLagrangianPressureRateEqualsTheRateFormsDensityRate) {
  // The TL pressure -K div u of a displacement u equals K / rho0 times the rate form's density rate -rho0 tr L at
  // velocity u (MCM's continuity (1.32), the same plain gradient V_j grad W_ij at the initial positions): two codes.
  const Scene<2> s = powell_impact_scene({.spacing = 0.05, .scheme = powell_formulation_options("sph")});
  const ImpactTotalLagrangian tl = impact_total_lagrangian(s);
  const auto& d = s.scheme->discretisation();
  Eigen::VectorXd y = s.scheme->uniform_state(), u(d.dofs());
  for (int i = 0; i < d.size(); ++i) {
    const Eigen::Vector2d w(std::sin(3 * d.particles.x(i, 0)) + 0.2 * d.particles.x(i, 1),
                            std::cos(2 * d.particles.x(i, 1)) * d.particles.x(i, 0));
    s.scheme->set_velocity(y, i, w);
    u.segment<2>(2 * d.free_slot[i]) = w;
  }
  Eigen::VectorXd f;
  s.scheme->rate(y, f);
  const double K = s.scheme->material().bulk_modulus();
  for (int i = 0; i < d.size(); i += 7)
    EXPECT_NEAR(tl.pressure(u, i), K / 7.8 * f[s.scheme->density_offset(i)], 1e-12 * K) << i;
  EXPECT_EQ(tl.v0.size(), d.dofs());
  EXPECT_NEAR(0.5 * tl.v0.dot(tl.v0.cwiseProduct(tl.system.mass.replicate(1, 2).transpose().reshaped())),
              s.scheme->kinetic_energy(s.y0), 1e-15);
  EXPECT_THROW(tl.pressure(u, d.size()), std::invalid_argument);
}

TEST(PowellImpact, FiniteStrainTotalLagrangianAgreesWithTheLinearToSecondOrderAndIgnoresRotation) {
  // The SVK TL-SPH and Powell's linear TL-SPH share their operators: at a displacement eps w their accelerations and
  // pressures differ by O(eps^2) (the relative difference halves when eps halves). A rigid rotation by theta gives
  // the linear form a pressure -K tr(R - I) = 2 K (1 - cos theta) but leaves det F = 1 (to the lattice's gradient
  // error) in the finite-strain one.
  const Scene<2> s = powell_impact_scene({.problem = ImpactProblem::Beam, .spacing = 0.05});
  const ImpactTotalLagrangian lin = impact_total_lagrangian(s, ImpactTLModel::Linear);
  const ImpactTotalLagrangian svk = impact_total_lagrangian(s, ImpactTLModel::StVenantKirchhoff);
  const auto& d = s.scheme->discretisation();
  Eigen::VectorXd w(d.dofs());
  for (int f = 0; f < d.free_count(); ++f) {
    const Eigen::RowVector2d x = d.particles.x.row(d.free[f]);
    w.segment<2>(2 * f) << std::sin(2 * x.x()) * x.y(), 0.3 * std::cos(3 * x.x());
  }
  const int a = impact_particle_a({.problem = ImpactProblem::Beam, .spacing = 0.05});
  const auto accel = [](const ImpactTotalLagrangian& m, const Eigen::VectorXd& u) {
    Eigen::VectorXd out;
    m.system.acceleration(u, out);
    return out;
  };
  double previous = 0, previous_p = 0;
  for (double eps : {1e-3, 5e-4}) {
    const Eigen::VectorXd u = eps * w;
    const double diff = (accel(lin, u) - accel(svk, u)).norm() / accel(lin, u).norm();
    const double diff_p = std::abs(lin.pressure(u, a) - svk.pressure(u, a)) / std::abs(lin.pressure(u, a));
    EXPECT_LT(diff, 0.05);
    if (previous > 0) {
      EXPECT_NEAR(diff / previous, 0.5, 0.02);  // relative difference O(eps): absolute O(eps^2)
      EXPECT_NEAR(diff_p / previous_p, 0.5, 0.02);
    }
    previous = diff, previous_p = diff_p;
  }
  // Rigid rotation about the beam's centre by 0.1 rad.
  const double th = 0.1;
  Eigen::Matrix2d R;
  R << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
  Eigen::VectorXd u(d.dofs());
  for (int f = 0; f < d.free_count(); ++f) {
    const Eigen::Vector2d x = d.particles.x.row(d.free[f]).transpose() - Eigen::Vector2d(2, 0.2);
    u.segment<2>(2 * f) = R * x - x;
  }
  int interior = -1;  // a particle with a complete neighbourhood (depth >= 3: 2h = 2.6 dx)
  for (int i = 0; i < d.size(); ++i)
    if (d.particles.depth[i] >= 3 && std::abs(d.particles.x(i, 0) - 2.0) < 0.3) interior = i;
  ASSERT_GE(interior, 0);
  const double K = s.scheme->material().bulk_modulus();
  EXPECT_NEAR(lin.pressure(u, interior) / (2 * K * (1 - std::cos(th))), 1.0, 0.05);  // -K tr(R - I)
  EXPECT_LT(std::abs(svk.pressure(u, interior)), 0.02 * lin.pressure(u, interior));  // det R = 1
  EXPECT_EQ(parse_impact_tl_model("svk"), ImpactTLModel::StVenantKirchhoff);
  EXPECT_THROW(parse_impact_tl_model("neo"), std::invalid_argument);
}

TEST(PowellImpact, BadOptionsAreOneLineErrors) {
  EXPECT_EQ(error_of({.spacing = 0.04}), "powell_impact_scene: height 1 must be a whole multiple of 2 dx = 0.08");
  EXPECT_EQ(error_of({.spacing = 0.03}), "powell_impact_scene: length 1 must be a whole multiple of 1 dx = 0.03");
  EXPECT_EQ(error_of({.speed = INFINITY}), "powell_impact_scene: speed must be finite (got inf)");
  EXPECT_EQ(error_of({.t_end = -1}), "powell_impact_scene: t_end must be finite and > 0 (got -1)");
  EXPECT_EQ(error_of({.problem = ImpactProblem::Bar, .split = 0.251}),
            "powell_impact_scene: split * length / dx = 50.2 must be a whole number of particle columns");
  EXPECT_EQ(error_of({.problem = ImpactProblem::Bar, .split = 1}),
            "powell_impact_scene: split must be in (0, 1) (got 1)");
  EXPECT_EQ(error_of({.problem = ImpactProblem::Beam, .clamp_layers = 120}),
            "powell_impact_scene: clamp_layers 120 must be >= 1 and leave the section free (200 columns)");
  EXPECT_EQ(error_of({.problem = ImpactProblem::Beam, .split = 0.105}),
            "powell_impact_scene: the beam's section (21 columns) must leave an even number of columns to centre it "
            "in 200");
  EXPECT_NE(error_of({.spacing = 1e300}), "");
  // 1e6 x 1e6 particles: refused by the memory estimate before anything is allocated.
  EXPECT_THROW(powell_impact_scene({.spacing = 1e-6}), MemoryLimitError);
  // 4e6 spacings along the bar: one line saying so (it used to read "must be a whole multiple of 1 dx").
  EXPECT_EQ(error_of({.problem = ImpactProblem::Bar, .spacing = 1e-6}),
            "powell_impact_scene: length 4 is 4e+06 spacings of dx = 1e-06, more than 1e6 along one side");
  EXPECT_EQ(parse_impact_problem("beam"), ImpactProblem::Beam);
  EXPECT_EQ(impact_problem_name(parse_impact_problem("bar")), "bar");
  EXPECT_THROW(parse_impact_problem("plate"), std::invalid_argument);
}

// The clamped-beam study's 0.1 cm clamp in whole layers: Powell's five at dx = 0.02; refused where dx does not divide
// it or exceeds it.
TEST(PowellImpact, ClampLayers) {
  EXPECT_EQ(impact_clamp_layers(0.1, 0.02), 5);
  EXPECT_EQ(impact_clamp_layers(0.1, 0.0125), 8);
  EXPECT_EQ(impact_clamp_layers(0.1, 0.1), 1);
  for (double dx : {0.03, 0.2, 0.0, -0.02, std::nan("")})
    EXPECT_THROW(impact_clamp_layers(0.1, dx), std::invalid_argument) << dx;
}

}  // namespace powell_impact_test
}  // namespace sphstab
