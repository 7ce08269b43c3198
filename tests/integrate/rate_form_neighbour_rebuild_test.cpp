// Neighbour-list rebuild of the rate-form run (RateFormRunOptions::neighbour_skin, RateFormScheme::rebuilt): the list
// radius does not change the scheme (C_ij / S-SPH local means included), a rebuilt scheme is the scheme built from
// scratch at the new positions, runs with any skin are the exact all-pairs run, and two blocks that the one-time list
// lets pass through each other collide once the list follows them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/numerics/random_vector.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace rate_form_neighbour_rebuild_test {

const ElasticMaterial kGms = ElasticMaterial::from_bulk_shear(1.0, 0.22, 1.0);
const Kernel<2> kCubic(KernelType::CubicSpline);

/// max |a - b| / max |b|.
double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

/// relative_difference of two states field by field (x, v, rho, S), the largest: positions of order 10 would
/// otherwise hide the velocities and stresses.
double state_difference(const RateFormScheme<2>& s, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  std::vector<double> da(4, 0.0), db(4, 0.0);
  auto add = [&](int field, int offset, int count) {
    for (int c = 0; c < count; ++c) {
      da[field] = std::max(da[field], std::abs(a[offset + c] - b[offset + c]));
      db[field] = std::max(db[field], std::abs(b[offset + c]));
    }
  };
  for (int i = 0; i < s.discretisation().size(); ++i) {
    if (s.position_offset(i) >= 0) {
      add(0, s.position_offset(i), 2);
      add(1, s.velocity_offset(i), 2);
    }
    if (s.density_offset(i) >= 0) {
      add(2, s.density_offset(i), 1);
      add(3, s.stress_offset(i), 3);
    }
  }
  double worst = 0;
  for (int f = 0; f < 4; ++f)
    if (db[f] > 0) worst = std::max(worst, da[f] / db[f]);
  return worst;
}

/// A 7 x 7 square block at dx = 1 with the fixed layers of h = 1.3, free particles perturbed by 0.1 dx.
std::shared_ptr<const Discretisation<2>> block_with_layers() {
  return make_discretisation(
      make_lattice<2>(LatticeType::Square, 7,
                      {.spacing = 1.0, .support_radius = kCubic.support_radius(1.3), .perturbation = 0.1, .seed = 11}),
      kCubic, 1.3);
}

/// The option sets whose results could depend on the list: every term, both corrections, the local means.
std::vector<RateFormOptions> option_sets() {
  return {{},
          {.xsph = 0.5, .viscosity = ViscositySwitch::Compression, .artificial_stress = 0.3},
          {.continuity = ContinuityForm::Divergence,
           .gradient = RateFormGradient::Ncsph,
           .momentum = RateFormMomentum::Antisymmetric},
          {.momentum = RateFormMomentum::Cij},
          {.momentum = RateFormMomentum::Cij, .counting = NeighbourCounting::BoundaryLevel},
          {.xsph = 0.5, .momentum = RateFormMomentum::StabilisedSph, .excluded_depth = -1},
          {.momentum = RateFormMomentum::StabilisedSph, .switch_rule = SwitchRule::Always}};
}

/// A moving, stressed state near the reference positions (no pair crosses the support).
Eigen::VectorXd moving_state(const RateFormScheme<2>& s, std::uint64_t seed) {
  Eigen::VectorXd y = s.uniform_state() + random_vector(s.size(), 0.01, seed);
  for (int i = 0; i < s.discretisation().size(); ++i) y[s.density_offset(i)] = s.initial_density();
  return y;
}

TEST(RateFormNeighbourRebuild, ListRadiusDoesNotChangeTheRates) {
  // The same positions on a list of radius support + 1.3 (about twice the pairs): equal rates. Before the local
  // means were restricted to the support, C_ij and S-SPH moved by 11 % and 18 % (0.0022 of 0.020, 0.0056 of 0.032).
  // Measured: 0 (bitwise) for every option set.
  const auto disc = block_with_layers();
  for (const RateFormOptions& o : option_sets()) {
    const RateFormScheme<2> s(disc, kGms, o, 1.0 / 1.02, Eigen::Vector3d(0.01, -0.02, 0.005));
    const Eigen::VectorXd y = moving_state(s, 5);
    const RateFormScheme<2> wide = s.rebuilt(s.uniform_state(), kCubic.support_radius(1.3) + 1.3);
    EXPECT_GT(wide.discretisation().neighbours.nonzeros(), 3 * disc->neighbours.nonzeros() / 2);
    Eigen::VectorXd f, g;
    s.rate(y, f);
    wide.rate(y, g);
    EXPECT_LE(relative_difference(g, f), 1e-14) << s.name();
  }
}

