// Ismail's boundary methods (operators/ismail_boundary.hpp): the eta method's sums against the rows of the SPH
// matrices W and X, the prescribed value reached exactly, linear fields left unchanged, the vanishing Neumann
// denominator of a symmetric correction set; the modified-matrix Dirichlet method against a dense solve of
// Ismail's (2.46) matrix, the printed rows-and-columns variant missing the boundary value, and a singular W_CC.
#include "sphstab/operators/ismail_boundary.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace ismail_boundary_test {

Eigen::VectorXd random_field(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-1, 1);
  Eigen::VectorXd v(n);
  for (int k = 0; k < n; ++k) v[k] = dist(gen);
  return v;
}

struct Line {
  ParticleSet<1> set;
  Kernel<1> kernel{KernelType::ModifiedMollifier};
  double h = 2.75;  // Ismail's 5.5 dx
  std::vector<int> free, right_ghosts, left_ghosts;
  int last_free = 0, first_free = 0;
};

Line make_line(int n) {
  Line l;
  l.set = make_lattice<1>(LatticeType::Line, n, {.spacing = 1.0, .support_radius = l.kernel.support_radius(l.h)});
  double xmin = 1e300, xmax = -1e300;
  for (int i = 0; i < l.set.size(); ++i)
    if (l.set.role[i] == Role::Free) {
      l.free.push_back(i);
      if (l.set.x(i, 0) > xmax) xmax = l.set.x(i, 0), l.last_free = i;
      if (l.set.x(i, 0) < xmin) xmin = l.set.x(i, 0), l.first_free = i;
    }
  for (int i = 0; i < l.set.size(); ++i)
    if (l.set.role[i] != Role::Free) (l.set.x(i, 0) > xmax ? l.right_ghosts : l.left_ghosts).push_back(i);
  return l;
}

SparseMatrix<> matrix(const Line& l, bool gradient) {
  const NeighbourList nl = find_neighbours(l.set, l.kernel.support_radius(l.h));
  return gradient ? gradient_matrix(l.set, nl, l.kernel, l.h, 0) : kernel_matrix(l.set, nl, l.kernel, l.h);
}

TEST(EtaBoundary1D, SumsAreTheRowsOfIsmailsWAndX) {
  const Line l = make_line(30);
  const Eigen::VectorXd f = random_field(l.set.size(), 1);
  const Eigen::VectorXd wf = matrix(l, false) * f, xf = matrix(l, true) * f;
  const EtaBoundary1D dir(l.set, l.kernel, l.h, l.last_free, l.right_ghosts, BoundaryCondition::Dirichlet);
  const EtaBoundary1D neu(l.set, l.kernel, l.h, l.first_free, l.left_ghosts, BoundaryCondition::Neumann, -1);
  EXPECT_NEAR(dir.value(f), wf[l.last_free], 1e-13);
  EXPECT_NEAR(neu.value(f), -xf[l.first_free], 1e-12);
}

TEST(EtaBoundary1D, PrescribedValueIsReachedExactlyAndOnlyTheTargetsChange) {
  const Line l = make_line(30);
  for (const auto cond : {BoundaryCondition::Dirichlet, BoundaryCondition::Neumann}) {
    const EtaBoundary1D wall(l.set, l.kernel, l.h, l.last_free, l.right_ghosts, cond, 1);
    Eigen::VectorXd f = random_field(l.set.size(), 2);
    const Eigen::VectorXd before = f;
    wall.apply(f, 0.37);
    EXPECT_NEAR(wall.value(f), 0.37, 1e-12);
    for (int i : l.free) EXPECT_EQ(f[i], before[i]);
    for (int i : l.left_ghosts) EXPECT_EQ(f[i], before[i]);
  }
}

