// The lattice stencil probe and the sine-transform preconditioner (issue 13): the probed stencil reproduces the
// free-free operator on interior rows, the FFTW application equals a dense DST-I reference, and sets that are not a
// square lattice in DOF order are refused in one line.
#include "sphstab/stability/lattice_sine_preconditioner.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>
#include <numbers>

#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/lattice_stencil.hpp"

namespace sphstab {
namespace lattice_sine_preconditioner_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

std::shared_ptr<const Discretisation<2>> lattice(LatticeType type, int n, double h = 1.3) {
  const Kernel<2> k(KernelType::CubicSpline);
  return make_discretisation(strain_lattice_2d(type, k, h, n), k, h);
}

MatrixFreeLinearisation<2> linearisation(const Discretisation<2>& d) {
  return MatrixFreeLinearisation(d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
}

TEST(LatticeStencil, ProbeReproducesTheInteriorRows) {
  const int n = 20;
  auto d = lattice(LatticeType::Square, n);
  const MatrixFreeLinearisation lin = linearisation(*d);
  const LatticeStencil st = probe_lattice_stencil(lin, LoadDirection::Tension);
  EXPECT_EQ(st.n, n);
  // Two hops of the support 2h = 2.6 dx: |d| < 5.2, and |d| = 5 would need a common neighbour at 2.5 from both.
  EXPECT_EQ(st.radius, 4);
  // K and L symmetric: S(-d) = S(d)^T.
  double asym = 0;
  for (int dj = -st.radius; dj <= st.radius; ++dj)
    for (int di = -st.radius; di <= st.radius; ++di) {
      asym = std::max(asym, (st.k_at(di, dj) - st.k_at(-di, -dj).transpose()).cwiseAbs().maxCoeff());
      asym = std::max(asym, (st.l_at(di, dj) - st.l_at(-di, -dj).transpose()).cwiseAbs().maxCoeff());
    }
  EXPECT_LE(asym, 1e-14 * st.scale());
  // Interior rows (at least 5 from the free edge): the operator is the restricted stencil to round-off.
  const std::vector<int> interior = {6 + n * 7, 13 + n * 5, 8 + n * 14};
  const double dev_interior = lattice_stencil_deviation(lin, LoadDirection::Tension, st, interior);
  EXPECT_LE(dev_interior, 1e-13);
  // Boundary rows (corner, edge middle, one in from the edge): the fixed layers (thickness >= the support) give every
  // free particle a complete neighbourhood, so these rows are the restricted stencil too (measured 1.2e-16).
  const double dev_boundary = lattice_stencil_deviation(lin, LoadDirection::Tension, st, {0, n / 2, n / 2 + n});
  EXPECT_LE(dev_boundary, 1e-13);
  std::cout << "stencil radius " << st.radius << ", max |entry| " << st.scale()
            << "; relative deviation of the operator from the restricted stencil: interior rows " << dev_interior
            << ", boundary rows " << dev_boundary << "\n";
}

TEST(LatticeStencil, RefusesWhatIsNotASquareLattice) {
  // A hexagonal lattice (64 free particles: a square number, but rows are shifted): one line naming the particle.
  auto hex = lattice(LatticeType::Hexagonal, 8);
  const MatrixFreeLinearisation lin = linearisation(*hex);
  ASSERT_TRUE(lin.symmetric());
  try {
    probe_lattice_stencil(lin, LoadDirection::Tension);
    ADD_FAILURE() << "hexagonal lattice accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("not at site"), std::string::npos) << what;
    EXPECT_NE(what.find("square lattice in DOF order"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  // Not a square number of free particles.
  Eigen::MatrixXd x(6, 2);
  x << 0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1;
  try {
    square_lattice(x, "test");
    ADD_FAILURE() << "3 x 2 lattice accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not a square number"), std::string::npos) << e.what();
  }
  // Right sites, wrong DOF order (y fastest).
  Eigen::MatrixXd t(4, 2);
  t << 0, 0, 0, 1, 1, 0, 1, 1;
  EXPECT_THROW(square_lattice(t, "test"), std::invalid_argument);
  // Too small to probe: the central column reaches the free edge.
  auto small = lattice(LatticeType::Square, 8);
  try {
    probe_lattice_stencil(linearisation(*small), LoadDirection::Tension);
    ADD_FAILURE() << "8 x 8 lattice probed";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("too small"), std::string::npos) << e.what();
  }
}

/// Orthonormal DST-I matrix of size n: S_ab = sqrt(2/(n+1)) sin(pi (a+1)(b+1)/(n+1)), S = S^T = S^{-1}.
Eigen::MatrixXd dst1(int n) {
  Eigen::MatrixXd s(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      s(a, b) = std::sqrt(2.0 / (n + 1)) * std::sin(std::numbers::pi * (a + 1) * (b + 1) / (n + 1));
  return s;
}

TEST(LatticeSinePreconditioner, EqualsTheDenseSineTransformReference) {
  // Stencil probed on a 16 x 16 lattice, preconditioners for n = 5 and 7 (smaller than the probe lattice).
  auto d = lattice(LatticeType::Square, 16);
  const LatticeStencil st = probe_lattice_stencil(linearisation(*d), LoadDirection::Tension);
  for (int n : {5, 7}) {
    const LatticeSinePreconditioner t(st, n, 0.02);
    // Symbols independently: sum_d S(d)_cc cos(k . d) on k = pi m/(n+1); sigma = 1.02 max L/K.
    std::vector<double> kh[2], lh[2];
    double top = -1e300;
    for (int c = 0; c < 2; ++c)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double kx = std::numbers::pi * (i + 1) / (n + 1), ky = std::numbers::pi * (j + 1) / (n + 1);
          double sk = 0, sl = 0;
          for (int dj = -st.radius; dj <= st.radius; ++dj)
            for (int di = -st.radius; di <= st.radius; ++di) {
              sk += st.k_at(di, dj)(c, c) * std::cos(kx * di + ky * dj);
              sl += st.l_at(di, dj)(c, c) * std::cos(kx * di + ky * dj);
            }
          kh[c].push_back(sk);
          lh[c].push_back(sl);
          top = std::max(top, sl / sk);
        }
    EXPECT_NEAR(t.symbol_max(), top, 1e-12 * top);
    EXPECT_NEAR(t.sigma(), 1.02 * top, 1e-12 * top);
    // Dense T: per component c, (S (x) S) diag(1/(sigma Kcc - Lcc)) (S (x) S) on the field f = i + n j.
    const Eigen::MatrixXd s = dst1(n);
    Eigen::MatrixXd s2(n * n, n * n);  // (S (x) S)_{(i + n j), (i' + n j')} = S_jj' S_ii'
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int jj = 0; jj < n; ++jj)
          for (int ii = 0; ii < n; ++ii) s2(i + n * j, ii + n * jj) = s(j, jj) * s(i, ii);
    // The symbol scale: sigma sum |S_K| + sum |S_L| bounds the round-off of sigma K_cc - L_cc, which nearly cancels
    // next to the top of the spectrum (sigma is only 2 % above it), so eigenvalues are compared through 1/eigenvalue.
    double scale = 0;
    for (int q = 0; q < st.width() * st.width(); ++q)
      scale += t.sigma() * st.k[q].cwiseAbs().maxCoeff() + st.l[q].cwiseAbs().maxCoeff();
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(2 * n * n, 2 * n * n);
    for (int c = 0; c < 2; ++c) {
      Eigen::VectorXd diag(n * n);
      for (int q = 0; q < n * n; ++q) {
        EXPECT_NEAR(1.0 / t.eigenvalue(c, q % n, q / n), t.sigma() * kh[c][q] - lh[c][q], 1e-14 * scale);
        diag[q] = t.eigenvalue(c, q % n, q / n);  // the dense reference checks the transforms
      }
      const Eigen::MatrixXd tc = s2 * diag.asDiagonal() * s2;
      for (int a = 0; a < n * n; ++a)
        for (int b = 0; b < n * n; ++b) dense(2 * a + c, 2 * b + c) = tc(a, b);
    }
    // Symmetric positive definite.
    EXPECT_LE((dense - dense.transpose()).cwiseAbs().maxCoeff(), 1e-13 * dense.cwiseAbs().maxCoeff());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues().minCoeff(), 0.0);
    Eigen::MatrixXd x = Eigen::MatrixXd::Random(2 * n * n, 3), y(2 * n * n, 3);
    t.apply(x, y);
    const Eigen::MatrixXd ref = dense * x;
    const double rel = (y - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
    EXPECT_LE(rel, 1e-12) << "n = " << n;
    // In place gives the same.
    Eigen::MatrixXd z = x;
    t.apply(z, z);
    EXPECT_EQ((z - y).cwiseAbs().maxCoeff(), 0.0);
    std::cout << "n = " << n << ": FFTW application vs dense DST-I reference, max relative difference " << rel << "\n";
  }
}

TEST(LatticeSinePreconditioner, ThreeDimensionalApplicationEqualsTheDenseSineTransformReference) {
  // 3D: the Dim b = 9 real fields of a 3-column block go through the transforms two at a time as one complex field,
  // so pairs join components of different columns (x and y of column 0, z of column 0 with x of column 1, ...) and
  // the ninth field goes alone. Columns of very different size check that a field's round-off stays relative to
  // the block. Reference: per component c, (S (x) S (x) S) diag(eigenvalue) (S (x) S (x) S), dense.
  const Kernel<3> k(KernelType::CubicSpline);
  const auto d =
      make_discretisation(make_lattice<3>(LatticeType::Cubic, 11, {.support_radius = k.support_radius(1.3)}), k, 1.3);
  const MatrixFreeLinearisation<3> lin(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const LatticeStencil<3> st = probe_lattice_stencil(lin, LoadDirection::Tension);
  const int n = 4, nn = n * n * n;
  const LatticeSinePreconditioner<3> t(st, n);
  const Eigen::MatrixXd s = dst1(n);
  Eigen::MatrixXd s3(nn, nn);  // (S (x) S (x) S)_{(i + n j + n^2 k), (i' + n j' + n^2 k')}
  for (int q = 0; q < nn; ++q)
    for (int r = 0; r < nn; ++r) s3(q, r) = s(q % n, r % n) * s(q / n % n, r / n % n) * s(q / (n * n), r / (n * n));
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * nn, 3 * nn);
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd diag(nn);
    for (int q = 0; q < nn; ++q) diag[q] = t.eigenvalue(c, q % n, q / n % n, q / (n * n));
    const Eigen::MatrixXd tc = s3 * diag.asDiagonal() * s3;
    for (int a = 0; a < nn; ++a)
      for (int b = 0; b < nn; ++b) dense(3 * a + c, 3 * b + c) = tc(a, b);
  }
  Eigen::MatrixXd x = Eigen::MatrixXd::Random(3 * nn, 3), y(3 * nn, 3);
  x.col(1) *= 1e6;
  t.apply(x, y);
  const Eigen::MatrixXd ref = dense * x;
  const double rel = (y - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
  EXPECT_LE(rel, 1e-12);
  for (int v : {0, 2}) {  // the small columns, each against its own size
    const double col = (y.col(v) - ref.col(v)).cwiseAbs().maxCoeff() / ref.col(v).cwiseAbs().maxCoeff();
    EXPECT_LE(col, 1e-8) << "column " << v;
    std::cout << "3D, column " << v << " (1e-6 of column 1): relative difference " << col << "\n";
  }
  // One column alone (3 fields: the z field alone) gives its column of the block within round-off.
  Eigen::MatrixXd one(3 * nn, 1);
  t.apply(x.col(2), one);
  EXPECT_LE((one.col(0) - ref.col(2)).cwiseAbs().maxCoeff(), 1e-12 * ref.col(2).cwiseAbs().maxCoeff());
}

TEST(LatticeSinePreconditioner, RejectsBadInput) {
  auto d = lattice(LatticeType::Square, 12);
  const LatticeStencil st = probe_lattice_stencil(linearisation(*d), LoadDirection::Tension);
  EXPECT_THROW(LatticeSinePreconditioner(st, 0), std::invalid_argument);
  EXPECT_THROW(LatticeSinePreconditioner(st, 4, 0.0), std::invalid_argument);
  const LatticeSinePreconditioner t(st, 4);
  Eigen::MatrixXd x(32, 2), y(31, 2);
  EXPECT_THROW(t.apply(x, y), std::invalid_argument);
}

}  // namespace lattice_sine_preconditioner_test
}  // namespace sphstab
