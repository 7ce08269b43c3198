#include "sphstab/operators/column_shepard.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "correction_fixture.hpp"
#include "sphstab/operators/shepard.hpp"

namespace sphstab {
namespace column_shepard_test {

using test::make_case;

template <int Dim>
void expect_columns_vanish(LatticeType type, int n) {
  auto c = make_case<Dim>(type, n, 1.3, 0.2, false, 0);
  for (int a = 0; a < Dim; ++a) {
    SparseMatrix<> gt = column_shepard_gradient(c.ops.W, c.ops.G[a]);
    const double col = test::max_abs(test::column_sums(gt)), row = test::max_abs(test::row_sums(gt));
    EXPECT_LT(col, 1e-13);  // column sums of O(1/h) entries: round-off
    // (3.62) trades the row property for the column one: rows do NOT sum to zero on this irregular set.
    EXPECT_GT(row, 1e-2);
    std::printf("column-shepard dim %d axis %d: max |column sum| %.2e, max |row sum| %.2e\n", Dim, a, col, row);
    EXPECT_LT(test::complex_mismatch(gt, column_shepard_gradient(c.cops.W, c.cops.G[a])), 1e-15);
  }
}

TEST(ColumnShepard, ColumnsSumToZeroRowsDoNot) {
  expect_columns_vanish<1>(LatticeType::Line, 20);
  expect_columns_vanish<2>(LatticeType::Square, 7);
  expect_columns_vanish<3>(LatticeType::Cubic, 3);
}

TEST(ColumnShepard, EqualsShepardOnRegularPeriodicLattice) {
  auto c = make_case<2>(LatticeType::Square, 8, 1.3, 0.0, true);
  for (int a = 0; a < 2; ++a) {
    Eigen::MatrixXd d = Eigen::MatrixXd(column_shepard_gradient(c.ops.W, c.ops.G[a])) -
                        Eigen::MatrixXd(shepard_gradient(c.ops.W, c.ops.G[a]));
    EXPECT_LT(d.cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(ColumnShepard, RejectsBadInput) {
  auto c = make_case<1>(LatticeType::Line, 6, 1.3, 0.0, false, 0);
  SparseMatrix<> small(3, 3);
  small.setIdentity();
  EXPECT_THROW(column_shepard_gradient(c.ops.W, small), std::invalid_argument);
  EXPECT_THROW(column_shepard_gradient(SparseMatrix<>(4, 4), SparseMatrix<>(4, 4)), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
