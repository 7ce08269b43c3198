#include "sphstab/analysis/fragments.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "sphstab/problems/colliding_rings.hpp"

namespace sphstab {
namespace fragments_test {

/// Independent reference: breadth-first search over the O(N^2) bond matrix, fragments numbered by their lowest
/// particle index (the same convention as find_fragments, so the label vectors must be equal).
std::vector<int> brute_force_labels(const Eigen::Matrix2Xd& x, double radius) {
  const int n = static_cast<int>(x.cols());
  std::vector<int> label(n, -1);
  int next = 0;
  for (int s = 0; s < n; ++s) {
    if (label[s] >= 0) continue;
    std::vector<int> stack{s};
    label[s] = next;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      for (int j = 0; j < n; ++j)
        if (label[j] < 0 && (x.col(i) - x.col(j)).squaredNorm() < radius * radius) {
          label[j] = next;
          stack.push_back(j);
        }
    }
    ++next;
  }
  return label;
}

/// Positions (2 x N) of the particles of `rings` that pass `keep`.
Eigen::Matrix2Xd kept(const CollidingRings& rings, const std::function<bool(int)>& keep) {
  std::vector<int> idx;
  for (int p = 0; p < rings.size(); ++p)
    if (keep(p)) idx.push_back(p);
  Eigen::Matrix2Xd x(2, static_cast<Eigen::Index>(idx.size()));
  for (std::size_t k = 0; k < idx.size(); ++k) x.col(static_cast<Eigen::Index>(k)) = rings.particles.x.row(idx[k]);
  return x;
}

TEST(Fragments, TwoSeparatedRingsAreTwoAndTouchingRingsAreOne) {
  const CollidingRings rings = make_colliding_rings();  // closest particles of the two rings 0.3 = 3 dp apart
  const Fragments f = find_fragments(rings.particles.x.transpose(), 1.5 * 0.1);
  ASSERT_EQ(f.count(), 2);
  EXPECT_EQ(f.label, rings.ring);  // ring 0 holds particle 0
  EXPECT_EQ(f.sizes, (std::vector<int>{2196, 2196}));
  EXPECT_EQ(f.largest(), 2196);
  // The kernel support 2h = 3 dp does not reach across 3 dp (strict inequality) ...
  EXPECT_EQ(find_fragments(rings.particles.x.transpose(), 0.3 - 1e-12).count(), 2);
  // ... a slightly larger bond radius does.
  EXPECT_EQ(find_fragments(rings.particles.x.transpose(), 0.3 + 1e-9).count(), 1);
  // Rings touching (gap 0: closest particles dp apart) are one fragment.
  const CollidingRings touching = make_colliding_rings({.gap = 0});
  const Fragments t = find_fragments(touching.particles.x.transpose(), 1.5 * 0.1);
  EXPECT_EQ(t.count(), 1);
  EXPECT_EQ(t.largest(), 2 * 2196);
}

TEST(Fragments, ARingCutOnceStaysOneCutTwiceFallsInTwo) {
  const CollidingRings rings = make_colliding_rings();
  const double cx = rings.centre[0].x(), r = 1.5 * 0.1;
  auto in_ring0 = [&](int p) { return rings.ring[p] == 0; };
  // Strips |y| < 0.2 remove 4 rows (y = +-0.05, +-0.15): the rows left on either side of a cut (y = +-0.25) are
  // 0.5 apart, more than the bond radius.
  auto in_right_strip = [&](int p) { return std::abs(rings.particles.x(p, 1)) < 0.2 && rings.particles.x(p, 0) > cx; };
  auto in_left_strip = [&](int p) { return std::abs(rings.particles.x(p, 1)) < 0.2 && rings.particles.x(p, 0) < cx; };

  const Fragments whole = find_fragments(kept(rings, in_ring0), r);
  EXPECT_EQ(whole.count(), 1);
  EXPECT_EQ(whole.largest(), 2196);

  const Eigen::Matrix2Xd once = kept(rings, [&](int p) { return in_ring0(p) && !in_right_strip(p); });
  EXPECT_EQ(once.cols(), 2196 - 4 * 10);  // 4 rows x 10 cells across the ring
  EXPECT_EQ(find_fragments(once, r).count(), 1);

  const Eigen::Matrix2Xd twice =
      kept(rings, [&](int p) { return in_ring0(p) && !in_right_strip(p) && !in_left_strip(p); });
  const Fragments two = find_fragments(twice, r);
  ASSERT_EQ(two.count(), 2);
  EXPECT_EQ(two.sizes, (std::vector<int>{(2196 - 80) / 2, (2196 - 80) / 2}));  // the lower and upper halves
  for (Eigen::Index i = 0; i < twice.cols(); ++i) EXPECT_EQ(two.label[i], twice(1, i) > 0 ? 1 : 0) << i;
  // A bond radius wider than the cut (0.5 between particle centres) rejoins the halves.
  EXPECT_EQ(find_fragments(twice, 0.5 + 1e-9).count(), 1);
  EXPECT_EQ(find_fragments(twice, 0.5 - 1e-9).count(), 2);
}

TEST(Fragments, AgreesWithBruteForceOnRandomSets) {
  std::mt19937 gen(20011);  // fixed seed
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 50 + 40 * trial;
    Eigen::Matrix2Xd x(2, n);
    for (int i = 0; i < n; ++i) x.col(i) = Eigen::Vector2d(unit(gen), 0.5 * unit(gen));
    if (trial % 3 == 0) x.col(n - 1) = x.col(0);  // a coincident pair is bonded
    // Radii around the percolation threshold give many fragments of many sizes.
    const double radius = (0.6 + 0.1 * (trial % 5)) / std::sqrt(n / 0.5);
    const Fragments f = find_fragments(x, radius);
    const std::vector<int> expected = brute_force_labels(x, radius);
    EXPECT_EQ(f.label, expected) << "trial " << trial;
    std::vector<int> sizes(f.count(), 0);
    for (int l : expected) ++sizes.at(l);
    EXPECT_EQ(f.sizes, sizes) << "trial " << trial;
    EXPECT_GT(f.count(), 1) << "trial " << trial << ": a test that cannot tell fragments apart";
    if (trial % 3 == 0) {
      EXPECT_EQ(f.label[n - 1], f.label[0]);
    }
    // The neighbour-list route agrees with the positions route.
    ParticleSet<2> set;
    set.x = x.transpose();
    set.volume = Eigen::VectorXd::Constant(n, 0.5 / n);
    set.role.assign(n, Role::Free);
    EXPECT_EQ(fragments_of(find_neighbours_brute_force(set, radius)).label, expected) << "trial " << trial;
  }
}

