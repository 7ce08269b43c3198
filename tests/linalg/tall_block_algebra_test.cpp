// linalg/tall_block_algebra: the block LOBPCG's dense kernels against Eigen's products (round-off), their documented
// summation order (which makes the AVX2 and baseline builds of the kernels give the same bits), fused passes against
// their operations one after the other (the same bits), and the same bits for any thread count.
#include "../../src/linalg/tall_block_algebra.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <vector>

#include "sphstab/core/threads.hpp"
#include "sphstab/numerics/random_vector.hpp"

namespace sphstab {
namespace tall_block_algebra_test {

/// rows x cols uniform in [-1, 1]: 9003 rows are 3 chunks (the last partial) and 3 rows beyond a multiple of 4.
Eigen::MatrixXd random_block(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
  return random_vector(static_cast<int>(rows * cols), 1.0, seed).reshaped(rows, cols);
}

constexpr Eigen::Index kRows = 2 * tall::kRowChunk + 811;

TEST(TallBlockAlgebra, AgreesWithEigenProducts) {
  const Eigen::MatrixXd a = random_block(kRows, 7, 1), b = random_block(kRows, 5, 2), c = random_block(7, 5, 3);
  const Eigen::MatrixXd g = tall::gram(a, b), g_ref = a.transpose() * b;
  EXPECT_LE((g - g_ref).norm(), 1e-13 * g_ref.norm() + 1e-12);

  Eigen::MatrixXd y = b, y_ref = b;
  tall::subtract_product(y, a, c);
  y_ref -= a * c;
  EXPECT_LE((y - y_ref).norm(), 1e-14 * y_ref.norm());

  // Columns [1, 8) times c7 into [0, 5) (overlapping ranges), with a tail of the last 3 input columns into [5, 7).
  Eigen::MatrixXd q = random_block(kRows, 9, 4), q_ref = q;
  const Eigen::MatrixXd c7 = random_block(7, 5, 5), tail = random_block(3, 2, 6);
  tall::transform_columns(q, 1, c7, 0, tail);
  q_ref.leftCols(5) = q_ref.middleCols(1, 7) * c7;
  q_ref.middleCols(5, 2) = q_ref.middleCols(5, 3) * tail;  // columns 5..7 of the input (untouched by the line above)
  EXPECT_LE((q.leftCols(7) - q_ref.leftCols(7)).norm(), 1e-14 * q_ref.leftCols(7).norm());
  EXPECT_TRUE(q.rightCols(2) == q_ref.rightCols(2));
}

TEST(TallBlockAlgebra, RitzGramsAreTheSymmetrisedFullProducts) {
  const Eigen::MatrixXd v = random_block(kRows, 9, 7), kv = random_block(kRows, 9, 8), lv = random_block(kRows, 9, 9);
  Eigen::MatrixXd g, h;
  tall::ritz_grams(v, kv, lv, {4, 3, 2}, g, h);
  for (const auto& [out, w] : {std::pair{&g, &kv}, std::pair{&h, &lv}}) {
    Eigen::MatrixXd full = v.transpose() * *w;
    // Blocks above the diagonal as computed, below them their transposes; diagonal blocks averaged.
    Eigen::MatrixXd want = full.triangularView<Eigen::Upper>();
    int b0 = 0;
    for (int bw : {4, 3, 2}) {
      want.block(b0, b0, bw, bw) = 0.5 * (full.block(b0, b0, bw, bw) + full.block(b0, b0, bw, bw).transpose());
      want.block(b0, b0 + bw, bw, 9 - b0 - bw) = full.block(b0, b0 + bw, bw, 9 - b0 - bw);
      b0 += bw;
    }
    want.triangularView<Eigen::StrictlyLower>() = want.transpose().triangularView<Eigen::StrictlyLower>();
    EXPECT_LE((*out - want).norm(), 1e-13 * want.norm());
    EXPECT_TRUE(*out == out->transpose());
  }
}

TEST(TallBlockAlgebra, GramFollowsTheDocumentedSummationOrder) {
  // One chunk of 10 rows: lane l sums rows l and l + 4, the lanes add as (l0 + l1) + (l2 + l3), then rows 8 and 9.
  // Values of very different sizes, so that another order would change the bits.
  Eigen::VectorXd a(10), b = Eigen::VectorXd::Ones(10);
  a << 1e16, 1, 1, 1, -1e16, 1, 1, 1, 1, 1;
  const double lane[4] = {a[0] + a[4], a[1] + a[5], a[2] + a[6], a[3] + a[7]};
  const double want = (((lane[0] + lane[1]) + (lane[2] + lane[3])) + a[8]) + a[9];
  EXPECT_EQ(want, 8.0);  // exact; in row order 1e16 swallows the ones: 5, in two lanes 7
  EXPECT_EQ(tall::gram(a, b)(0, 0), want);
  EXPECT_EQ(tall::gram(b, a)(0, 0), want);
}

TEST(TallBlockAlgebra, FusedPassGivesTheSameBitsAsItsOperations) {
  const Eigen::MatrixXd z = random_block(kRows, 6, 10), kz = random_block(kRows, 6, 11);
  const Eigen::MatrixXd c = 0.1 * random_block(6, 4, 12), s = 0.1 * random_block(6, 4, 13);
  const Eigen::MatrixXd y0 = random_block(kRows, 4, 14), ky0 = random_block(kRows, 4, 15);
  Eigen::MatrixXd y = y0, ky = ky0, g;
  tall::RowPass().subtract(y, z, c).subtract(ky, kz, s).gram(y, ky, g).run();
  Eigen::MatrixXd y_ref = y0, ky_ref = ky0;
  tall::subtract_product(y_ref, z, c);
  tall::subtract_product(ky_ref, kz, s);
  EXPECT_TRUE(y == y_ref);
  EXPECT_TRUE(ky == ky_ref);
  EXPECT_TRUE(g == tall::gram(y_ref, ky_ref));
  EXPECT_THROW(tall::RowPass().gram(y, z.topRows(10), g), std::invalid_argument);
  EXPECT_THROW(tall::RowPass().subtract(y, z, s.topRows(5)), std::invalid_argument);
}

TEST(TallBlockAlgebra, SameBitsForAnyThreadCount) {
  const Eigen::MatrixXd a = random_block(kRows, 8, 16), b = random_block(kRows, 4, 17), c = random_block(8, 4, 18);
  std::vector<Eigen::MatrixXd> grams, products;
  for (int threads : {1, 2, 3}) {
    set_threads(threads);
    grams.push_back(tall::gram(a, b));
    Eigen::MatrixXd y = b;
    tall::subtract_product(y, a, c);
    products.push_back(y);
  }
  set_threads(1);
  for (std::size_t t = 1; t < grams.size(); ++t) {
    EXPECT_TRUE(grams[t] == grams[0]);
    EXPECT_TRUE(products[t] == products[0]);
  }
}

}  // namespace tall_block_algebra_test
}  // namespace sphstab