TEST(RateFormNeighbourRebuild, RunWithoutRebuildEqualsTheSkinZeroRun) {
  // A skin of 0.5 dx that is never exceeded (largest motion ~0.05 dx): one build, the skin-0 result. Measured:
  // 0 (bitwise) for every option set and both integrators.
  const auto disc = block_with_layers();
  for (const RateFormOptions& o : option_sets())
    for (RateFormIntegrator integrator : {RateFormIntegrator::PredictorCorrector, RateFormIntegrator::Leapfrog}) {
      const RateFormScheme<2> s(disc, kGms, o, 1.0 / 1.02);
      const Eigen::VectorXd y0 = moving_state(s, 7);
      RateFormRunOptions ro{.dt = 0.05, .t_end = 4.0, .integrator = integrator};
      const RateFormRunResult a = run_rate_form(s, y0, ro);
      ro.neighbour_skin = 0.5;
      const RateFormRunResult b = run_rate_form(s, y0, ro);
      ASSERT_TRUE(a.completed() && b.completed()) << a.message << " / " << b.message;
      EXPECT_EQ(a.neighbour_builds, 0);
      EXPECT_EQ(b.neighbour_builds, 1) << s.name();
      EXPECT_LE(state_difference(s, b.y, a.y), 1e-12) << s.name();
    }
}

TEST(RateFormNeighbourRebuild, RebuiltSchemeIsTheSchemeBuiltAtTheNewPositions) {
  // Free particles sheared by 0.8 dx per dx of height plus noise (most pairs change), fixed layers at rest: the rates
  // of rebuilt() equal those of a discretisation and scheme made from scratch at those positions (to 1e-14; measured
  // 0), and differ from the stale list's by O(1) (measured 0.22-0.55 relative in the worst field).
  const auto disc = block_with_layers();
  const ParticleSet<2>& p = disc->particles;
  for (const RateFormOptions& o : option_sets()) {
    RateFormScheme<2> s(disc, kGms, o, 1.0 / 1.02, Eigen::Vector3d(0.01, -0.02, 0.005));
    s.set_driven({0, 24}, {Eigen::Vector2d(0.1, 0), Eigen::Vector2d(0, -0.2)});
    Eigen::VectorXd y = moving_state(s, 9);
    ParticleSet<2> moved = p;
    const Eigen::VectorXd noise = random_vector(2 * p.size(), 0.1, 13);
    for (int i = 0; i < p.size(); ++i) {
      if (s.position_offset(i) < 0) continue;
      moved.x(i, 0) += 0.8 * (p.x(i, 1) - 3.5) + noise[2 * i];
      moved.x(i, 1) += noise[2 * i + 1];
      y.segment<2>(s.position_offset(i)) = moved.x.row(i).transpose();
    }
    RateFormScheme<2> scratch(make_discretisation(moved, kCubic, 1.3), kGms, o, 1.0 / 1.02,
                              Eigen::Vector3d(0.01, -0.02, 0.005));
    scratch.set_driven({0, 24}, {Eigen::Vector2d(0.1, 0), Eigen::Vector2d(0, -0.2)});
    const RateFormScheme<2> re = s.rebuilt(y, kCubic.support_radius(1.3) + 0.4);
    EXPECT_EQ(re.driven_particles(), s.driven_particles());
    EXPECT_EQ(re.mass(), s.mass());
    Eigen::VectorXd f_re, f_scratch, f_stale;
    re.rate(y, f_re);
    scratch.rate(y, f_scratch);
    s.rate(y, f_stale);
    EXPECT_LE(relative_difference(f_re, f_scratch), 1e-14) << s.name();
    EXPECT_GT(state_difference(s, f_stale, f_scratch), 0.1) << s.name();  // the test can tell
  }
}

