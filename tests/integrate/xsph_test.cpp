#include "sphstab/integrate/xsph.hpp"

#include <gtest/gtest.h>

#include <random>

#include "sphstab/numerics/random_vector.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace xsph_test {

template <int Dim>
std::shared_ptr<const Discretisation<Dim>> lattice(int n, bool periodic, double perturbation = 0) {
  Kernel<Dim> k(KernelType::CubicSpline);
  auto set = make_lattice<Dim>(Dim == 1 ? LatticeType::Line : LatticeType::Square, n,
                               {.spacing = 1.0,
                                .support_radius = k.support_radius(1.3),
                                .periodic = periodic,
                                .perturbation = perturbation,
                                .seed = 4});
  return make_discretisation(set, k, 1.3);
}

TEST(Xsph, ConservesMomentumWithoutFixedNeighbours) {
  auto d = lattice<2>(8, true);  // periodic: every particle free, equal volumes
  auto hook = xsph_hook<2>(d, {.epsilon = 0.1});
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.05, 1), v = random_vector(d->dofs(), 1.0, 2);
  Eigen::VectorXd w;
  hook(u, v, w);
  double dp[2] = {0, 0}, p[2] = {0, 0};
  for (int f = 0; f < d->free_count(); ++f)
    for (int a = 0; a < 2; ++a) {
      dp[a] += w[2 * f + a] - v[2 * f + a];  // equal masses
      p[a] += std::abs(v[2 * f + a]);
    }
  EXPECT_LT(std::abs(dp[0]), 1e-14 * p[0]);
  EXPECT_LT(std::abs(dp[1]), 1e-14 * p[1]);
  EXPECT_GT((w - v).cwiseAbs().maxCoeff(), 1e-3);  // it did smooth
  // a uniform velocity is left unchanged
  Eigen::VectorXd uniform(d->dofs());
  for (int f = 0; f < d->free_count(); ++f) uniform.segment<2>(2 * f) << 0.3, -0.2;
  hook(u, uniform, w);
  EXPECT_LT((w - uniform).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Xsph, FixedLayersActAsAWallAndMatchTheSmoothingMatrix) {
  auto d = lattice<2>(6, false);
  const Eigen::VectorXd v = random_vector(d->dofs(), 1.0, 3), zero = Eigen::VectorXd::Zero(d->dofs());
  Eigen::VectorXd w;
  for (bool fixed : {true, false}) {
    const XsphOptions o{.epsilon = 0.1, .current_positions = true, .include_fixed = fixed};
    xsph_hook<2>(d, o)(zero, v, w);
    const SparseMatrix<> S = xsph_smoothing_matrix(*d, o);
    Eigen::VectorXd sv(d->dofs());
    for (int a = 0; a < 2; ++a) {
      Eigen::VectorXd c(d->free_count());
      for (int f = 0; f < d->free_count(); ++f) c[f] = v[2 * f + a];
      const Eigen::VectorXd s = S * c;
      for (int f = 0; f < d->free_count(); ++f) sv[2 * f + a] = s[f];
    }
    EXPECT_LT((w - sv).cwiseAbs().maxCoeff(), 1e-15);
    // momentum change = -eps sum_{i free, j fixed} v_i W_ij (equal masses), zero without fixed neighbours
    const SparseMatrix<> W = kernel_matrix(d->particles, d->neighbours, d->kernel, d->h);
    double expected = 0, dp = 0;
    for (int f = 0; f < d->free_count(); ++f) {
      dp += w[2 * f] - v[2 * f];
      for (SparseMatrix<>::InnerIterator it(W, d->free[f]); it; ++it)
        if (d->free_slot[it.col()] < 0 && fixed) expected -= 0.1 * v[2 * f] * it.value();
    }
    EXPECT_NEAR(dp, expected, 1e-14 * d->free_count());
  }
}

TEST(Xsph, OneDimensionalAndCurrentPositions) {
  auto d = lattice<1>(20, false);
  const Eigen::VectorXd v = random_vector(d->dofs(), 1.0, 5), u = random_vector(d->dofs(), 0.2, 6);
  Eigen::VectorXd w_cur, w_ref;
  xsph_hook<1>(d, {.epsilon = 0.1, .current_positions = true})(u, v, w_cur);
  xsph_hook<1>(d, {.epsilon = 0.1, .current_positions = false})(u, v, w_ref);
  EXPECT_GT((w_cur - w_ref).cwiseAbs().maxCoeff(), 1e-4);  // the kernel moved with the particles
  Eigen::VectorXd w0;
  xsph_hook<1>(d, {.epsilon = 0.1, .current_positions = true})(Eigen::VectorXd::Zero(d->dofs()), v, w0);
  EXPECT_LT((w0 - w_ref).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Xsph, BadInput) {
  auto d = lattice<2>(4, false);
  EXPECT_THROW(xsph_hook<2>(nullptr), std::invalid_argument);
  EXPECT_THROW(xsph_hook<2>(d, {.epsilon = -1}), std::invalid_argument);
  EXPECT_THROW(xsph_smoothing_matrix(*d, {.epsilon = NAN}), std::invalid_argument);
  auto hook = xsph_hook<2>(d);
  Eigen::VectorXd w;
  EXPECT_THROW(hook(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3), w), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