TEST(EtaBoundary1D, LinearFieldWithItsOwnBoundaryValuesIsLeftUnchanged) {
  // Support 5.5 dx: sum W dV = 1 and <x_x> = 1 to ~1e-5 (lattice sum), so a linear field f = 2 x + 1 already satisfies
  // its own Dirichlet value and slope at b and eta is ~0.
  const Line l = make_line(30);
  Eigen::VectorXd f = (2 * l.set.x.col(0)).array() + 1.0;
  const double xb = l.set.x(l.last_free, 0);
  const EtaBoundary1D dir(l.set, l.kernel, l.h, l.last_free, l.right_ghosts, BoundaryCondition::Dirichlet);
  const EtaBoundary1D neu(l.set, l.kernel, l.h, l.last_free, l.right_ghosts, BoundaryCondition::Neumann, 1);
  const double w0 = l.kernel.value(0.0, l.h);
  EXPECT_LT(std::abs(dir.apply(f, 2 * xb + 1)) * w0, 1e-4 * std::abs(2 * xb + 1));
  // The plain sum's slope error (~1e-5 relative) is divided by the small one-sided N: the ghost change stays below
  // 1e-3 of the field's change over one spacing (2 dx).
  EXPECT_NEAR(neu.value(f) / 2.0, 1.0, 1e-4);
  EXPECT_LT(std::abs(neu.apply(f, 2.0)) * w0, 1e-3 * 2.0);
  // and a wrong slope is corrected exactly (and visibly)
  const double eta = neu.apply(f, 3.0);
  EXPECT_NEAR(neu.value(f), 3.0, 1e-12);
  EXPECT_GT(std::abs(eta) * w0, 0.1);
}

TEST(EtaBoundary1D, SymmetricNeumannSetHasAVanishingDenominator) {
  // Ismail's printed sum over B + I + G: sum W W' dV = 0 over a symmetric cover (W W' odd) -> one-line error.
  const Line l = make_line(30);
  const int b = l.free[15];
  std::vector<int> both;
  for (int i = 0; i < l.set.size(); ++i)
    if (i != b && std::abs(l.set.x(i, 0) - l.set.x(b, 0)) < l.kernel.support_radius(l.h)) both.push_back(i);
  EXPECT_THROW(EtaBoundary1D(l.set, l.kernel, l.h, b, both, BoundaryCondition::Neumann), std::invalid_argument);
  EXPECT_NO_THROW(EtaBoundary1D(l.set, l.kernel, l.h, b, both, BoundaryCondition::Dirichlet));
  try {
    EtaBoundary1D(l.set, l.kernel, l.h, b, both, BoundaryCondition::Neumann);
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  EXPECT_THROW(EtaBoundary1D(l.set, l.kernel, l.h, b, {b}, BoundaryCondition::Dirichlet), std::invalid_argument);
  EXPECT_THROW(EtaBoundary1D(l.set, l.kernel, l.h, l.last_free, l.left_ghosts, BoundaryCondition::Dirichlet),
               std::invalid_argument);  // targets outside the support of b
}

TEST(ModifiedMatrixDirichlet, AgreesWithADenseSolveOfIsmailsMatrixAndHitsTheBoundaryValues) {
  const Line l = make_line(30);
  const SparseMatrix<> w = matrix(l, false);
  std::vector<int> c{l.last_free};  // B: the last free particle; G: the right ghosts
  c.insert(c.end(), l.right_ghosts.begin(), l.right_ghosts.end());
  const ModifiedMatrixDirichlet mm(w, c);
  const Eigen::VectorXd f0 = random_field(l.set.size(), 4);
  const Eigen::VectorXd fbar = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(c.size()), 0.25);
  Eigen::VectorXd f = f0;
  mm.apply(f, fbar);
  const Eigen::VectorXd wf = w * f;
  for (std::size_t k = 0; k < c.size(); ++k) EXPECT_NEAR(wf[c[k]], 0.25, 1e-9) << k;
  for (int i : l.free)
    if (i != l.last_free) EXPECT_EQ(f[i], f0[i]);
  // Ismail (2.46) with the interior rows replaced by identity rows, solved densely (an independent route)
  Eigen::MatrixXd m = Eigen::MatrixXd(w);
  Eigen::VectorXd rhs = f0;
  std::vector<char> in_c(l.set.size(), 0);
  for (std::size_t k = 0; k < c.size(); ++k) in_c[c[k]] = 1, rhs[c[k]] = 0.25;
  for (int i = 0; i < l.set.size(); ++i)
    if (!in_c[i]) m.row(i).setZero(), m(i, i) = 1;
  const Eigen::VectorXd dense = m.fullPivLu().solve(rhs);
  EXPECT_LT((dense - f).cwiseAbs().maxCoeff(), 1e-8 * std::max(1.0, dense.cwiseAbs().maxCoeff()));
  // the printed variant (rows AND columns of the interior zeroed: block diagonal) drops W_CI f_I and misses fbar
  Eigen::MatrixXd printed = m;
  for (int i = 0; i < l.set.size(); ++i)
    if (!in_c[i])
      for (int j = 0; j < l.set.size(); ++j)
        if (j != i) printed(j, i) = 0;
  const Eigen::VectorXd g = printed.fullPivLu().solve(rhs);
  double miss = 0;
  for (std::size_t k = 0; k < c.size(); ++k) miss = std::max(miss, std::abs((w * g)[c[k]] - 0.25));
  EXPECT_GT(miss, 1e-2);
}