TEST(RateFormNeighbourRebuild, RebuildWrapsPositionsIntoThePeriodicBox) {
  // A periodic lattice whose state carries some particles one box length away (the rate uses the minimum image):
  // rebuilt() wraps them for the search, and its rates are the original's at that state (measured 0, bitwise) and,
  // to the rounding of the shifted coordinates, at the unshifted state (measured 1.2e-15).
  const auto disc =
      make_discretisation(make_lattice<2>(LatticeType::Square, 10, {.spacing = 1.0, .periodic = true}), kCubic, 1.3);
  const RateFormScheme<2> s(disc, kGms, {.xsph = 0.5, .momentum = RateFormMomentum::Cij}, 1.0 / 1.02);
  const Eigen::VectorXd y = moving_state(s, 17);
  Eigen::VectorXd shifted = y;
  // Shift particles away from the box faces in the shifted axis, all the same way in one axis (the rate's minimum
  // image takes at most one box length off).
  for (int i = 0; i < disc->size(); ++i) {
    const int a = i % 2;
    if (i % 3 < 2 && disc->particles.x(i, a) > 3 && disc->particles.x(i, a) < 7)
      shifted[s.position_offset(i) + a] += a == 0 ? 10.0 : -10.0;
  }
  const RateFormScheme<2> re = s.rebuilt(shifted, 3.0);
  EXPECT_GE(re.discretisation().particles.x.minCoeff(), 0.0);
  EXPECT_LE(re.discretisation().particles.x.maxCoeff(), 10.0);
  Eigen::VectorXd f, g, f_shifted;
  s.rate(y, f);
  s.rate(shifted, f_shifted);
  re.rate(shifted, g);
  EXPECT_LE(relative_difference(g, f_shifted), 1e-14);
  EXPECT_LE(relative_difference(g, f), 1e-12);  // positions rounded at 10 + x
}

/// Two free 6 x 6 blocks (dx = 1, h = 1.5 dx) with 4.5 dx between facing rows (support 3 dx), moving towards each
/// other at +-0.05 (GMS units, rho0 = K = 1, mu = 0.22).
struct TwoBlocks {
  RateFormScheme<2> scheme;
  Eigen::VectorXd y0;
  std::vector<int> left, right;
};

TwoBlocks two_blocks(const RateFormOptions& options) {
  const int n = 6;
  ParticleSet<2> p;
  p.x.resize(2 * n * n, 2);
  p.volume = Eigen::VectorXd::Ones(2 * n * n);
  p.role.assign(2 * n * n, Role::Free);
  p.spacing = 1.0;
  std::vector<int> left, right;
  for (int b = 0; b < 2; ++b)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int k = b * n * n + j * n + i;
        p.x.row(k) << i + b * (n - 1 + 4.5), j;
        p.depth.push_back(std::min({i, j, n - 1 - i, n - 1 - j}));
        (b == 0 ? left : right).push_back(k);
      }
  RateFormScheme<2> s(make_discretisation(p, kCubic, 1.5), kGms, options);
  Eigen::VectorXd y = s.uniform_state();
  for (int k : left) s.set_velocity(y, k, Eigen::Vector2d(0.05, 0));
  for (int k : right) s.set_velocity(y, k, Eigen::Vector2d(-0.05, 0));
  return {std::move(s), std::move(y), std::move(left), std::move(right)};
}

Eigen::Vector2d momentum(const RateFormScheme<2>& s, const Eigen::VectorXd& y, const std::vector<int>& particles) {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (int i : particles) m += s.mass()[i] * y.segment<2>(s.velocity_offset(i));
  return m;
}

TEST(RateFormNeighbourRebuild, AnySkinGivesTheAllPairsRun) {
  // The colliding blocks to t = 60 (contact from t ~ 15, rebound by t ~ 50): skins 0.2 and 0.6 rebuild 28-30 and
  // 8-10 times; a skin of 25 holds every pair of the 72 particles in one list (an all-pairs search). All three agree
  // to rounding, for both integrators, with GMS XSPH and Powell's XSPH (measured 0 with the predictor-corrector,
  // <= 2.2e-15 with the leap-frog, worst field); the one-time list (skin 0) does not (measured 1.7-1.8: the blocks
  // pass through each other).
  for (RateFormIntegrator integrator : {RateFormIntegrator::PredictorCorrector, RateFormIntegrator::Leapfrog}) {
    const TwoBlocks blocks = two_blocks({.xsph = 0.5});
    RateFormRunOptions ro{.dt = 0.2, .t_end = 60.0, .integrator = integrator};
    if (integrator == RateFormIntegrator::Leapfrog) ro.leapfrog_xsph = 0.05;
    ro.neighbour_skin = 25;
    const RateFormRunResult all = run_rate_form(blocks.scheme, blocks.y0, ro);
    ASSERT_TRUE(all.completed()) << all.message;
    EXPECT_EQ(all.neighbour_builds, 1);
    for (double skin : {0.2, 0.6}) {
      ro.neighbour_skin = skin;
      const RateFormRunResult r = run_rate_form(blocks.scheme, blocks.y0, ro);
      ASSERT_TRUE(r.completed()) << r.message;
      EXPECT_GE(r.neighbour_builds, 5) << skin;
      EXPECT_LE(state_difference(blocks.scheme, r.y, all.y), 1e-12)
          << "skin " << skin << ", " << r.neighbour_builds << " builds";
    }
    ro.neighbour_skin = 0;
    const RateFormRunResult stale = run_rate_form(blocks.scheme, blocks.y0, ro);
    EXPECT_GT(state_difference(blocks.scheme, stale.y, all.y), 0.1);
  }
}

