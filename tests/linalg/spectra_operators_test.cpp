// CHOLMOD-backed Spectra operators: shift-invert (SymEigsShiftSolver, SymGEigsShiftSolver ShiftInvert and
// Buckling modes) and the Cholesky-mode B operator (SymGEigsSolver), against dense LAPACK.
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsShiftSolver.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <Spectra/SymGEigsSolver.h>
#include <gtest/gtest.h>

#include <random>

#include "sphstab/linalg/cholmod_cholesky_op.hpp"
#include "sphstab/linalg/cholmod_shift_invert.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"

namespace sphstab {
namespace spectra_operators_test {

/// Symmetric banded test pair: A indefinite (random band), B positive definite (diagonally dominant band).
struct Pair {
  ColSparseMatrix a, b;
};

Pair make_pair(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> ta, tb;
  for (int i = 0; i < n; ++i) {
    ta.emplace_back(i, i, 3 * u(rng));
    tb.emplace_back(i, i, 4 + u(rng));
    for (int d = 1; d <= 3 && i + d < n; ++d) {
      const double va = u(rng), vb = 0.5 * u(rng);
      ta.emplace_back(i, i + d, va);
      ta.emplace_back(i + d, i, va);
      tb.emplace_back(i, i + d, vb);
      tb.emplace_back(i + d, i, vb);
    }
  }
  Pair p;
  p.a.resize(n, n);
  p.b.resize(n, n);
  p.a.setFromTriplets(ta.begin(), ta.end());
  p.b.setFromTriplets(tb.begin(), tb.end());
  return p;
}

TEST(CholmodShiftInvert, StandardProblemEigenvaluesNearShift) {
  const int n = 300;
  Pair p = make_pair(n, 7);
  const Eigen::VectorXd all = symmetric_eigen(Eigen::MatrixXd(p.a)).values;
  // Shift below the spectrum: A - sigma I positive definite (LLT), nearest eigenvalues = smallest.
  const double sigma = all[0] - 0.5;
  CholmodShiftInvert op(p.a);
  Spectra::SymEigsShiftSolver<CholmodShiftInvert> eigs(op, 4, 30, sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  ASSERT_EQ(eigs.info(), Spectra::CompInfo::Successful);
  Eigen::VectorXd got = eigs.eigenvalues();
  std::sort(got.data(), got.data() + got.size());
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[k], all[k], 1e-10 * std::abs(all[n - 1]));
  EXPECT_EQ(op.sign(), 1.0);
  // Shift above the spectrum: -(A - sigma I) is factorised (sign -1); nearest = largest.
  const double sigma2 = all[n - 1] + 0.5;
  CholmodShiftInvert op2(p.a);
  Spectra::SymEigsShiftSolver<CholmodShiftInvert> eigs2(op2, 3, 30, sigma2);
  eigs2.init();
  eigs2.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  ASSERT_EQ(eigs2.info(), Spectra::CompInfo::Successful);
  Eigen::VectorXd got2 = eigs2.eigenvalues();
  std::sort(got2.data(), got2.data() + got2.size());
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got2[k], all[n - 3 + k], 1e-10 * std::abs(all[n - 1]));
  EXPECT_EQ(op2.sign(), -1.0);
}

TEST(CholmodShiftInvert, InteriorShiftNeedsLdlt) {
  const int n = 200;
  Pair p = make_pair(n, 11);
  const Eigen::VectorXd all = symmetric_eigen(Eigen::MatrixXd(p.a)).values;
  const double sigma = 0.5 * (all[n / 2] + all[n / 2 + 1]);
  CholmodShiftInvert llt(p.a);
  EXPECT_THROW(llt.set_shift(sigma), std::invalid_argument);
  CholmodShiftInvert ldlt(p.a, ColSparseMatrix(), CholmodFactorKind::LDLT);
  Spectra::SymEigsShiftSolver<CholmodShiftInvert> eigs(ldlt, 2, 30, sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  ASSERT_EQ(eigs.info(), Spectra::CompInfo::Successful);
  Eigen::VectorXd got = eigs.eigenvalues();
  std::sort(got.data(), got.data() + got.size());
  // Unpivoted LDL^T on an indefinite matrix: accuracy depends on the pivots; 1e-8 is ample for these bands.
  EXPECT_NEAR(got[0], all[n / 2], 1e-8);
  EXPECT_NEAR(got[1], all[n / 2 + 1], 1e-8);
}

TEST(CholmodShiftInvert, GeneralisedShiftInvertAndBucklingModes) {
  const int n = 250;
  Pair p = make_pair(n, 3);
  const Eigen::VectorXd all =
      generalized_symmetric_eigen(Eigen::MatrixXd(p.a), Eigen::MatrixXd(p.b)).values;  // A x = lambda B x
  // Shift-invert with sigma above lambda_max: -(A - sigma B) is positive definite.
  const double sigma = all[n - 1] + 0.1;
  CholmodShiftInvert op(p.a, p.b);
  Spectra::SparseSymMatProd<double> bop(p.b);
  Spectra::SymGEigsShiftSolver<CholmodShiftInvert, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
      eigs(op, bop, 2, 30, sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  ASSERT_EQ(eigs.info(), Spectra::CompInfo::Successful);
  Eigen::VectorXd got = eigs.eigenvalues();
  std::sort(got.data(), got.data() + got.size());
  EXPECT_NEAR(got[1], all[n - 1], 1e-10 * std::abs(all[n - 1]));
  EXPECT_NEAR(got[0], all[n - 2], 1e-10 * std::abs(all[n - 1]));

  // Buckling mode: B x = mu A' x with B positive definite as the "stiffness", A as the "geometric" matrix:
  // mu = 1/lambda. Shift at a small positive mu below the smallest positive mu = 1/lambda_max.
  CholmodShiftInvert bop_si(p.b, p.a);
  Spectra::SparseSymMatProd<double> kop(p.b);
  const double mu_sigma = 0.5 / all[n - 1];
  Spectra::SymGEigsShiftSolver<CholmodShiftInvert, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::Buckling>
      buck(bop_si, kop, 1, 30, mu_sigma);
  buck.init();
  buck.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  ASSERT_EQ(buck.info(), Spectra::CompInfo::Successful);
  EXPECT_NEAR(buck.eigenvalues()[0], 1.0 / all[n - 1], 1e-10 / all[n - 1]);
}

TEST(CholmodCholeskyOp, CholeskyModeMatchesDsygv) {
  const int n = 400;
  Pair p = make_pair(n, 5);
  const Eigen::VectorXd all = generalized_symmetric_eigen(Eigen::MatrixXd(p.a), Eigen::MatrixXd(p.b)).values;
  for (CholmodVariant variant : {CholmodVariant::Simplicial, CholmodVariant::Supernodal}) {
    CholmodCholeskyOp bop(p.b, variant);
    ASSERT_EQ(bop.info(), Status::Successful);
    Spectra::SparseSymMatProd<double> op(p.a);
    Spectra::SymGEigsSolver<decltype(op), CholmodCholeskyOp, Spectra::GEigsMode::Cholesky> eigs(op, bop, 3, 40);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, 2000, 1e-12);
    ASSERT_EQ(eigs.info(), Spectra::CompInfo::Successful);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(eigs.eigenvalues()[k], all[n - 1 - k], 1e-10 * std::abs(all[n - 1]));
    // Eigenvectors satisfy A x = lambda B x with x^T B x = 1.
    Eigen::MatrixXd x = eigs.eigenvectors();
    for (int k = 0; k < 3; ++k) {
      Eigen::VectorXd r = p.a * x.col(k) - eigs.eigenvalues()[k] * (p.b * x.col(k));
      EXPECT_LT(r.norm(), 1e-8);
      EXPECT_NEAR(x.col(k).dot(p.b * x.col(k)), 1.0, 1e-10);
    }
  }
}

TEST(CholmodCholeskyOp, ReportsIndefiniteB) {
  Pair p = make_pair(20, 9);
  CholmodCholeskyOp bop(p.a);  // random band, indefinite
  EXPECT_EQ(bop.info(), Status::NumericalIssue);
}

}  // namespace
}  // namespace sphstab
