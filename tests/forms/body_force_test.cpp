// The body-force decorator (forms/body_force.hpp): the added acceleration is exactly b on every free DOF (real and
// complex overloads), the Jacobian is the inner one's entry for entry, the potential makes M a = -dU/du for a
// conservative inner form (complex step of the energy), and bad input.
#include "sphstab/forms/body_force.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "forms_fixture.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"

namespace sphstab {
namespace body_force_test {

using test::kLame;
using test::kRho;

std::shared_ptr<const FiniteStrainTotalLagrangian<2>> inner_form(double perturbation = 0.1) {
  auto d = test::lattice_discretisation<2>({.n = 5, .perturbation = perturbation});
  return std::make_shared<FiniteStrainTotalLagrangian<2>>(d, std::make_shared<StVenantKirchhoff<2>>(kLame), kRho);
}

TEST(BodyForce, AddsTheAccelerationExactlyOnEveryFreeDof) {
  const auto tl = inner_form();
  const Eigen::Vector2d b(0.3, -2.0);
  const BodyForce force(tl, b);
  ASSERT_EQ(force.dofs(), tl->dofs());
  ASSERT_EQ(force.dim(), 2);
  const Eigen::VectorXd u = test::random_vector(tl->dofs(), 0.05, 11);
  Eigen::VectorXd a, a0;
  force.acceleration(u, a);
  tl->acceleration(u, a0);
  ASSERT_GT(a0.cwiseAbs().maxCoeff(), 1e-3);  // a deformed state: the inner form is not trivially zero
  for (int k = 0; k < force.dofs(); ++k) EXPECT_EQ(a[k], a0[k] + b[k % 2]) << k;  // bitwise: one addition
  // the complex overload adds the same real b and leaves the imaginary part (the derivative) alone
  const Eigen::VectorXcd uc =
      u.cast<std::complex<double>>() + std::complex<double>(0, 1e-20) * Eigen::VectorXd::Ones(u.size());
  Eigen::VectorXcd ac, ac0;
  force.acceleration(uc, ac);
  tl->acceleration(uc, ac0);
  for (int k = 0; k < force.dofs(); ++k) {
    EXPECT_EQ(ac[k].real(), ac0[k].real() + b[k % 2]) << k;
    EXPECT_EQ(ac[k].imag(), ac0[k].imag()) << k;
  }
  // at rest the inner form gives exactly 0 (F = I), so a = b: free fall of an undeformed body
  force.acceleration(Eigen::VectorXd::Zero(force.dofs()), a);
  for (int k = 0; k < force.dofs(); ++k) EXPECT_EQ(a[k], b[k % 2]) << k;
}

TEST(BodyForce, JacobianIsTheInnerFormsEntryForEntry) {
  const auto tl = inner_form();
  const BodyForce force(tl, Eigen::Vector2d(0, -9.81));
  const Eigen::VectorXd u = test::random_vector(tl->dofs(), 0.05, 5);
  const Eigen::MatrixXd A = Eigen::MatrixXd(jacobian(force, u)), A0 = Eigen::MatrixXd(jacobian(*tl, u));
  ASSERT_GT(A0.cwiseAbs().maxCoeff(), 1e-2);  // not trivially zero
  EXPECT_EQ((A - A0).cwiseAbs().maxCoeff(), 0.0);
}

TEST(BodyForce, PotentialMakesTheForceTheNegativeEnergyGradient) {
  // Plain gradient, difference strain, plus divergence: the variational pair, so M a = -dU/du with U the strain
  // energy plus -sum m b u. dU/du by complex step (step 1e-30: exact to rounding), compared with -M a.
  const auto tl = inner_form(0.0);
  ASSERT_TRUE(tl->conservative());
  const Eigen::Vector2d b(0.5, -2.0);
  const BodyForce force(tl, b);
  ASSERT_TRUE(force.conservative());
  const Eigen::VectorXd u = test::random_vector(tl->dofs(), 0.05, 3);
  Eigen::VectorXd a;
  force.acceleration(u, a);
  const Eigen::VectorXd m = force.dof_mass(), ma = m.cwiseProduct(a);
  const double worst = test::max_abs(test::energy_gradient(force, u) + ma), scale = test::max_abs(ma);
  // both sides are sums of O(30) terms of size ~scale: rounding ~ 1e-14 scale; 1e-11 leaves margin
  EXPECT_LT(worst, 1e-11 * scale);
  // the potential's value: U_body(u) - U_inner(u) = -sum m b u exactly up to rounding
  double expected = 0;
  for (int k = 0; k < force.dofs(); ++k) expected -= m[k] * b[k % 2] * u[k];
  EXPECT_NEAR(force.strain_energy(u) - tl->strain_energy(u), expected, 1e-13 * m.sum());
}

TEST(BodyForce, RejectsBadInput) {
  const auto tl = inner_form();
  EXPECT_THROW(BodyForce(nullptr, Eigen::Vector2d(0, 1)), std::invalid_argument);
  EXPECT_THROW(BodyForce(tl, Eigen::Vector3d(0, 1, 0)), std::invalid_argument);
  EXPECT_THROW(BodyForce(tl, Eigen::Vector2d(0, std::numeric_limits<double>::quiet_NaN())), std::invalid_argument);
  EXPECT_THROW(BodyForce(tl, Eigen::Vector2d(std::numeric_limits<double>::infinity(), 0)), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
