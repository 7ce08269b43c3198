#include "sphstab/operators/local_polish.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "correction_fixture.hpp"
#include "sphstab/operators/shepard.hpp"

namespace sphstab {
namespace local_polish_test {

using test::Complex;
using test::make_case;

template <int Dim>
void expect_interior_unchanged(LatticeType type, int n) {
  // Regular lattice with complete fixed layers: C_ij = G_ij wherever i and all its neighbours are complete.
  auto c = make_case<Dim>(type, n, 1.3, 0.0, false);
  Eigen::VectorXd counts = neighbour_counts(c.set, c.nl, NeighbourCounting::Actual);
  const int reach = fixed_layers_needed(Kernel<Dim>(KernelType::CubicSpline).support_radius(1.3), 1.0);
  int checked = 0;
  for (int a = 0; a < Dim; ++a) {
    SparseMatrix<> cm = local_polish(c.ops.G[a], counts);
    for (int i = 0; i < c.set.size(); ++i) {
      if (c.set.depth[i] < 2 * reach) continue;
      ++checked;
      for (SparseMatrix<>::InnerIterator it(cm, i); it; ++it)
        EXPECT_NEAR(it.value(), c.ops.G[a].coeff(i, it.col()), 1e-13);
    }
  }
  EXPECT_GT(checked, 0);
  // Periodic regular lattice: every row is interior.
  auto p = make_case<Dim>(type, type == LatticeType::Cubic ? 6 : 8, 1.3, 0.0, true);
  Eigen::VectorXd pc = neighbour_counts(p.set, p.nl, NeighbourCounting::Actual);
  for (int a = 0; a < Dim; ++a)
    EXPECT_LT((Eigen::MatrixXd(local_polish(p.ops.G[a], pc)) - Eigen::MatrixXd(p.ops.G[a])).cwiseAbs().maxCoeff(),
              1e-13);
}

TEST(LocalPolish, RegularInteriorIsUnchanged) {
  expect_interior_unchanged<1>(LatticeType::Line, 16);
  expect_interior_unchanged<2>(LatticeType::Square, 10);
  expect_interior_unchanged<2>(LatticeType::Hexagonal, 10);
  expect_interior_unchanged<3>(LatticeType::Cubic, 8);
}

template <int Dim>
void expect_rows_vanish(LatticeType type, int n) {
  // Perturbed, no fixed layers (deficient surfaces), actual counts: sum_j C_ij = 0 for every i.
  auto c = make_case<Dim>(type, n, 1.3, 0.2, false, 0);
  Eigen::VectorXd counts = neighbour_counts(c.set, c.nl, NeighbourCounting::Actual);
  for (int a = 0; a < Dim; ++a) {
    SparseMatrix<> cm = local_polish(c.ops.G[a], counts);
    EXPECT_GT(test::max_abs(test::row_sums(c.ops.G[a])), 0.1);
    EXPECT_LT(test::max_abs(test::row_sums(cm)), 1e-12);
    EXPECT_LT(test::complex_mismatch(cm, local_polish(c.cops.G[a], counts)), 1e-15);
  }
}

TEST(LocalPolish, RowsSumToZeroWithActualCounts) {
  expect_rows_vanish<1>(LatticeType::Line, 20);
  expect_rows_vanish<2>(LatticeType::Square, 8);
  expect_rows_vanish<2>(LatticeType::Hexagonal, 8);
  expect_rows_vanish<3>(LatticeType::Cubic, 4);
}

// (4.9) as printed: last term = mean of the ROW means of the neighbours. Its rows do not sum to zero, which is why
// algorithm 4.1's column means are implemented.
TEST(LocalPolish, PrintedLastTermOf49BreaksTheRowSumProperty) {
  auto c = make_case<2>(LatticeType::Square, 8, 1.3, 0.2, false, 0);
  Eigen::VectorXd counts = neighbour_counts(c.set, c.nl, NeighbourCounting::Actual);
  const SparseMatrix<>& g = c.ops.G[0];
  LocalMeans<double> m = local_means(g, counts);
  LocalMeans<double> printed = m;
  for (int i = 0; i < g.rows(); ++i) {
    printed.mean_of_columns[i] = 0;
    for (SparseMatrix<>::InnerIterator it(g, i); it; ++it) printed.mean_of_columns[i] += m.row[it.col()];
    printed.mean_of_columns[i] /= counts[i];
  }
  const double ours = test::max_abs(test::row_sums(local_polish(g, m)));
  const double as_printed = test::max_abs(test::row_sums(local_polish(g, printed)));
  std::printf("max |sum_j C_ij|: algorithm 4.1 %.2e, (4.9) as printed %.2e\n", ours, as_printed);
  EXPECT_LT(ours, 1e-12);
  EXPECT_GT(as_printed, 1e-2);
}

TEST(LocalPolish, BoundaryLevelCountsFollowFigure43) {
  // 1D line without fixed layers, h = 1.3 dx (2 neighbours each side): the rule restores 5 everywhere.
  auto l = make_case<1>(LatticeType::Line, 10, 1.3, 0.0, false, 0);
  Eigen::VectorXd n1 = neighbour_counts(l.set, l.nl, NeighbourCounting::BoundaryLevel);
  EXPECT_EQ(n1, Eigen::VectorXd::Constant(10, 5.0));
  EXPECT_EQ(neighbour_counts(l.set, l.nl, NeighbourCounting::Actual)[0], 3.0);
  // Square lattice: a full neighbourhood has 21 members (|d| < 2.6). Flat edges are restored to 21, corners not.
  auto s = make_case<2>(LatticeType::Square, 10, 1.3, 0.0, false, 0);
  Eigen::VectorXd n2 = neighbour_counts(s.set, s.nl, NeighbourCounting::BoundaryLevel);
  auto index = [](int ix, int iy) { return iy * 10 + ix; };  // free block ordering, lexicographic in x first
  EXPECT_EQ(s.set.x(index(3, 0), 0), 3.5);
  EXPECT_EQ(n2[index(5, 5)], 21.0);  // interior
  EXPECT_EQ(n2[index(5, 0)], 21.0);  // edge, depth 0 (13 actual neighbours)
  EXPECT_EQ(n2[index(5, 1)], 21.0);  // depth 1
  EXPECT_EQ(n2[index(0, 0)], 11.0);  // corner (8 actual neighbours)
  EXPECT_EQ(neighbour_counts(s.set, s.nl, NeighbourCounting::Actual)[index(0, 0)], 8.0);
}

TEST(LocalPolish, RowSumsWithBoundaryLevelCountsAreReported) {
  auto c = make_case<2>(LatticeType::Square, 8, 1.3, 0.2, false, 0);
  Eigen::VectorXd actual = neighbour_counts(c.set, c.nl, NeighbourCounting::Actual);
  Eigen::VectorXd level = neighbour_counts(c.set, c.nl, NeighbourCounting::BoundaryLevel);
  SparseMatrix<> cm = local_polish(c.ops.G[0], level);
  Eigen::VectorXd sums = test::row_sums(cm);
  double worst_changed = 0, worst_same = 0, worst_raw = test::max_abs(test::row_sums(c.ops.G[0]));
  for (int i = 0; i < c.set.size(); ++i) {
    double& worst = level[i] != actual[i] ? worst_changed : worst_same;
    worst = std::max(worst, std::abs(sums[i]));
  }
  std::printf("Fig. 4.3 counts: max |sum_j C_ij| %.3e on re-counted particles, %.1e elsewhere (raw G: %.3e)\n",
              worst_changed, worst_same, worst_raw);
  RecordProperty("fig43_row_sum_recounted", std::to_string(worst_changed));
  EXPECT_LT(worst_same, 1e-12);         // unchanged counts: the proof holds
  EXPECT_GT(worst_changed, 1e-2);       // re-counted particles: sum_j C_ij = (1 - |N(i)|/n_i)(...) != 0
  EXPECT_LT(worst_changed, worst_raw);  // but smaller than the raw deficiency here
}

TEST(LocalPolish, FirstStepShepardOption418) {
  auto c = make_case<2>(LatticeType::Square, 8, 1.3, 0.0, false, 0);
  Eigen::VectorXd counts = neighbour_counts(c.set, c.nl, NeighbourCounting::Actual);
  for (int a = 0; a < 2; ++a) {
    ShepardReference ref = shepard_reference(c.ops.W, c.ops.G[a]);
    SparseMatrix<> gm = reference_shepard_gradient(c.ops.W, c.ops.G[a], ref);
    SparseMatrix<> c418 = local_polish(c.ops.G[a], local_means(gm, counts));
    SparseMatrix<> plain = local_polish(c.ops.G[a], counts);
    // In the reference configuration, sum_j C_ij = sum_j G_ij (the raw row sum), not zero.
    EXPECT_LT(test::max_abs(test::row_sums(c418) - test::row_sums(c.ops.G[a])), 1e-13);
    const double d418 = (Eigen::MatrixXd(c418) - Eigen::MatrixXd(c.ops.G[a])).cwiseAbs().maxCoeff();
    const double dplain = (Eigen::MatrixXd(plain) - Eigen::MatrixXd(c.ops.G[a])).cwiseAbs().maxCoeff();
    const double gmax = Eigen::MatrixXd(c.ops.G[a]).cwiseAbs().maxCoeff();
    std::printf("axis %d: max |C_ij(0) - G_ij(0)| = %.3e with (4.18), %.3e without (max |G| %.3e)\n", a, d418, dplain,
                gmax);
    // Powell claims C_ij(0) = grad W_ij(0) for all i, j with (4.18). It does not hold: the row means of the
    // Shepard gradient vanish at t = 0, but its column means do not near the surface, so C_ij(0) - G_ij(0) =
    // m_i - c_j != 0 there (here even larger than without (4.18): 0.085 vs 0.059 with max |G| = 0.20).
    EXPECT_GT(d418, 0.1 * gmax);
    EXPECT_GT(dplain, 0.1 * gmax);
    SparseMatrix<Complex> gmc = reference_shepard_gradient(c.cops.W, c.cops.G[a], ref);
    EXPECT_LT(test::complex_mismatch(c418, local_polish(c.cops.G[a], local_means(gmc, counts))), 1e-15);
  }
}

TEST(LocalPolish, RejectsBadInput) {
  auto c = make_case<1>(LatticeType::Line, 6, 1.3, 0.0, false, 0);
  auto d = make_case<1>(LatticeType::Line, 4, 1.3, 0.0, false, 0);
  EXPECT_THROW(local_polish(c.ops.G[0], Eigen::VectorXd::Ones(3)), std::invalid_argument);
  EXPECT_THROW(local_polish(c.ops.G[0], Eigen::VectorXd::Zero(6)), std::invalid_argument);
  EXPECT_THROW(neighbour_counts(d.set, c.nl, NeighbourCounting::Actual), std::invalid_argument);
  ParticleSet<1> no_depth = c.set;
  no_depth.depth.clear();
  EXPECT_THROW(neighbour_counts(no_depth, c.nl, NeighbourCounting::BoundaryLevel), std::invalid_argument);
  LocalMeans<double> m = local_means(d.ops.G[0], Eigen::VectorXd::Ones(4));
  EXPECT_THROW(local_polish(c.ops.G[0], m), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
