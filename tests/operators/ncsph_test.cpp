#include "sphstab/operators/ncsph.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "correction_fixture.hpp"

namespace sphstab {
namespace ncsph_test {

using test::Complex;
using test::make_case;

// sum_j (f_j - f_i) G^b_ij for the linear field f = b . x (differences by minimum image) must equal b_b.
template <int Dim>
double linear_field_error(const test::Case<Dim>& c, const std::array<SparseMatrix<>, Dim>& g, bool free_only) {
  Eigen::Matrix<double, 1, Dim> slope;
  for (int a = 0; a < Dim; ++a) slope[a] = 0.7 - 1.3 * a;
  double err = 0;
  for (int b = 0; b < Dim; ++b)
    for (int i = 0; i < c.set.size(); ++i) {
      if (free_only && c.set.role[i] != Role::Free) continue;
      double sum = 0;
      for (SparseMatrix<>::InnerIterator it(g[b], i); it; ++it)
        sum += slope.dot(-c.set.separation(i, it.col())) * it.value();
      err = std::max(err, std::abs(sum - slope[b]));
    }
  return err;
}

template <int Dim>
void expect_linear_exactness(LatticeType type, int n, bool periodic) {
  auto c = make_case<Dim>(type, n, 1.3, 0.2, periodic);
  auto g = ncsph_gradient<Dim, double>(c.set, c.ops.W, c.ops.G);
  // The uncorrected gradient is far from exact on the perturbed lattice ...
  EXPECT_GT(linear_field_error<Dim>(c, c.ops.G, true), 1e-2);
  // ... NCSPH reproduces linear fields on the free particles (and, M_i being invertible, on all of them).
  EXPECT_LT(linear_field_error<Dim>(c, g, true), 1e-12);
  EXPECT_LT(linear_field_error<Dim>(c, g, false), 1e-12);
  std::printf("NCSPH %dD %s%s: linear-field error %.1e (uncorrected G: %.2e)\n", Dim, lattice_name(type).c_str(),
              periodic ? " periodic" : "", linear_field_error<Dim>(c, g, false),
              linear_field_error<Dim>(c, c.ops.G, true));
  auto gc = ncsph_gradient<Dim, Complex>(c.set, c.cops.W, c.cops.G);
  for (int a = 0; a < Dim; ++a) {
    EXPECT_LT(test::max_abs(test::row_sums(g[a])), 1e-13);  // (1.13a), round-off of O(1/h) entries
    EXPECT_LT(test::complex_mismatch(g[a], gc[a]), 1e-15);
  }
}

TEST(Ncsph, ExactForLinearFieldsOnPerturbedLattices) {
  expect_linear_exactness<1>(LatticeType::Line, 20, false);
  expect_linear_exactness<1>(LatticeType::Line, 20, true);
  expect_linear_exactness<2>(LatticeType::Square, 7, false);
  expect_linear_exactness<2>(LatticeType::Hexagonal, 8, true);
  expect_linear_exactness<2>(LatticeType::FaceCentred, 6, false);
  expect_linear_exactness<3>(LatticeType::Cubic, 3, false);
}

// The complex-step path differentiates through the correction: compare with a central difference of the double
// path when one particle moves.
TEST(Ncsph, ComplexStepDerivativeMatchesCentralDifference) {
  auto c = make_case<2>(LatticeType::Square, 4, 1.3, 0.2, false);
  Kernel<2> w(KernelType::CubicSpline);
  const int moved = 5, axis = 1;
  const double eps = 1e-30, step = 1e-5;
  Positions<2, Complex> xc = c.set.x.cast<Complex>();
  xc(moved, axis) += Complex(0, eps);
  auto oc = assemble_operators<2, Complex>(c.set, c.nl, w, 1.3, {true, true, false}, &xc);
  auto gc = ncsph_gradient<2, Complex>(c.set, oc.W, oc.G, &xc);
  std::array<std::array<SparseMatrix<>, 2>, 2> gpm;
  for (int s = 0; s < 2; ++s) {
    Positions<2, double> x = c.set.x;
    x(moved, axis) += s == 0 ? step : -step;
    auto o = assemble_operators<2, double>(c.set, c.nl, w, 1.3, {true, true, false}, &x);
    gpm[s] = ncsph_gradient<2, double>(c.set, o.W, o.G, &x);
  }
  double worst = 0, scale = 0;
  for (int a = 0; a < 2; ++a) {
    Eigen::MatrixXd cs = Eigen::MatrixXcd(gc[a]).imag() / eps;
    Eigen::MatrixXd fd = (Eigen::MatrixXd(gpm[0][a]) - Eigen::MatrixXd(gpm[1][a])) / (2 * step);
    worst = std::max(worst, (cs - fd).cwiseAbs().maxCoeff());
    scale = std::max(scale, cs.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(scale, 1e-2);  // the moved particle really changes the operator
  // Central difference: truncation O(step^2 f''') ~ 1e-10 and cancellation ~ 1e-16/step ~ 1e-11; loose on purpose.
  EXPECT_LT(worst, 1e-8);
}

TEST(Ncsph, SingularMomentMatrixThrowsNamingTheParticle) {
  // h = 0.3 dx: support 0.6 dx, every particle only sees itself, M_i = 0.
  auto c = make_case<1>(LatticeType::Line, 5, 0.3, 0.0, false, 0);
  try {
    ncsph_gradient<1, double>(c.set, c.ops.W, c.ops.G);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("particle 0"), std::string::npos) << e.what();
  }
  // 2D particles on one line: M_i has a zero row (no y-separation), singular for every particle.
  ParticleSet<2> line;
  line.x.resize(6, 2);
  for (int i = 0; i < 6; ++i) line.x.row(i) << i, 0.0;
  line.volume = Eigen::VectorXd::Ones(6);
  line.role.assign(6, Role::Free);
  line.depth.assign(6, 0);
  Kernel<2> w(KernelType::CubicSpline);
  auto nl = find_neighbours(line, 2.6);
  auto ops = assemble_operators<2, double>(line, nl, w, 1.3);
  EXPECT_THROW((ncsph_gradient<2, double>(line, ops.W, ops.G)), std::invalid_argument);
}

TEST(Ncsph, RejectsMismatchedInput) {
  auto c = make_case<2>(LatticeType::Square, 4, 1.3, 0.0, false);
  auto d = make_case<2>(LatticeType::Square, 3, 1.3, 0.0, false);
  EXPECT_THROW((ncsph_gradient<2, double>(d.set, c.ops.W, c.ops.G)), std::invalid_argument);  // size
  std::array<SparseMatrix<>, 2> g = c.ops.G;
  g[1].prune([](int r, int col, double) { return r != col; });  // drops the diagonal: another pattern
  EXPECT_THROW((ncsph_gradient<2, double>(c.set, c.ops.W, g)), std::invalid_argument);
  Positions<2, double> x(3, 2);
  EXPECT_THROW((ncsph_gradient<2, double>(c.set, c.ops.W, c.ops.G, &x)), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
