#include "sphstab/particles/block_lattice.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {
namespace block_lattice_test {

// 7 x 3 free particles with the layers of the cubic spline at h = 1.3 dx (support 2.6: 2 layers): free block first,
// x fastest, at ((i + 1/2) dx, (j + 1/2) dx); 11 x 7 particles in all; every free neighbourhood complete.
TEST(BlockLattice, RectangleWithCompleteNeighbourhoods) {
  const Kernel<2> k(KernelType::CubicSpline);
  const double h = 1.3;
  const auto p = make_block_lattice_2d(7, 3, {.spacing = 1.0, .support_radius = k.support_radius(h)});
  ASSERT_EQ(p.size(), 11 * 7);
  ASSERT_EQ(p.count(Role::Free), 21);
  for (int j = 0, f = 0; j < 3; ++j)
    for (int i = 0; i < 7; ++i, ++f) {
      EXPECT_EQ(p.role[f], Role::Free);
      EXPECT_DOUBLE_EQ(p.x(f, 0), i + 0.5);
      EXPECT_DOUBLE_EQ(p.x(f, 1), j + 0.5);
    }
  // fixed particles: lexicographic (y, then x), inside [-2, 9] x [-2, 5]
  for (int f = 22; f < p.size(); ++f) {
    EXPECT_EQ(p.role[f], Role::Fixed);
    EXPECT_TRUE(p.x(f - 1, 1) < p.x(f, 1) || (p.x(f - 1, 1) == p.x(f, 1) && p.x(f - 1, 0) < p.x(f, 0)));
  }
  EXPECT_DOUBLE_EQ(p.x.col(0).minCoeff(), -1.5);
  EXPECT_DOUBLE_EQ(p.x.col(0).maxCoeff(), 8.5);
  EXPECT_DOUBLE_EQ(p.x.col(1).maxCoeff(), 4.5);
  EXPECT_EQ(p.depth[0], 2);  // free corner particle, two layers outside it
  const auto nl = find_neighbours(p, k.support_radius(h));
  const auto ops = assemble_operators(p, nl, k, h);
  for (int a = 0; a < 2; ++a) {
    const Eigen::VectorXd g = ops.G[a] * Eigen::VectorXd::Ones(p.size());
    EXPECT_LT(g.head(21).cwiseAbs().maxCoeff(), 1e-14);  // sum_j G_ij = 0: complete (0.5 exactly for a one-sided row)
  }
}

TEST(BlockLattice, RejectsBadInput) {
  EXPECT_THROW(make_block_lattice_2d(0, 3, {.support_radius = 2.6}), std::invalid_argument);
  EXPECT_THROW(make_block_lattice_2d(3, 3, {.periodic = true}), std::invalid_argument);
  EXPECT_THROW(make_block_lattice_2d(3, 3, {.support_radius = 2.6, .perturbation = 0.1}), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
