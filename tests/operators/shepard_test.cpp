#include "sphstab/operators/shepard.hpp"

#include <gtest/gtest.h>

#include "correction_fixture.hpp"

namespace sphstab {
namespace shepard_test {

using test::Complex;
using test::make_case;

template <int Dim>
void expect_shepard_properties(LatticeType type, int n) {
  // No fixed layers and perturbed: deficient surface neighbourhoods, sum_j W_ij far from 1.
  auto c = make_case<Dim>(type, n, 1.3, 0.2, false, 0);
  SparseMatrix<> wt = shepard_kernel(c.ops.W);
  EXPECT_GT(test::max_abs(test::row_sums(c.ops.W) - Eigen::VectorXd::Ones(c.set.size())), 0.1);
  EXPECT_LT(test::max_abs(test::row_sums(wt) - Eigen::VectorXd::Ones(c.set.size())), 1e-14);
  EXPECT_LT(test::complex_mismatch(wt, shepard_kernel(c.cops.W)), 1e-15);
  for (int a = 0; a < Dim; ++a) {
    SparseMatrix<> gt = shepard_gradient(c.ops.W, c.ops.G[a]);
    // Row sums of O(1/h) entries cancel to round-off.
    EXPECT_LT(test::max_abs(test::row_sums(gt)), 1e-13);
    EXPECT_LT(test::complex_mismatch(gt, shepard_gradient(c.cops.W, c.cops.G[a])), 1e-15);
  }
}

TEST(Shepard, KernelRowsSumToOneAndGradientRowsToZero) {
  expect_shepard_properties<1>(LatticeType::Line, 20);
  expect_shepard_properties<2>(LatticeType::Square, 7);
  expect_shepard_properties<2>(LatticeType::Hexagonal, 6);
  expect_shepard_properties<3>(LatticeType::Cubic, 3);
}

// (3.61) is the derivative of the Shepard kernel (1.14) with respect to x_i: check row i of the Shepard gradient
// against a complex step of particle i, pushed through assemble_operators and shepard_kernel.
TEST(Shepard, GradientIsTheComplexStepDerivativeOfTheShepardKernel) {
  auto c = make_case<2>(LatticeType::Square, 5, 1.4, 0.2, false, 0);
  Kernel<2> w(KernelType::CubicSpline);
  const double eps = 1e-30;
  for (int a = 0; a < 2; ++a) {
    SparseMatrix<> gt = shepard_gradient(c.ops.W, c.ops.G[a]);
    for (int i = 0; i < c.set.size(); i += 3) {
      Positions<2, Complex> x = c.set.x.cast<Complex>();
      x(i, a) += Complex(0, eps);
      auto ops = assemble_operators<2, Complex>(c.set, c.nl, w, 1.4, {true, false, false}, &x);
      SparseMatrix<Complex> wt = shepard_kernel(ops.W);
      for (SparseMatrix<Complex>::InnerIterator it(wt, i); it; ++it)
        EXPECT_NEAR(it.value().imag() / eps, gt.coeff(i, it.col()), 1e-14);
    }
  }
}

TEST(Shepard, RegularPeriodicLatticeKeepsAntisymmetry) {
  auto c = make_case<2>(LatticeType::Hexagonal, 8, 1.3, 0.0, true);
  const double s = test::row_sums(c.ops.W)[0];
  for (int a = 0; a < 2; ++a) {
    SparseMatrix<> gt = shepard_gradient(c.ops.W, c.ops.G[a]);
    // G~ = G / S on a regular lattice (S the same for all particles, sum_j G_ij = 0).
    EXPECT_LT((Eigen::MatrixXd(gt) - Eigen::MatrixXd(c.ops.G[a]) / s).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((Eigen::MatrixXd(gt) + Eigen::MatrixXd(gt).transpose()).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(Shepard, RawGradientIsAntisymmetricOnEqualVolumeSets) {
  auto c = make_case<2>(LatticeType::Square, 6, 1.3, 0.25, false);
  for (int a = 0; a < 2; ++a)
    EXPECT_LT((Eigen::MatrixXd(c.ops.G[a]) + Eigen::MatrixXd(c.ops.G[a]).transpose()).cwiseAbs().maxCoeff(), 1e-15);
  // ... while the Shepard gradient of the same (perturbed, equal-volume) set is not.
  SparseMatrix<> gt = shepard_gradient(c.ops.W, c.ops.G[0]);
  EXPECT_GT((Eigen::MatrixXd(gt) + Eigen::MatrixXd(gt).transpose()).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(Shepard, ReferenceGradientEqualsShepardGradientAtTheReference) {
  auto c = make_case<2>(LatticeType::Square, 6, 1.3, 0.2, false, 0);
  for (int a = 0; a < 2; ++a) {
    ShepardReference ref = shepard_reference(c.ops.W, c.ops.G[a]);
    SparseMatrix<> g1 = reference_shepard_gradient(c.ops.W, c.ops.G[a], ref);
    SparseMatrix<> g2 = shepard_gradient(c.ops.W, c.ops.G[a]);
    EXPECT_LT((Eigen::MatrixXd(g1) - Eigen::MatrixXd(g2)).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT(test::complex_mismatch(g1, reference_shepard_gradient(c.cops.W, c.cops.G[a], ref)), 1e-15);
  }
}

TEST(Shepard, RejectsBadInput) {
  auto c = make_case<1>(LatticeType::Line, 6, 1.3, 0.0, false, 0);
  SparseMatrix<> small(3, 3);
  small.setIdentity();
  EXPECT_THROW(shepard_gradient(c.ops.W, small), std::invalid_argument);  // size mismatch
  EXPECT_THROW(shepard_kernel(SparseMatrix<>(3, 4)), std::invalid_argument);
  SparseMatrix<> zero_row = c.ops.W;
  zero_row.prune([](int r, int, double) { return r != 2; });  // particle 2 loses every entry: S_2 = 0
  EXPECT_THROW(shepard_kernel(zero_row), std::invalid_argument);
  EXPECT_THROW(shepard_gradient(zero_row, c.ops.G[0]), std::invalid_argument);
  ShepardReference bad{Eigen::VectorXd::Ones(2), Eigen::VectorXd::Zero(2)};
  EXPECT_THROW(reference_shepard_gradient(c.ops.W, c.ops.G[0], bad), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