TEST(RateFormNeighbourRebuild, BlocksCollideOnlyWithARebuiltList) {
  // Without a rebuild the blocks never see each other: each translates unchanged (centre-of-mass velocity +-0.05 to
  // rounding) and by t = 120 they have passed through one another. With a skin of 0.3 dx they collide (contact from
  // t ~ 15, largest compression at t ~ 37) and rebound: the total momentum stays zero to rounding at every step and
  // each block's centre-of-mass x-velocity reverses. Measured, plain and with XSPH 0.5, both integrators: fastest
  // rebound -0.0399 / +0.0399 (plain) and -0.0393 / +0.0393 (XSPH) at t ~ 50, i.e. 79 % of the approach speed (the
  // interface then pulls the blocks together again: SPH has no contact model); |total momentum| <= 1.3e-15; 20-22
  // builds.
  for (const RateFormOptions& o : {RateFormOptions{}, RateFormOptions{.xsph = 0.5}})
    for (RateFormIntegrator integrator : {RateFormIntegrator::PredictorCorrector, RateFormIntegrator::Leapfrog}) {
      const TwoBlocks b = two_blocks(o);
      const double mass = 36.0;
      RateFormRunOptions ro{.dt = 0.2, .t_end = 120.0, .integrator = integrator};
      const RateFormRunResult pass = run_rate_form(b.scheme, b.y0, ro);
      ASSERT_TRUE(pass.completed()) << pass.message;
      EXPECT_NEAR(momentum(b.scheme, pass.y, b.left)[0] / mass, 0.05, 1e-15);
      EXPECT_NEAR(momentum(b.scheme, pass.y, b.right)[0] / mass, -0.05, 1e-15);
      double xl = 0, xr = 0;  // centres: the left block's is now right of the right block's
      for (int i : b.left) xl += pass.y[b.scheme.position_offset(i)] / 36;
      for (int i : b.right) xr += pass.y[b.scheme.position_offset(i)] / 36;
      EXPECT_GT(xl, xr + 2.0);

      double rebound_left = 1, rebound_right = -1, drift = 0;
      ro.t_end = 60;
      ro.neighbour_skin = 0.3;
      ro.observer = [&](long, double, const Eigen::VectorXd& y) {
        const Eigen::Vector2d pl = momentum(b.scheme, y, b.left), pr = momentum(b.scheme, y, b.right);
        rebound_left = std::min(rebound_left, pl[0] / mass);
        rebound_right = std::max(rebound_right, pr[0] / mass);
        drift = std::max(drift, (pl + pr).norm());
      };
      const RateFormRunResult hit = run_rate_form(b.scheme, b.y0, ro);
      ASSERT_TRUE(hit.completed()) << hit.message;
      EXPECT_GT(hit.neighbour_builds, 2);
      EXPECT_LE(drift, 1e-14);
      EXPECT_LT(rebound_left, -0.03);
      EXPECT_GT(rebound_right, 0.03);
    }
}

TEST(RateFormNeighbourRebuild, RejectsBadInput) {
  const TwoBlocks b = two_blocks({});
  for (double skin : {-0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(run_rate_form(b.scheme, b.y0, {.dt = 0.1, .t_end = 1.0, .neighbour_skin = skin}),
                 std::invalid_argument);
  Eigen::VectorXd bad = b.y0;
  bad[b.scheme.position_offset(3)] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(run_rate_form(b.scheme, bad, {.dt = 0.1, .t_end = 1.0, .neighbour_skin = 0.3}), std::invalid_argument);
  EXPECT_THROW(b.scheme.rebuilt(bad, 4.0), std::invalid_argument);
  EXPECT_THROW(b.scheme.rebuilt(b.y0.head(10), 4.0), std::invalid_argument);
  EXPECT_THROW(b.scheme.rebuilt(b.y0, 2.0), std::invalid_argument);  // below the support 3
  EXPECT_THROW(b.scheme.rebuilt(b.y0, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
