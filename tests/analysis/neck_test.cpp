#include "sphstab/analysis/neck.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "sphstab/problems/plastic_slab.hpp"

namespace sphstab {
namespace neck_test {

constexpr double kDp = 0.016;

/// A slab with some particles removed: positions (2 x N) and the end lists renumbered.
struct Cut {
  Eigen::Matrix2Xd x;
  std::vector<int> left, right;
};

/// Keeps the particles p of the GMS slab (column c = p / 63, row r = p % 63, r = 31 on y = 0) with keep(c, r).
Cut cut_slab(const PlasticSlab& slab, const std::function<bool(int, int)>& keep) {
  std::vector<int> new_index(slab.size(), -1);
  std::vector<int> idx;
  for (int p = 0; p < slab.size(); ++p)
    if (keep(p / slab.rows, p % slab.rows)) {
      new_index[p] = static_cast<int>(idx.size());
      idx.push_back(p);
    }
  Cut cut;
  cut.x.resize(2, static_cast<Eigen::Index>(idx.size()));
  for (std::size_t k = 0; k < idx.size(); ++k) cut.x.col(static_cast<Eigen::Index>(k)) = slab.particles.x.row(idx[k]);
  for (int p : slab.left_end)
    if (new_index[p] >= 0) cut.left.push_back(new_index[p]);
  for (int p : slab.right_end)
    if (new_index[p] >= 0) cut.right.push_back(new_index[p]);
  return cut;
}

const SlabNeckOptions kOptions{.bin_width = kDp, .particle_size = kDp, .bond_radius = 1.5 * kDp};

TEST(Neck, AnUnstrainedSlabIsOneWideEverywhere) {
  const PlasticSlab slab = make_plastic_slab();
  const SlabNeck neck = slab_neck(slab.particles.x.transpose(), slab.left_end, slab.right_end, kOptions);
  const NeckProfile& p = neck.profile;
  // Free columns 13 .. 174 (162), one per bin, each bin centred on its column.
  ASSERT_EQ(p.width.size(), 162u);
  EXPECT_NEAR(p.bin_width, kDp, 1e-15);
  EXPECT_NEAR(p.x_lo, slab.particles.x(12 * 63, 0) + kDp / 2, 1e-12);
  EXPECT_NEAR(p.x_hi, slab.particles.x(175 * 63, 0) - kDp / 2, 1e-12);
  for (std::size_t k = 0; k < p.width.size(); ++k) {
    EXPECT_EQ(p.count[k], 63) << k;
    EXPECT_NEAR(p.width[k], 63 * kDp, 1e-12) << k;  // 62 dp between the outer rows + dp
    EXPECT_NEAR(p.centre[k], slab.particles.x((13 + static_cast<int>(k)) * 63, 0), 1e-12) << k;
  }
  EXPECT_NEAR(p.min_width, 1.008, 1e-12);
  EXPECT_LE(std::abs(p.min_width - 1.0), kDp);  // the nominal width W = 1, to a spacing
  EXPECT_EQ(p.min_bin, 0);                      // all equal: the first bin
  EXPECT_FALSE(neck.broken);
  EXPECT_EQ(neck.fragments.count(), 1);
}

TEST(Neck, FindsAHandMadeNeckItsWidthAndPlace) {
  const PlasticSlab slab = make_plastic_slab();
  // A flat neck: columns 90 .. 97 keep rows 31 +- 18 (37 rows): width 37 dp.
  const Cut flat = cut_slab(slab, [](int c, int r) { return c < 90 || c > 97 || std::abs(r - 31) <= 18; });
  const SlabNeck a = slab_neck(flat.x, flat.left, flat.right, kOptions);
  EXPECT_NEAR(a.profile.min_width, 37 * kDp, 1e-12);
  EXPECT_NEAR(a.profile.min_x, slab.particles.x(90 * 63, 0), 1e-12);  // the first of the equal bins
  EXPECT_FALSE(a.broken);
  // A V-shaped neck, narrowest (21 rows) at column 94 alone, the same at its mirror position.
  auto v_neck = [](int c, int r) { return std::abs(r - 31) <= 10 + std::abs(c - 94); };
  const Cut v = cut_slab(slab, v_neck);
  const SlabNeck b = slab_neck(v.x, v.left, v.right, kOptions);
  EXPECT_NEAR(b.profile.min_width, 21 * kDp, 1e-12);
  EXPECT_NEAR(b.profile.min_x, slab.particles.x(94 * 63, 0), 1e-12);
  EXPECT_EQ(b.profile.min_bin, 94 - 13);
  EXPECT_NEAR(b.profile.width[95 - 13], 23 * kDp, 1e-12);
  EXPECT_FALSE(b.broken);
  const Cut v_mirror = cut_slab(slab, [&](int c, int r) { return v_neck(187 - c, r); });
  EXPECT_NEAR(slab_neck(v_mirror.x, v_mirror.left, v_mirror.right, kOptions).profile.min_x,
              slab.particles.x((187 - 94) * 63, 0), 1e-12);
}

TEST(Neck, StretchedColumnsLeaveEmptyBinsThatDoNotCount) {
  const PlasticSlab slab = make_plastic_slab();
  Eigen::Matrix2Xd x = slab.particles.x.transpose();
  x.row(0) *= 1.13;  // columns 1.13 dp apart: some bins of width dp hold no column
  const SlabNeck fine = slab_neck(x, slab.left_end, slab.right_end, kOptions);
  int empty = 0;
  for (std::size_t k = 0; k < fine.profile.width.size(); ++k)
    if (fine.profile.count[k] == 0) {
      ++empty;
      EXPECT_TRUE(std::isnan(fine.profile.width[k])) << k;
    } else {
      EXPECT_NEAR(fine.profile.width[k], 63 * kDp, 1e-12) << k;
    }
  EXPECT_GT(empty, 10);
  EXPECT_NEAR(fine.profile.min_width, 63 * kDp, 1e-12);  // not 0 from an empty bin
  SlabNeckOptions coarse_options = kOptions;
  coarse_options.bin_width = 2 * kDp;
  const SlabNeck coarse = slab_neck(x, slab.left_end, slab.right_end, coarse_options);
  for (int c : coarse.profile.count) EXPECT_GT(c, 0);
  // Bonds of 1.5 dp still hold columns 1.13 dp apart; bonds of 1.1 dp do not.
  EXPECT_FALSE(coarse.broken);
  coarse_options.bond_radius = 1.1 * kDp;
  EXPECT_TRUE(slab_neck(x, slab.left_end, slab.right_end, coarse_options).broken);
}

TEST(Neck, BreakFlagNeedsTheEndsInDifferentFragments) {
  const PlasticSlab slab = make_plastic_slab();
  // Split in two: columns 93 .. 95 removed (the halves are 4 dp apart).
  const Cut split = cut_slab(slab, [](int c, int) { return c < 93 || c > 95; });
  const SlabNeck s = slab_neck(split.x, split.left, split.right, kOptions);
  EXPECT_TRUE(s.broken);
  EXPECT_EQ(s.fragments.count(), 2);
  EXPECT_EQ(s.fragments.sizes, (std::vector<int>{93 * 63, 92 * 63}));
  // A one-column crack (2 dp between the halves) is bridged by bonds of 2.5 dp, not of 1.5 dp.
  const Cut crack = cut_slab(slab, [](int c, int) { return c != 100; });
  EXPECT_TRUE(slab_neck(crack.x, crack.left, crack.right, kOptions).broken);
  SlabNeckOptions wide = kOptions;
  wide.bond_radius = 2.5 * kDp;
  EXPECT_FALSE(slab_neck(crack.x, crack.left, crack.right, wide).broken);
  // A block cut loose in the middle (a moat 2 cells wide around columns 80 .. 84, rows 25 .. 35) is a second
  // fragment, but the ends are still joined: not broken.
  const Cut island = cut_slab(slab, [](int c, int r) {
    const bool block = c >= 80 && c <= 84 && r >= 25 && r <= 35;
    const bool moat = c >= 78 && c <= 86 && r >= 23 && r <= 37 && !block;
    return !moat;
  });
  const SlabNeck i = slab_neck(island.x, island.left, island.right, kOptions);
  EXPECT_EQ(i.fragments.count(), 2);
  EXPECT_EQ(i.fragments.sizes[1], 5 * 11);
  EXPECT_FALSE(i.broken);
  // The intact slab: one fragment, not broken.
  EXPECT_FALSE(slab_neck(slab.particles.x.transpose(), slab.left_end, slab.right_end, kOptions).broken);
}

TEST(Neck, EndsSeparatedOnHandMadeFragments) {
  Fragments f;
  f.label = {0, 0, 1, 1, 2};
  f.sizes = {2, 2, 1};
  EXPECT_FALSE(ends_separated(f, {0}, {1}));
  EXPECT_TRUE(ends_separated(f, {0, 1}, {2, 3}));
  EXPECT_FALSE(ends_separated(f, {0, 4}, {2, 4}));  // fragment 2 holds both
  EXPECT_TRUE(ends_separated(f, {4}, {0, 3}));
  EXPECT_THROW(ends_separated(f, {}, {1}), std::invalid_argument);
  EXPECT_THROW(ends_separated(f, {0}, {5}), std::invalid_argument);
  EXPECT_THROW(ends_separated(f, {-1}, {1}), std::invalid_argument);
}

TEST(Neck, ProfileBinsAndBadInput) {
  // Three particles per bin edge case: x_hi itself goes in the last bin; outside [x_lo, x_hi] is ignored.
  Eigen::Matrix2Xd x(2, 5);
  x << 0.0, 0.5, 1.0, 1.5, 2.5,  //
      0.0, 1.0, -1.0, 2.0, 9.0;
  const NeckProfile p = neck_profile(x, 0.0, 1.0, 0.5, 0.1);
  ASSERT_EQ(p.width.size(), 2u);
  EXPECT_EQ(p.count, (std::vector<int>{1, 2}));
  EXPECT_NEAR(p.width[0], 0.1, 1e-15);
  EXPECT_NEAR(p.width[1], 2.1, 1e-15);
  EXPECT_EQ(p.min_bin, 0);
  EXPECT_NEAR(p.min_x, 0.25, 1e-15);
  // The requested width is rounded so that the bins tile the range: 1 / 0.3 -> 3 bins of 1/3.
  EXPECT_NEAR(neck_profile(x, 0.0, 1.0, 0.3, 0.0).bin_width, 1.0 / 3, 1e-15);
  // All bins empty: no minimum.
  const NeckProfile none = neck_profile(x, 3.0, 4.0, 0.5, 0.0);
  EXPECT_EQ(none.min_bin, -1);
  EXPECT_TRUE(std::isnan(none.min_width));

  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(neck_profile(x, 1.0, 1.0, 0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(neck_profile(x, 1.0, 0.0, 0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(neck_profile(x, nan, 1.0, 0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(neck_profile(x, 0.0, inf, 0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(neck_profile(x, 0.0, 1.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(neck_profile(x, 0.0, 1.0, -0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(neck_profile(x, 0.0, 1.0, nan, 0.0), std::invalid_argument);
  EXPECT_THROW(neck_profile(x, 0.0, 1.0, 1e-12, 0.0), std::invalid_argument);  // 1e12 bins
  EXPECT_THROW(neck_profile(x, 0.0, 1.0, 0.5, -0.1), std::invalid_argument);
  EXPECT_THROW(neck_profile(x, 0.0, 1.0, 0.5, nan), std::invalid_argument);
  Eigen::Matrix2Xd bad = x;
  bad(0, 1) = nan;
  EXPECT_THROW(neck_profile(bad, 0.0, 1.0, 0.5, 0.0), std::invalid_argument);

  const PlasticSlab slab = make_plastic_slab({.spacing = 0.05});
  const Eigen::Matrix2Xd sx = slab.particles.x.transpose();
  const SlabNeckOptions ok{.bin_width = 0.05, .particle_size = 0.05, .bond_radius = 0.075};
  EXPECT_NO_THROW(slab_neck(sx, slab.left_end, slab.right_end, ok));
  for (SlabNeckOptions o :
       {SlabNeckOptions{0.0, 0.05, 0.075}, SlabNeckOptions{nan, 0.05, 0.075}, SlabNeckOptions{0.05, -1.0, 0.075},
        SlabNeckOptions{0.05, inf, 0.075}, SlabNeckOptions{0.05, 0.05, 0.0}, SlabNeckOptions{0.05, 0.05, nan}})
    EXPECT_THROW(slab_neck(sx, slab.left_end, slab.right_end, o), std::invalid_argument);
  EXPECT_THROW(slab_neck(sx, {}, slab.right_end, ok), std::invalid_argument);
  EXPECT_THROW(slab_neck(sx, slab.left_end, {static_cast<int>(sx.cols())}, ok), std::invalid_argument);
  EXPECT_THROW(slab_neck(sx, slab.right_end, slab.left_end, ok), std::invalid_argument);  // ends swapped: no range
  Eigen::Matrix2Xd sbad = sx;
  sbad(1, 7) = inf;
  EXPECT_THROW(slab_neck(sbad, slab.left_end, slab.right_end, ok), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