TEST(Fragments, ReadsPositionsThroughAStridedMapOfAState) {
  // A state with 5 numbers per particle (x, y, then 3 others), as a run's y vector interleaves them.
  const CollidingRings rings = make_colliding_rings({.inner_radius = 1, .outer_radius = 1.5});
  const int n = rings.size(), stride = 5;
  Eigen::VectorXd y = Eigen::VectorXd::Constant(stride * n, 1e30);
  for (int i = 0; i < n; ++i) y.segment<2>(stride * i) = rings.particles.x.row(i).transpose();
  Eigen::Map<const Eigen::Matrix2Xd, 0, Eigen::OuterStride<>> x(y.data(), 2, n, Eigen::OuterStride<>(stride));
  const Fragments f = find_fragments(x, 0.15);
  EXPECT_EQ(f.count(), 2);
  EXPECT_EQ(f.label, rings.ring);
}

TEST(Fragments, EdgeCasesAndBadInput) {
  EXPECT_EQ(find_fragments(Eigen::Matrix2Xd(2, 0), 1.0).count(), 0);
  EXPECT_EQ(find_fragments(Eigen::Matrix2Xd(2, 0), 1.0).largest(), 0);
  const Eigen::Matrix2Xd one = Eigen::Matrix2Xd::Zero(2, 1);
  EXPECT_EQ(find_fragments(one, 1.0).sizes, std::vector<int>{1});
  // Points on a line 1 apart: bonded for radius > 1 only.
  Eigen::Matrix2Xd line(2, 4);
  line << 0, 1, 2, 3, 0, 0, 0, 0;
  EXPECT_EQ(find_fragments(line, 1.0).count(), 4);
  EXPECT_EQ(find_fragments(line, 1.0 + 1e-12).count(), 1);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(find_fragments(line, 0.0), std::invalid_argument);
  EXPECT_THROW(find_fragments(line, -1.0), std::invalid_argument);
  EXPECT_THROW(find_fragments(line, nan), std::invalid_argument);
  EXPECT_THROW(find_fragments(line, std::numeric_limits<double>::infinity()), std::invalid_argument);
  Eigen::Matrix2Xd bad = line;
  bad(1, 2) = nan;
  EXPECT_THROW(find_fragments(bad, 1.5), std::invalid_argument);
  NeighbourList list;
  list.offsets = {0, 2, 3};
  list.indices = {0, 2, 1};  // index 2 of a 2-particle list
  EXPECT_THROW(fragments_of(list), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
