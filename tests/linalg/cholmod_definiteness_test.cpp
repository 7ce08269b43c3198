#include "sphstab/linalg/cholmod_definiteness.hpp"

#include <gtest/gtest.h>

#include <random>

#include "sphstab/linalg/dense_symmetric_eigen.hpp"

namespace sphstab {
namespace cholmod_definiteness_test {

/// Random sparse symmetric matrix Q D Q^T restricted to a band: here built as B^T B + shift I with a random sparse
/// B, so that its smallest eigenvalue can be placed on either side of zero by the shift.
ColSparseMatrix random_symmetric(int n, double shift, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) t.emplace_back(i, std::uniform_int_distribution<int>(0, n - 1)(rng), u(rng));
  ColSparseMatrix b(n, n);
  b.setFromTriplets(t.begin(), t.end());
  ColSparseMatrix eye(n, n);
  eye.setIdentity();
  ColSparseMatrix a = ColSparseMatrix(b.transpose()) * b + shift * eye;
  a.makeCompressed();
  return a;
}

TEST(CholmodDefiniteness, AgreesWithDenseEigenvaluesOnRandomMatrices) {
  std::mt19937_64 rng(20261122);
  int positive = 0, negative = 0;
  for (CholmodVariant variant : {CholmodVariant::Simplicial, CholmodVariant::Supernodal}) {
    for (int trial = 0; trial < 40; ++trial) {
      const int n = 5 + trial * 3;
      ColSparseMatrix a0 = random_symmetric(n, 0.0, rng);
      const double lmin0 = symmetric_eigen(Eigen::MatrixXd(a0)).values[0];
      // Shift so that the smallest eigenvalue is +-(0.01 .. 0.5): clear of the rounding band.
      const double target = (trial % 2 == 0 ? 1 : -1) * (0.01 + 0.49 * (trial % 7) / 6.0);
      ColSparseMatrix eye(n, n);
      eye.setIdentity();
      ColSparseMatrix a = a0 + (target - lmin0) * eye;
      a.makeCompressed();
      const double lmin = symmetric_eigen(Eigen::MatrixXd(a)).values[0];
      ASSERT_NEAR(lmin, target, 1e-9);
      ColSparseMatrix lower = lower_triangle(a);
      lower.makeCompressed();
      CholmodDefiniteness check(variant);
      check.analyze_pattern(lower);
      const bool pd = check.is_positive_definite(lower);
      EXPECT_EQ(pd, lmin > 0) << "n = " << n << " lambda_min = " << lmin;
      EXPECT_EQ(check.info(), pd ? Status::Successful : Status::NumericalIssue);
      if (!pd) EXPECT_LT(check.failed_column(), n);
      EXPECT_EQ(is_positive_definite(a, variant), pd);
      (pd ? positive : negative)++;
    }
  }
  EXPECT_GT(positive, 10);
  EXPECT_GT(negative, 10);
}

TEST(CholmodDefiniteness, RefactorisesWithNewValuesOnTheSamePattern) {
  // Tridiagonal 2 - 2cos: eigenvalues 2 - 2 cos(k pi/(n+1)) + s; positive definite iff s > -lambda_min.
  const int n = 50;
  const double lmin = 2 - 2 * std::cos(M_PI / (n + 1));
  auto make = [&](double s) {
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, 2 + s);
      if (i + 1 < n) t.emplace_back(i + 1, i, -1);
    }
    ColSparseMatrix m(n, n);
    m.setFromTriplets(t.begin(), t.end());
    return m;
  };
  CholmodDefiniteness check;
  check.analyze_pattern(make(0));
  EXPECT_TRUE(check.is_positive_definite(make(0)));
  EXPECT_TRUE(check.is_positive_definite(make(-0.99 * lmin)));
  EXPECT_FALSE(check.is_positive_definite(make(-1.01 * lmin)));
  EXPECT_TRUE(check.is_positive_definite(make(1.0)));
}

TEST(CholmodDefiniteness, IsQuietOnFailure) {
  ColSparseMatrix a(2, 2);
  a.insert(0, 0) = 1;
  a.insert(1, 1) = -1;
  a.makeCompressed();
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const bool pd = is_positive_definite(a);
  const std::string out = testing::internal::GetCapturedStdout(), err = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(pd);
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

TEST(CholmodDefiniteness, RejectsBadInput) {
  ColSparseMatrix rect(2, 3);
  rect.makeCompressed();
  EXPECT_THROW(is_positive_definite(rect), std::invalid_argument);
  ColSparseMatrix empty;
  EXPECT_THROW(is_positive_definite(empty), std::invalid_argument);
  CholmodDefiniteness check;
  ColSparseMatrix a(2, 2);
  a.setIdentity();
  EXPECT_THROW(check.is_positive_definite(a), std::logic_error);  // no analyze_pattern yet
}

}  // namespace
}  // namespace sphstab
