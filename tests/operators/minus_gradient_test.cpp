#include "sphstab/operators/minus_gradient.hpp"

#include <gtest/gtest.h>

#include <random>

#include "correction_fixture.hpp"

namespace sphstab {
namespace minus_gradient_test {

using test::make_case;

template <int Dim>
void expect_minus_properties(LatticeType type, int n) {
  // Perturbed lattice without fixed layers: the raw G rows do not sum to zero near the surface.
  auto c = make_case<Dim>(type, n, 1.3, 0.2, false, 0);
  for (int a = 0; a < Dim; ++a) {
    SparseMatrix<> gm = minus_gradient(c.ops.G[a]);
    EXPECT_GT(test::max_abs(test::row_sums(c.ops.G[a])), 0.1);  // the correction has something to correct
    // Gradient of a constant vanishes (row sums of O(1) entries: round-off only).
    EXPECT_LT(test::max_abs(test::row_sums(gm)), 1e-13);
    // Two routes to (1.15): the matrix times f, and sum_j (f_j - f_i) G_ij evaluated pairwise.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::VectorXd f(c.set.size());
    for (auto& v : f) v = u(rng);
    Eigen::VectorXd direct = Eigen::VectorXd::Zero(c.set.size());
    for (int i = 0; i < c.ops.G[a].outerSize(); ++i)
      for (SparseMatrix<>::InnerIterator it(c.ops.G[a], i); it; ++it) direct[i] += (f[it.col()] - f[i]) * it.value();
    EXPECT_LT(test::max_abs(gm * f - direct), 1e-13);
    // Complex-step instantiation agrees with the double one for real inputs.
    EXPECT_LT(test::complex_mismatch(gm, minus_gradient(c.cops.G[a])), 1e-15);
  }
}

TEST(MinusGradient, ConstantFieldHasZeroGradient) {
  expect_minus_properties<1>(LatticeType::Line, 20);
  expect_minus_properties<2>(LatticeType::Square, 7);
  expect_minus_properties<2>(LatticeType::Hexagonal, 6);
  expect_minus_properties<3>(LatticeType::Cubic, 3);
}

TEST(MinusGradient, InsertsAMissingDiagonal) {
  SparseMatrix<> g(3, 3);
  g.insert(0, 1) = 2.0;
  g.insert(1, 0) = -2.0;
  g.insert(2, 0) = 5.0;
  g.insert(2, 2) = 1.0;
  g.makeCompressed();
  Eigen::MatrixXd m = minus_gradient(g);
  Eigen::MatrixXd expected(3, 3);
  expected << -2, 2, 0, -2, 2, 0, 5, 0, -5;
  EXPECT_EQ(m, expected);
}

TEST(MinusGradient, RejectsBadInput) {
  EXPECT_THROW(minus_gradient(SparseMatrix<>(2, 3)), std::invalid_argument);
  EXPECT_THROW(minus_gradient(SparseMatrix<>(0, 0)), std::invalid_argument);
  SparseMatrix<> g(2, 2);
  g.insert(0, 1) = std::nan("");
  EXPECT_THROW(minus_gradient(g), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
