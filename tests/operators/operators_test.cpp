#include "sphstab/operators/operators.hpp"

#include <gtest/gtest.h>

#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace operators_test {

template <int Dim>
void expect_pairwise(LatticeType type, int n) {
  Kernel<Dim> k(KernelType::WendlandC4);
  const double h = 1.3;
  auto p = make_lattice<Dim>(type, n, {.spacing = 1.0, .support_radius = 2 * h, .perturbation = 0.15});
  auto nl = find_neighbours(p, k.support_radius(h));
  auto ops = assemble_operators(p, nl, k, h, {.kernel = true, .gradient = true, .hessian = true});
  Eigen::MatrixXd W = ops.W, G0 = ops.G[0];
  for (int i = 0; i < p.size(); ++i)
    for (int j = 0; j < p.size(); ++j) {
      Eigen::Matrix<double, 1, Dim> d = p.x.row(i) - p.x.row(j);
      double r = d.norm();
      double w = r < k.support_radius(h) ? k.value(r, h) * p.volume[j] : 0.0;
      EXPECT_NEAR(W(i, j), w, 1e-14);
      double g = (i == j || r >= k.support_radius(h)) ? 0.0 : k.d1(r, h) * d[0] / r * p.volume[j];
      EXPECT_NEAR(G0(i, j), g, 1e-14);
    }
  // Antisymmetry of G (equal volumes) on any set, symmetry of H.
  for (int a = 0; a < Dim; ++a) {
    EXPECT_NEAR((ops.G[a] + SparseMatrix<>(ops.G[a].transpose())).norm(), 0.0, 1e-13);
    for (int b = 0; b < Dim; ++b)
      EXPECT_NEAR((ops.H[a][b] - SparseMatrix<>(ops.H[a][b].transpose())).norm(), 0.0, 1e-13);
  }
}

TEST(Operators, AssemblyEqualsPairwiseEvaluation) {
  expect_pairwise<1>(LatticeType::Line, 15);
  expect_pairwise<2>(LatticeType::Square, 6);
  expect_pairwise<3>(LatticeType::Cubic, 3);
}

TEST(Operators, HessianMatchesComplexStepOfGradient) {
  Kernel<2> k(KernelType::CubicSpline);
  const double h = 1.3, eps = 1e-30;
  auto p = make_lattice<2>(LatticeType::Square, 4, {.spacing = 1.0, .support_radius = 2 * h, .perturbation = 0.2});
  auto nl = find_neighbours(p, k.support_radius(h));
  auto ops = assemble_operators(p, nl, k, h, {.kernel = false, .gradient = true, .hessian = true});
  for (int b = 0; b < 2; ++b) {
    // Move every particle by i*eps in axis b: d(G^a_ij)/d(x_i^b) for a pair only sees x_i - x_j, so move
    // particle i alone, one at a time, and compare row i.
    for (int i = 0; i < p.size(); i += 5) {
      Positions<2, std::complex<double>> x = p.x.cast<std::complex<double>>();
      x(i, b) += std::complex<double>(0, eps);
      auto c = assemble_operators<2, std::complex<double>>(p, nl, k, h, {false, true, false}, &x);
      for (int a = 0; a < 2; ++a)
        for (SparseMatrix<std::complex<double>>::InnerIterator it(c.G[a], i); it; ++it) {
          if (it.col() == i) continue;
          EXPECT_NEAR(it.value().imag() / eps, ops.H[a][b].coeff(i, it.col()), 1e-12);
        }
    }
  }
}

TEST(Operators, RejectsBadInput) {
  Kernel<1> k(KernelType::CubicSpline);
  auto p = make_lattice<1>(LatticeType::Line, 5, {.spacing = 1.0, .support_radius = 2.0});
  auto nl = find_neighbours(p, 2.0);
  EXPECT_THROW(assemble_operators(p, nl, k, 0.0), std::invalid_argument);
  EXPECT_THROW(assemble_operators(p, nl, k, -1.0), std::invalid_argument);
  EXPECT_THROW(assemble_operators(p, nl, k, 2.0), std::invalid_argument);  // support 4 > radius 2
  EXPECT_THROW(gradient_matrix(p, nl, k, 1.0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
