#include "sphstab/operators/mean_polish.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "correction_fixture.hpp"
#include "sphstab/operators/shepard.hpp"

namespace sphstab {
namespace mean_polish_test {

using test::Complex;
using test::make_case;

double max_row_sum(const Eigen::MatrixXd& a) { return a.rowwise().sum().cwiseAbs().maxCoeff(); }
double max_col_sum(const Eigen::MatrixXd& a) { return a.colwise().sum().cwiseAbs().maxCoeff(); }

// (3.64) written out, an independent route to algorithm 3.1.
Eigen::MatrixXd closed_form_364(const Eigen::MatrixXd& a) {
  const double n = static_cast<double>(a.rows());
  Eigen::VectorXd r = a.rowwise().sum() / n;
  Eigen::RowVectorXd c = a.colwise().sum() / n;
  Eigen::MatrixXd out = a;
  for (int i = 0; i < a.rows(); ++i)
    for (int j = 0; j < a.cols(); ++j) out(i, j) = a(i, j) - r[i] - c[j] + r.sum() / n;
  return out;
}

template <int Dim>
void expect_polished(LatticeType type, int n) {
  auto c = make_case<Dim>(type, n, 1.3, 0.2, false);
  for (int a = 0; a < Dim; ++a) {
    Eigen::MatrixXd p = mean_polish(c.ops.G[a]);
    EXPECT_LT(max_row_sum(p), 1e-12);
    EXPECT_LT(max_col_sum(p), 1e-12);
    EXPECT_LT((p - closed_form_364(Eigen::MatrixXd(c.ops.G[a]))).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((mean_polish<double>(p) - p).cwiseAbs().maxCoeff(), 1e-14);  // idempotent
    Eigen::MatrixXcd pc = mean_polish(c.cops.G[a]);
    EXPECT_LT((pc - p.cast<Complex>()).cwiseAbs().maxCoeff(), 1e-15);

    Eigen::MatrixXd sp = shepard_column_polish(c.ops.W, c.ops.G[a]);
    EXPECT_LT(max_row_sum(sp), 1e-12);
    EXPECT_LT(max_col_sum(sp), 1e-12);
    // Column polish of the Shepard gradient, written out.
    Eigen::MatrixXd gt(shepard_gradient(c.ops.W, c.ops.G[a]));
    Eigen::MatrixXd expected = gt.rowwise() - gt.colwise().mean();
    EXPECT_LT((sp - expected).cwiseAbs().maxCoeff(), 1e-15);
    Eigen::MatrixXcd spc = shepard_column_polish(c.cops.W, c.cops.G[a]);
    EXPECT_LT((spc - sp.cast<Complex>()).cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(MeanPolish, RowsAndColumnsSumToZero) {
  expect_polished<1>(LatticeType::Line, 20);
  expect_polished<2>(LatticeType::Square, 6);
  expect_polished<2>(LatticeType::Hexagonal, 6);
  expect_polished<3>(LatticeType::Cubic, 3);
}

TEST(MeanPolish, LeavesRegularPeriodicGradientUnchanged) {
  // Rows and columns of G already sum to zero (regular, antisymmetric): nothing to polish, no fill.
  auto c = make_case<2>(LatticeType::Square, 8, 1.3, 0.0, true);
  Eigen::MatrixXd p = mean_polish(c.ops.G[0]);
  EXPECT_LT((p - Eigen::MatrixXd(c.ops.G[0])).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(MeanPolish, FillIsReportedAndDense) {
  auto c = make_case<1>(LatticeType::Line, 30, 1.3, 0.1, false);
  Eigen::MatrixXd p = mean_polish(c.ops.G[0]);
  PolishFill f = polish_fill(c.ops.G[0], p);
  const long n = c.set.size();
  EXPECT_EQ(f.size, n);
  EXPECT_EQ(f.stored_before, c.nl.nonzeros());
  EXPECT_EQ(f.nonzero_before, c.nl.nonzeros() - n);  // G_ii = 0 stored explicitly
  // Every off-diagonal entry is filled ("action at a distance"). For an antisymmetric G (equal volumes)
  // c_j = -r_j and the mean vanishes, so the polish is G_ij - r_i + r_j: still antisymmetric, its diagonal is
  // zero up to round-off (some of those entries come out exactly 0, some at 1e-17).
  EXPECT_GE(f.nonzero_after, n * (n - 1));
  EXPECT_LT(p.diagonal().cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((p + p.transpose()).cwiseAbs().maxCoeff(), 1e-15);
  std::printf("mean polish fill (1D, N = %ld): %ld stored -> %ld non-zero\n", n, f.stored_before, f.nonzero_after);
  SparseMatrix<> s = dense_to_sparse_all_entries(p);
  EXPECT_EQ(s.nonZeros(), n * n);
  EXPECT_EQ(Eigen::MatrixXd(s), p);
}

TEST(MeanPolish, FreeSubsetPolishesTheFreeBlockOnly) {
  auto c = make_case<2>(LatticeType::Square, 5, 1.3, 0.2, false);
  std::vector<int> free = c.set.indices(Role::Free);
  Eigen::MatrixXd g(c.ops.G[0]);
  Eigen::MatrixXd p = mean_polish(c.ops.G[0], free);
  const int nf = static_cast<int>(free.size());
  ASSERT_EQ(free.back(), nf - 1);  // free particles come first
  EXPECT_LT(max_row_sum(p.topLeftCorner(nf, nf)), 1e-12);
  EXPECT_LT(max_col_sum(p.topLeftCorner(nf, nf)), 1e-12);
  EXPECT_LT((p - closed_form_364(g.topLeftCorner(nf, nf))).topLeftCorner(nf, nf).cwiseAbs().maxCoeff(), 1e-14);
  // Entries with a fixed index are untouched.
  EXPECT_EQ(p.rightCols(p.cols() - nf), g.rightCols(g.cols() - nf));
  EXPECT_EQ(p.bottomRows(p.rows() - nf), g.bottomRows(g.rows() - nf));
}

TEST(MeanPolish, RejectsBadInput) {
  EXPECT_THROW(mean_polish<double>(Eigen::MatrixXd(2, 3)), std::invalid_argument);
  EXPECT_THROW(mean_polish<double>(Eigen::MatrixXd(0, 0)), std::invalid_argument);
  Eigen::MatrixXd a = Eigen::MatrixXd::Ones(3, 3);
  EXPECT_THROW(mean_polish<double>(a, {0, 3}), std::invalid_argument);
  EXPECT_THROW(mean_polish<double>(a, {1, 1}), std::invalid_argument);
  EXPECT_THROW(row_mean_polish<double>(a, {-1}), std::invalid_argument);
  a(1, 1) = std::nan("");
  EXPECT_THROW(column_mean_polish<double>(a), std::invalid_argument);
  EXPECT_THROW(polish_fill(SparseMatrix<>(3, 3), Eigen::MatrixXd(2, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
