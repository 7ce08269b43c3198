// Class-by-class growth of a mirror-symmetric block equals the growth of the whole spectrum, and the excited class is
// the one of the initial velocity.
#include "sphstab/growth/class_growth.hpp"

#include "sphstab/integrate/time_step.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <memory>

#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/problems/swegle.hpp"

namespace sphstab {
namespace class_growth_test {

TEST(ClassGrowth, ClassesTogetherGiveTheWholeSpectrum) {
  // 9 x 9 Swegle block in tension (unstable), centre particle pushed along +x: class (px, py) = (-1, +1).
  const SwegleScene s = make_swegle_scene({.n = 9, .area_ratio = 1.04});
  auto force = std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Plus, s.prestrain);
  const SparseMatrix<> A = jacobian(*force, Eigen::VectorXd::Zero(force->dofs()));
  const double mid = 0.5 * s.options.n * s.options.spacing;
  const MirrorClasses c = mirror_classes(mirror_symmetry(s.free_positions(), Eigen::Vector2d(mid, mid), 1e-8), s.v0);
  ASSERT_EQ(c.basis.size(), 4u);
  ASSERT_GE(c.excited, 0);
  EXPECT_EQ(c.parity[c.excited], std::make_pair(-1, 1));
  int columns = 0;
  for (const auto& q : c.basis) columns += static_cast<int>(q.cols());
  EXPECT_EQ(columns, force->dofs());  // the classes span the DOFs

  const ClassGrowth g = class_growth(A, c);
  const LinearGrowth whole = matrix_growth(Eigen::MatrixXd(A));
  EXPECT_LT(g.commutation, 1e-12);
  EXPECT_GT(whole.gamma, 1.0);
  EXPECT_NEAR(g.gamma_all, whole.gamma, 1e-9 * whole.gamma);
  EXPECT_NEAR(g.lambda_max, whole.lambda_max, 1e-9 * whole.lambda_max);
  EXPECT_LE(g.gamma_excited, g.gamma_all * (1 + 1e-12));
  EXPECT_NEAR(g.mode.norm(), 1.0, 1e-12);
  EXPECT_NEAR(class_share(c.symmetry, -1, 1, g.mode), 1.0, 1e-12);  // the mode lies in the excited class
  EXPECT_TRUE(std::isnan(g.gamma_map));                             // no dt given

  // With the identity as "smoothing" the leap-frog map of the class is the plain leap-frog map: its growth tends
  // to the excited class's gamma as dt -> 0.
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(force->dofs(), force->dofs());
  const ClassGrowth m = class_growth(A, c, identity, 1e-4 / std::sqrt(g.lambda_max));
  EXPECT_NEAR(m.gamma_map, g.gamma_excited, 1e-3 * g.gamma_excited);
  EXPECT_THROW(class_growth(A, c, identity, 0.0), std::invalid_argument);
  // Without a smoothing and dt > 0: the plain leap-frog map, the same growth as with the identity hook, and, at a
  // large dt, the closed form of leapfrog_growth_rate on the whole A's eigenvalues (the excited class holds the
  // fastest mode here: gamma_excited = gamma_all).
  const ClassGrowth plain = class_growth(A, c, {}, 1e-4 / std::sqrt(g.lambda_max));
  EXPECT_NEAR(plain.gamma_map, m.gamma_map, 1e-12 * m.gamma_map);
  ASSERT_NEAR(g.gamma_excited, g.gamma_all, 1e-12 * g.gamma_all);
  const double dt = 0.5 / std::sqrt(g.lambda_max);
  const Eigen::VectorXcd mu = Eigen::MatrixXd(A).eigenvalues();
  const double closed = leapfrog_growth_rate(mu, dt);
  EXPECT_NEAR(class_growth(A, c, {}, dt).gamma_map, closed, 1e-9 * closed);
  EXPECT_THROW(class_growth(A, c, {}, -1.0), std::invalid_argument);
  EXPECT_THROW(class_growth(SparseMatrix<>(3, 3), c), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