TEST(ModifiedMatrixDirichlet, WorksInTwoDimensionsOnTheFixedLayers) {
  // [Ismail2009] §2.9: the method is dimension-free; C = every fixed particle of a 2D lattice, prescribed values from
  // a linear field, interior values random.
  const Kernel<2> kernel(KernelType::ModifiedMollifier);
  const double h = 1.5;
  const ParticleSet<2> set =
      make_lattice<2>(LatticeType::Square, 8, {.spacing = 1.0, .support_radius = kernel.support_radius(h)});
  const NeighbourList nl = find_neighbours(set, kernel.support_radius(h));
  const SparseMatrix<> w = kernel_matrix(set, nl, kernel, h);
  const std::vector<int> c = set.indices(Role::Fixed);
  Eigen::VectorXd fbar(static_cast<Eigen::Index>(c.size()));
  for (std::size_t k = 0; k < c.size(); ++k) fbar[k] = 0.5 * set.x(c[k], 0) - set.x(c[k], 1);
  const ModifiedMatrixDirichlet mm(w, c);
  Eigen::VectorXd f = random_field(set.size(), 5);
  const Eigen::VectorXd f0 = f;
  mm.apply(f, fbar);
  const Eigen::VectorXd wf = w * f;
  for (std::size_t k = 0; k < c.size(); ++k) EXPECT_NEAR(wf[c[k]], fbar[k], 1e-9);
  for (int i : set.indices(Role::Free)) EXPECT_EQ(f[i], f0[i]);
}

TEST(ModifiedMatrixDirichlet, SingularBlockAndBadInputAreOneLineErrors) {
  ParticleSet<1> set;
  set.x.resize(4, 1);
  set.x << 0.0, 1.0, 1.0, 2.0;  // particles 1 and 2 coincide: W_CC has two equal rows
  set.volume = Eigen::VectorXd::Ones(4);
  set.role = std::vector<Role>(4, Role::Free);
  set.depth = std::vector<int>(4, 0);
  const Kernel<1> kernel(KernelType::CubicSpline);
  const NeighbourList nl = find_neighbours(set, kernel.support_radius(1.0));
  const SparseMatrix<> w = kernel_matrix(set, nl, kernel, 1.0);
  EXPECT_THROW(ModifiedMatrixDirichlet(w, {1, 2}), std::invalid_argument);
  EXPECT_NO_THROW(ModifiedMatrixDirichlet(w, {0, 1}));
  EXPECT_THROW(ModifiedMatrixDirichlet(w, {}), std::invalid_argument);
  EXPECT_THROW(ModifiedMatrixDirichlet(w, {0, 0}), std::invalid_argument);
  EXPECT_THROW(ModifiedMatrixDirichlet(w, {7}), std::invalid_argument);
  try {
    ModifiedMatrixDirichlet(w, {1, 2});
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_EQ(std::string(e.what()).rfind("ModifiedMatrixDirichlet:", 0), 0u);
  }
}

}  // namespace
}  // namespace sphstab
