#include "sphstab/problems/colliding_rings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace sphstab {
namespace colliding_rings_test {

/// Independent count: cell centres in doubled grid units are the odd integers (a, b); the ring keeps
/// (2 R_in)^2 <= a^2 + b^2 <= (2 R_out)^2 with R_in, R_out the radii in spacings (whole numbers here), in exact
/// integer arithmetic.
long odd_lattice_annulus_count(long r_in, long r_out) {
  long n = 0;
  for (long a = -2 * r_out - 1; a <= 2 * r_out + 1; a += 2)
    for (long b = -2 * r_out - 1; b <= 2 * r_out + 1; b += 2) {
      const long q = a * a + b * b;
      if (4 * r_in * r_in <= q && q <= 4 * r_out * r_out) ++n;
    }
  return n;
}

/// Doubled grid coordinates 2 (x - c) / dp of one ring's particles; each must be an odd integer to 1e-9.
std::set<std::pair<long, long>> doubled_grid(const CollidingRings& rings, int which) {
  std::set<std::pair<long, long>> cells;
  const double dp = rings.options.spacing;
  for (int p = 0; p < rings.size(); ++p) {
    if (rings.ring[p] != which) continue;
    const double a = 2 * (rings.particles.x(p, 0) - rings.centre[which].x()) / dp;
    const double b = 2 * (rings.particles.x(p, 1) - rings.centre[which].y()) / dp;
    const long ia = std::lround(a), ib = std::lround(b);
    EXPECT_NEAR(a, static_cast<double>(ia), 1e-9) << p;
    EXPECT_NEAR(b, static_cast<double>(ib), 1e-9) << p;
    EXPECT_TRUE(std::abs(ia) % 2 == 1 && std::abs(ib) % 2 == 1) << p << ": not a cell centre";
    cells.emplace(ia, ib);
  }
  return cells;
}

TEST(CollidingRings, GmsAndSiParticleCountsMatchAnIndependentCountAndTheArea) {
  const CollidingRings gms = make_colliding_rings();
  EXPECT_EQ(gms.per_ring, 2196);
  EXPECT_EQ(gms.per_ring, odd_lattice_annulus_count(30, 40));
  EXPECT_EQ(gms.size(), 2 * 2196);
  const double gms_area = M_PI * (16.0 - 9.0) / 0.01;  // 2199.1 particles of volume dp^2
  EXPECT_LT(std::abs(gms.per_ring - gms_area) / gms_area, 0.01);
  EXPECT_NEAR(gms.particles.volume.sum(), 2 * 2196 * 0.01, 1e-10);

  const CollidingRings si =
      make_colliding_rings({.inner_radius = 0.03, .outer_radius = 0.04, .spacing = 5e-4, .gap = 1e-3, .speed = 1});
  EXPECT_EQ(si.per_ring, 8804);
  EXPECT_EQ(si.per_ring, odd_lattice_annulus_count(60, 80));
  EXPECT_EQ(si.size(), 2 * 8804);
  const double si_area = M_PI * (0.04 * 0.04 - 0.03 * 0.03) / (5e-4 * 5e-4);  // 8796.5
  EXPECT_LT(std::abs(si.per_ring - si_area) / si_area, 0.01);
  EXPECT_DOUBLE_EQ(si.particles.spacing, 5e-4);

  // A disc (r_in = 0) of radius 4 dp: 0 <= a^2 + b^2 <= 64 over odd a, b.
  EXPECT_EQ(make_colliding_rings({.inner_radius = 0, .outer_radius = 0.4}).per_ring, odd_lattice_annulus_count(0, 4));
}

TEST(CollidingRings, EachRingMapsOntoItselfUnderTheMirrorsAboutItsCentre) {
  const CollidingRings rings = make_colliding_rings();
  for (int r = 0; r < 2; ++r) {
    const auto cells = doubled_grid(rings, r);
    ASSERT_EQ(static_cast<int>(cells.size()), rings.per_ring) << "duplicate positions in ring " << r;
    std::set<std::pair<long, long>> mirror_x, mirror_y, swapped;
    for (const auto& [a, b] : cells) {
      mirror_x.emplace(-a, b);
      mirror_y.emplace(a, -b);
      swapped.emplace(b, a);
    }
    EXPECT_EQ(mirror_x, cells) << r;
    EXPECT_EQ(mirror_y, cells) << r;
    EXPECT_EQ(swapped, cells) << r;
  }
  // Ring 1 is ring 0 moved by c_1 - c_0, particle by particle; the centres sit on the x axis, symmetric about x = 0.
  EXPECT_EQ(rings.centre[0], Eigen::Vector2d(-4.1, 0));
  EXPECT_EQ(rings.centre[1], Eigen::Vector2d(4.1, 0));
  const Eigen::RowVector2d shift = (rings.centre[1] - rings.centre[0]).transpose();
  for (int k = 0; k < rings.per_ring; ++k)
    EXPECT_LT((rings.particles.x.row(rings.per_ring + k) - rings.particles.x.row(k) - shift).norm(), 1e-12) << k;
}

TEST(CollidingRings, RadiiIdsVelocitiesAndTheGapBetweenTheClosestParticles) {
  const CollidingRings rings = make_colliding_rings();
  for (int p = 0; p < rings.size(); ++p) {
    const int r = p < rings.per_ring ? 0 : 1;
    EXPECT_EQ(rings.ring[p], r);
    const double radius = (rings.particles.x.row(p).transpose() - rings.centre[r]).norm();
    EXPECT_GE(radius, 3.0);
    EXPECT_LE(radius, 4.0);
    EXPECT_EQ(rings.velocity.col(p), Eigen::Vector2d(r == 0 ? 0.059 : -0.059, 0)) << p;
    EXPECT_EQ(rings.particles.role[p], Role::Free);
  }
  EXPECT_EQ(rings.velocity.cols(), rings.size());
  // Total momentum 0, up to the rounding of summing 2 x 2196 terms of +-0.059 (each ring's sum is 129.6).
  EXPECT_NEAR(rings.velocity.rowwise().sum().norm(), 0.0, 1e-12);
  // Brute force over pairs: the outermost particle on a ring's x axis rows is 3.95 from its centre, so the closest
  // particles of the two rings are gap + dp apart.
  auto closest = [](const CollidingRings& s) {
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < s.per_ring; ++i)
      for (int j = s.per_ring; j < s.size(); ++j)
        best = std::min(best, (s.particles.x.row(i) - s.particles.x.row(j)).norm());
    return best;
  };
  EXPECT_NEAR(closest(rings), 0.2 + 0.1, 1e-12);
  EXPECT_NEAR(closest(make_colliding_rings({.gap = 0})), 0.1, 1e-12);
  EXPECT_NEAR(closest(make_colliding_rings({.gap = 1.0})), 1.1, 1e-12);
}

