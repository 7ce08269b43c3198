#include "sphstab/problems/plastic_slab.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sphstab {
namespace plastic_slab_test {

TEST(PlasticSlab, GmsGridIs188By63With13DrivenColumnsAtEachEnd) {
  const PlasticSlab slab = make_plastic_slab();
  // L / dp = 187.5 and W / dp = 62.5 round up.
  EXPECT_EQ(slab.columns, 188);
  EXPECT_EQ(slab.rows, 63);
  EXPECT_EQ(slab.size(), 188 * 63);
  const ParticleSet<2>& s = slab.particles;
  EXPECT_DOUBLE_EQ(s.spacing, 0.016);
  EXPECT_EQ(s.count(Role::Free), s.size());
  EXPECT_NEAR(s.volume.sum(), 11844 * 0.016 * 0.016, 1e-10);
  // Centred on the origin: columns at +-93.5 dp, rows at +-31 dp.
  EXPECT_NEAR(s.x.col(0).minCoeff(), -1.496, 1e-12);
  EXPECT_NEAR(s.x.col(0).maxCoeff(), 1.496, 1e-12);
  EXPECT_NEAR(s.x.col(1).minCoeff(), -0.496, 1e-12);
  EXPECT_NEAR(s.x.col(1).maxCoeff(), 0.496, 1e-12);
  EXPECT_NEAR(s.x(1, 1) - s.x(0, 1), 0.016, 1e-12);   // particle c n_y + r: rows within a column
  EXPECT_NEAR(s.x(63, 0) - s.x(0, 0), 0.016, 1e-12);  // next column
  EXPECT_EQ(*std::max_element(s.depth.begin(), s.depth.end()), 31);
  // The first column is 0.004 inside the nominal end x = -1.5: 0.004 + 12 dp = 0.196 <= 0.2 < 0.004 + 13 dp.
  ASSERT_EQ(slab.left_end.size(), 13u * 63u);
  ASSERT_EQ(slab.right_end.size(), 13u * 63u);
  ASSERT_EQ(slab.driven.size(), 2u * 13u * 63u);
  for (int k = 0; k < 13 * 63; ++k) {
    EXPECT_EQ(slab.left_end[k], k);
    EXPECT_EQ(slab.right_end[k], (188 - 13) * 63 + k);
  }
  // Driven exactly where the nominal distance from an end is <= 0.2, checked particle by particle.
  for (int p = 0; p < s.size(); ++p) {
    const bool left = std::count(slab.left_end.begin(), slab.left_end.end(), p) > 0;
    const bool right = std::count(slab.right_end.begin(), slab.right_end.end(), p) > 0;
    EXPECT_EQ(left, s.x(p, 0) + 1.5 <= 0.2) << p;
    EXPECT_EQ(right, 1.5 - s.x(p, 0) <= 0.2) << p;
  }
  ASSERT_EQ(slab.driven_acceleration.cols(), static_cast<Eigen::Index>(slab.driven.size()));
  for (std::size_t k = 0; k < slab.driven.size(); ++k) {
    EXPECT_EQ(slab.driven[k], k < slab.left_end.size() ? slab.left_end[k] : slab.right_end[k - slab.left_end.size()]);
    const double ax = slab.particles.x(slab.driven[k], 0) < 0 ? -5e-6 : 5e-6;
    EXPECT_EQ(slab.driven_acceleration.col(static_cast<Eigen::Index>(k)), Eigen::Vector2d(ax, 0)) << k;
  }
}

TEST(PlasticSlab, WholeNumberGridsAndOtherZones) {
  // dp = 0.02: exactly 150 x 50; first column 0.01 inside the end, 0.01 + 9 dp = 0.19 <= 0.2 < 0.21: 10 columns.
  const PlasticSlab a = make_plastic_slab({.spacing = 0.02});
  EXPECT_EQ(a.columns, 150);
  EXPECT_EQ(a.rows, 50);
  EXPECT_EQ(a.left_end.size(), 10u * 50u);
  EXPECT_EQ(a.right_end.size(), 10u * 50u);
  EXPECT_NEAR(a.particles.x.col(0).minCoeff(), -1.49, 1e-12);
  // dp = 0.025: 120 x 40, 0.0125 + 7 dp = 0.1875 <= 0.2: 8 columns. a = -1e-5 pushes the ends in.
  const PlasticSlab b = make_plastic_slab({.spacing = 0.025, .acceleration = -1e-5});
  EXPECT_EQ(b.columns, 120);
  EXPECT_EQ(b.rows, 40);
  EXPECT_EQ(b.left_end.size(), 8u * 40u);
  EXPECT_EQ(b.driven_acceleration(0, 0), 1e-5);
  EXPECT_EQ(b.driven_acceleration(0, b.driven_acceleration.cols() - 1), -1e-5);
  EXPECT_TRUE((b.driven_acceleration.row(1).array() == 0).all());
  // A zone that ends exactly on a column (to rounding) includes it: L = 1, dp = 0.1, zone 0.25 = 0.05 + 2 dp.
  const PlasticSlab c = make_plastic_slab({.length = 1, .width = 0.5, .spacing = 0.1, .end_zone = 0.25});
  EXPECT_EQ(c.columns, 10);
  EXPECT_EQ(c.rows, 5);
  EXPECT_EQ(c.left_end.size(), 3u * 5u);
  EXPECT_EQ(c.right_end.size(), 3u * 5u);
}

TEST(PlasticSlab, EndDisplacementIsHalfATSquared) {
  EXPECT_DOUBLE_EQ(slab_end_displacement(400), 0.4);          // [GMS2001, §7.3]: 2.5e-6 t^2, 0.4 at t = 400
  EXPECT_DOUBLE_EQ(slab_end_displacement(400) / 3, 0.4 / 3);  // GMS's "strain 0.13" (one end over L)
  EXPECT_DOUBLE_EQ(slab_end_displacement(2.0, 3.0), 6.0);
  EXPECT_DOUBLE_EQ(slab_end_displacement(0.0), 0.0);
  EXPECT_THROW(slab_end_displacement(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(slab_end_displacement(1.0, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST(PlasticSlab, RejectsEveryBadOption) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(make_plastic_slab({.length = 0}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.length = -3}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.length = nan}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.width = 0}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.width = inf}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.width = 0.01}), std::invalid_argument);  // one row
  EXPECT_NO_THROW(make_plastic_slab({.width = 0.02}));                      // two rows
  EXPECT_THROW(make_plastic_slab({.spacing = 0}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.spacing = -0.016}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.spacing = nan}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.end_zone = 0}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.end_zone = nan}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.end_zone = 1.5}), std::invalid_argument);    // 2 zones = L
  EXPECT_THROW(make_plastic_slab({.end_zone = 0.001}), std::invalid_argument);  // first column 0.004 from the end
  // L = 0.5, dp = 0.016: 32 columns, a zone of 0.249 takes 16 at each end, none is left free.
  EXPECT_THROW(make_plastic_slab({.length = 0.5, .end_zone = 0.249}), std::invalid_argument);
  EXPECT_NO_THROW(make_plastic_slab({.length = 0.5, .end_zone = 0.24}));
  EXPECT_THROW(make_plastic_slab({.acceleration = nan}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.acceleration = -inf}), std::invalid_argument);
  EXPECT_THROW(make_plastic_slab({.length = 3e-70, .width = 1e-70, .spacing = 1e-72, .end_zone = 1e-71}),
               std::invalid_argument);  // outside the supported length range
  try {
    make_plastic_slab({.end_zone = 1.5});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_EQ(std::string(e.what()).rfind("make_plastic_slab: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace sphstab
