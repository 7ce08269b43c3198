// The CSM3 beam of Turek & Hron (problems/turek_hron_csm3.hpp): particle and clamp counts at 4 particles across
// (counted by hand in the comment), every free particle outside the cylinder and every clamp particle inside it and
// within the clamp width, the tip particles, and bad input.
#include "sphstab/problems/turek_hron_csm3.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sphstab {
namespace turek_hron_csm3_test {

using C = TurekHronCsm3;

TEST(TurekHronCsm3, AttachmentPointIsTheCylinderSurface) {
  EXPECT_NEAR(C::attachment_x(0.19), 0.2 + std::sqrt(0.05 * 0.05 - 0.01 * 0.01), 1e-15);
  EXPECT_NEAR(C::attachment_x(0.19), 0.2489898, 1e-7);
  EXPECT_DOUBLE_EQ(C::attachment_x(0.2), 0.25);
}

TEST(TurekHronCsm3, FourAcrossHas280FreeAnd16ClampParticles) {
  // dx = 0.005, rows y = 0.1925, 0.1975, 0.2025, 0.2075 (|y - 0.2| = 0.0075 or 0.0025): the cylinder surface is at
  // x = 0.249434 or 0.249938. Columns x_i = 0.6 - (i + 1/2) 0.005: x_69 = 0.2525 is outside, x_70 = 0.2475 inside
  // on every row, so 70 free particles per row (280). Clamp 4 dx = 0.02 deep: x_73 = 0.2325 (depth 0.0169 / 0.0174)
  // is in, x_74 = 0.2275 (depth 0.0219) out: 4 per row (16).
  const TurekHronBeam beam = turek_hron_beam({.across = 4, .clamp_layers = 4});
  EXPECT_DOUBLE_EQ(beam.dx, 0.005);
  EXPECT_EQ(beam.free_count, 280);
  EXPECT_EQ(beam.clamp_count, 16);
  const ParticleSet<2>& p = beam.particles;
  ASSERT_EQ(p.size(), 296);
  EXPECT_EQ(p.count(Role::Free), 280);
  for (int i = 0; i < p.size(); ++i) {
    const double r = std::hypot(p.x(i, 0) - C::cylinder_x, p.x(i, 1) - C::cylinder_y);
    const bool free = p.role[i] == Role::Free;
    EXPECT_EQ(free, i < 280) << i;  // free particles first
    if (free) {
      EXPECT_GE(r, C::radius) << i;
    } else {
      EXPECT_LT(r, C::radius) << i;
      EXPECT_LE(C::attachment_x(p.x(i, 1)) - p.x(i, 0), 4 * beam.dx + 1e-12) << i;
    }
    EXPECT_GT(p.x(i, 1), C::bottom_y);
    EXPECT_LT(p.x(i, 1), C::bottom_y + C::thickness);
    EXPECT_LT(p.x(i, 0), C::tip_x);
    EXPECT_DOUBLE_EQ(p.volume[i], 0.005 * 0.005);
  }
}

TEST(TurekHronCsm3, TipParticlesStraddleA) {
  for (int across : {4, 5}) {
    const TurekHronBeam beam = turek_hron_beam({.across = across});
    const std::size_t expected = across % 2 == 0 ? 2 : 1;
    for (int col = 0; col < 2; ++col) {
      ASSERT_EQ(beam.tip[col].size(), expected) << across;
      double ymean = 0;
      for (int f : beam.tip[col]) {
        EXPECT_EQ(beam.particles.role[f], Role::Free);
        EXPECT_NEAR(beam.particles.x(f, 0), C::tip_x - (col + 0.5) * beam.dx, 1e-15);
        ymean += beam.particles.x(f, 1) / static_cast<double>(expected);
      }
      EXPECT_NEAR(ymean, C::cylinder_y, 1e-15) << across;  // A is at the mean height of the tip particles
    }
  }
}

TEST(TurekHronCsm3, ClampWidthCountsColumns) {
  // a wider clamp adds exactly one particle per row and layer
  const TurekHronBeam a = turek_hron_beam({.across = 6, .clamp_layers = 3}),
                      b = turek_hron_beam({.across = 6, .clamp_layers = 5});
  EXPECT_EQ(a.free_count, b.free_count);
  EXPECT_EQ(b.clamp_count - a.clamp_count, 2 * 6);
}

TEST(TurekHronCsm3, RejectsBadInput) {
  EXPECT_THROW(turek_hron_beam({.across = 1}), std::invalid_argument);
  EXPECT_THROW(turek_hron_beam({.across = 4, .clamp_layers = 0}), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