TEST(CollidingRings, DepthIsTheChebyshevGridDistanceToTheOutsideMinusOne) {
  const CollidingRings rings = make_colliding_rings();
  const auto cells = doubled_grid(rings, 0);
  int deepest = 0;
  for (int p = 0; p < rings.per_ring; ++p) {
    const long a = std::lround(2 * (rings.particles.x(p, 0) - rings.centre[0].x()) / 0.1);
    const long b = std::lround(2 * (rings.particles.x(p, 1) - rings.centre[0].y()) / 0.1);
    // The smallest k such that a cell at Chebyshev distance k + 1 is missing (doubled offsets 2 (k + 1)).
    int expected = -1;
    for (int k = 0; k < 20 && expected < 0; ++k) {
      const long s = 2 * (k + 1);
      for (long da = -s; da <= s && expected < 0; da += 2)
        for (long db = -s; db <= s; db += 2)
          if ((std::abs(da) == s || std::abs(db) == s) && !cells.count({a + da, b + db})) {
            expected = k;
            break;
          }
    }
    EXPECT_EQ(rings.particles.depth[p], expected) << p;
    EXPECT_EQ(rings.particles.depth[p + rings.per_ring], rings.particles.depth[p]) << p;
    deepest = std::max(deepest, rings.particles.depth[p]);
  }
  EXPECT_EQ(deepest, 4);  // a ring 10 cells wide on its axes: depth 0 1 2 3 4 4 3 2 1 0
}

TEST(CollidingRings, RejectsEveryBadOption) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(make_colliding_rings({.inner_radius = -0.1}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.inner_radius = nan}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.outer_radius = 3.0}), std::invalid_argument);  // = r_in
  EXPECT_THROW(make_colliding_rings({.outer_radius = 2.0}), std::invalid_argument);  // < r_in
  EXPECT_THROW(make_colliding_rings({.outer_radius = inf}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.spacing = 0}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.spacing = -0.1}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.spacing = nan}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.spacing = 0.6}), std::invalid_argument);  // fewer than 2 spacings across
  EXPECT_NO_THROW(make_colliding_rings({.spacing = 0.5}));                      // exactly 2 across
  EXPECT_THROW(make_colliding_rings({.gap = -0.01}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.gap = inf}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.speed = nan}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.speed = -inf}), std::invalid_argument);
  EXPECT_THROW(make_colliding_rings({.inner_radius = 0, .outer_radius = 1e-70, .spacing = 1e-72}),
               std::invalid_argument);  // outside the supported length range
  try {
    make_colliding_rings({.outer_radius = 2.0});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_EQ(std::string(e.what()).rfind("make_colliding_rings: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace sphstab
