#include <gtest/gtest.h>

#include "sphstab/linalg/dense_general_eigen.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"

namespace sphstab {
namespace dense_eigen_test {

TEST(DenseSymmetricEigen, TridiagonalToeplitzExact) {
  const int n = 12;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 2;
    if (i + 1 < n) a(i, i + 1) = a(i + 1, i) = -1;
  }
  DenseSymmetricEigen e = symmetric_eigen(a, true);
  ASSERT_EQ(e.status, Status::Successful);
  for (int k = 0; k < n; ++k) EXPECT_NEAR(e.values[k], 2 - 2 * std::cos((k + 1) * M_PI / (n + 1)), 1e-14);
  EXPECT_LT((a * e.vectors - e.vectors * e.values.asDiagonal()).norm(), 1e-13);
}

TEST(DenseSymmetricEigen, GeneralisedAndIndefiniteB) {
  Eigen::MatrixXd a(2, 2), b(2, 2);
  a << 2, 1, 1, 3;
  b << 2, 0, 0, 1;
  DenseSymmetricEigen e = generalized_symmetric_eigen(a, b, true);
  ASSERT_EQ(e.status, Status::Successful);
  // det(A - l B) = (2 - 2l)(3 - l) - 1 = 2 l^2 - 8 l + 5 = 0.
  EXPECT_NEAR(e.values[0], (8 - std::sqrt(24.0)) / 4, 1e-14);
  EXPECT_NEAR(e.values[1], (8 + std::sqrt(24.0)) / 4, 1e-14);
  EXPECT_NEAR(e.vectors.col(0).dot(b * e.vectors.col(0)), 1.0, 1e-14);
  b(1, 1) = -1;
  DenseSymmetricEigen bad = generalized_symmetric_eigen(a, b);
  EXPECT_EQ(bad.status, Status::NumericalIssue);
  EXPECT_GT(bad.lapack_info, 2);
  EXPECT_THROW(generalized_symmetric_eigen(a, Eigen::MatrixXd::Identity(3, 3)), std::invalid_argument);
  EXPECT_THROW(symmetric_eigen(Eigen::MatrixXd(2, 3)), std::invalid_argument);
}

TEST(DenseGeneralEigen, RotationHasImaginaryPair) {
  Eigen::MatrixXd a(2, 2);
  a << 0, 1, -1, 0;
  DenseGeneralEigen e = general_eigen(a, true);
  ASSERT_EQ(e.status, Status::Successful);
  EXPECT_NEAR(std::abs(e.values[0].real()), 0.0, 1e-15);
  EXPECT_NEAR(std::abs(e.values[0].imag()), 1.0, 1e-15);
  EXPECT_NEAR(e.values[0].imag(), -e.values[1].imag(), 1e-15);
  for (int k = 0; k < 2; ++k) {
    Eigen::VectorXcd r = a.cast<std::complex<double>>() * e.vectors.col(k) - e.values[k] * e.vectors.col(k);
    EXPECT_LT(r.norm(), 1e-14);
  }
}

}  // namespace
}  // namespace sphstab
