#include "sphstab/io/matrix_market.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace sphstab {
namespace matrix_market_test {

std::string temp_path(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("sphstab_mm_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

TEST(MatrixMarket, SparseRoundTripIsExactAndKeepsExplicitZeros) {
  SparseMatrix<> a(3, 4);
  a.insert(0, 0) = 0.0;  // explicit zero (e.g. G_ii) must survive
  a.insert(0, 3) = 1.0 / 3.0;
  a.insert(2, 1) = -2.5e-17;
  a.insert(1, 2) = 123456789.123456789;
  a.makeCompressed();
  const std::string path = temp_path("a.mtx");
  write_matrix_market(path, a, "test matrix\nsecond comment line");
  SparseMatrix<> b = read_matrix_market(path);
  EXPECT_EQ(b.rows(), 3);
  EXPECT_EQ(b.cols(), 4);
  EXPECT_EQ(b.nonZeros(), 4);
  EXPECT_EQ(Eigen::MatrixXd(a), Eigen::MatrixXd(b));  // %.17g round-trips doubles exactly
  std::ifstream in(path);
  std::string banner;
  std::getline(in, banner);
  EXPECT_EQ(banner, "%%MatrixMarket matrix coordinate real general");
}

TEST(MatrixMarket, DenseRoundTrip) {
  Eigen::MatrixXd a(2, 3);
  a << 1, 2, 3, 4, 5, 6.000000000000001;
  const std::string path = temp_path("d.mtx");
  write_matrix_market(path, a);
  SparseMatrix<> b = read_matrix_market(path);
  EXPECT_EQ(Eigen::MatrixXd(b), a);
  EXPECT_EQ(b.nonZeros(), 6);
}

TEST(MatrixMarket, RejectsMalformedFiles) {
  EXPECT_THROW(read_matrix_market(temp_path("missing.mtx")), std::runtime_error);
  const std::string path = temp_path("bad.mtx");
  std::ofstream(path) << "%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n";
  EXPECT_THROW(read_matrix_market(path), std::runtime_error);
  std::ofstream(path) << "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 1\n";
  EXPECT_THROW(read_matrix_market(path), std::runtime_error);
  std::ofstream(path) << "%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 1\n";
  EXPECT_THROW(read_matrix_market(path), std::runtime_error);
  EXPECT_THROW(write_matrix_market("/nonexistent-dir/x.mtx", SparseMatrix<>(1, 1)), std::runtime_error);
}

}  // namespace
}  // namespace sphstab
