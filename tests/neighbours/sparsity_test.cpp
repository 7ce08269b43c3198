#include "sphstab/neighbours/sparsity.hpp"

#include <gtest/gtest.h>

#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace sparsity_test {

/// Dense boolean reachability within r hops, free block, for comparison.
Eigen::MatrixXi reach(const NeighbourList& nl, const std::vector<int>& free_slot, int r) {
  const int n = nl.size();
  Eigen::MatrixXi adj = Eigen::MatrixXi::Zero(n, n), R = Eigen::MatrixXi::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) adj(i, nl.indices[k]) = 1;
  for (int s = 0; s < r; ++s) R = ((R * adj).array() > 0).cast<int>();
  int nf = 0;
  for (int s : free_slot) nf += s >= 0;
  Eigen::MatrixXi out(nf, nf);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (free_slot[i] >= 0 && free_slot[j] >= 0) out(free_slot[i], free_slot[j]) = R(i, j);
  return out;
}

TEST(Sparsity, CouplingPatternIsGraphReachability) {
  auto set = make_lattice<2>(LatticeType::Hexagonal, 5, {.spacing = 1.0, .support_radius = 2.2, .perturbation = 0.1});
  auto nl = find_neighbours(set, 2.2);
  std::vector<int> slot(set.size(), -1);
  int f = 0;
  for (int i = 0; i < set.size(); ++i)
    if (set.role[i] == Role::Free) slot[i] = f++;
  for (int r : {0, 1, 2, 3}) {
    SparsityPattern p = coupling_pattern(nl, slot, 2, r);
    Eigen::MatrixXi ref = reach(nl, slot, r);
    ASSERT_EQ(p.rows, 2 * f);
    Eigen::MatrixXi got = Eigen::MatrixXi::Zero(2 * f, 2 * f);
    for (int row = 0; row < p.rows; ++row)
      for (long k = p.offsets[row]; k < p.offsets[row + 1]; ++k) {
        if (k > p.offsets[row]) EXPECT_LT(p.indices[k - 1], p.indices[k]);  // sorted, unique
        got(row, p.indices[k]) = 1;
      }
    for (int i = 0; i < f; ++i)
      for (int j = 0; j < f; ++j)
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) EXPECT_EQ(got(2 * i + a, 2 * j + b), ref(i, j)) << "r=" << r;
    std::vector<int> colours = colour_columns(p);
    EXPECT_TRUE(is_valid_column_colouring(p, colours));
  }
  EXPECT_THROW(coupling_pattern(nl, slot, 0, 1), std::invalid_argument);
  EXPECT_THROW(coupling_pattern(nl, slot, 1, -1), std::invalid_argument);
  EXPECT_THROW(coupling_pattern(nl, std::vector<int>(3, 0), 1, 1), std::invalid_argument);
}

TEST(Sparsity, ColouringValidityDetectsConflicts) {
  SparsityPattern p;
  p.rows = p.cols = 3;
  p.offsets = {0, 2, 3, 4};
  p.indices = {0, 2, 1, 2};
  EXPECT_TRUE(is_valid_column_colouring(p, {0, 0, 1}));
  EXPECT_FALSE(is_valid_column_colouring(p, {0, 1, 0}));  // row 0 has columns 0 and 2
  EXPECT_EQ(colour_count(colour_columns(p)), 2);
  SparsityPattern t = p.transpose();
  EXPECT_EQ(t.indices, (std::vector<int>{0, 1, 0, 2}));
}

}  // namespace
}  // namespace sphstab
