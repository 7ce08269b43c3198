#include "sphstab/stability/equilibrium.hpp"

#include <gtest/gtest.h>

#include "sphstab/forms/stabilised_sph.hpp"
#include "sphstab/forms/total_lagrangian.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace equilibrium_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2, 0.8, 7.8);

std::shared_ptr<const Discretisation<2>> block(int n, int fixed_layers = -1) {
  Kernel<2> k(KernelType::CubicSpline);
  auto set = make_lattice<2>(LatticeType::Square, n,
                             {.spacing = 1.0, .fixed_layers = fixed_layers, .support_radius = k.support_radius(1.3)});
  return make_discretisation(set, k, 1.3);
}

TEST(Equilibrium, LinearForceConvergesInOneNewtonStep) {
  TotalLagrangianForm2D tl(block(5, 1), kMaterial, PreStrain::uniaxial_x(0.02));  // a0 != 0
  const Equilibrium eq = find_equilibrium(tl, Eigen::VectorXd::Zero(tl.dofs()));
  ASSERT_EQ(eq.status, Status::Successful) << eq.message;
  EXPECT_EQ(eq.iterations, 1);
  EXPECT_LT(eq.residual, 1e-13 * eq.initial_residual);
  // u* = A^{-1} a0 exactly
  const Eigen::MatrixXd A(jacobian(tl, Eigen::VectorXd::Zero(tl.dofs())));
  EXPECT_LT((A * eq.u - tl.offset()).cwiseAbs().maxCoeff(), 1e-12 * tl.offset().cwiseAbs().maxCoeff());
}

TEST(Equilibrium, SymmetrisedStabilisedSphNearFixedLayers) {
  auto force = make_stabilised_sph(block(9), kMaterial, PreStrain::from_area_ratio(1.01));
  const Equilibrium eq = find_equilibrium(*force, Eigen::VectorXd::Zero(force->dofs()), {.load_steps = 2});
  ASSERT_EQ(eq.status, Status::Successful) << eq.message;
  EXPECT_GT(eq.initial_residual, 1e-4);  // not an equilibrium at the lattice
  EXPECT_LT(eq.residual, 1e-12 * eq.initial_residual);
  EXPECT_GT(eq.u.cwiseAbs().maxCoeff(), 1e-4);  // the boundary particles move
}

TEST(Equilibrium, AlreadyInEquilibriumAndBadInput) {
  TotalLagrangianForm2D tl(block(5), kMaterial, PreStrain::from_area_ratio(1.02));
  const Equilibrium eq = find_equilibrium(tl, Eigen::VectorXd::Zero(tl.dofs()), {.accel_scale = 1.0});
  EXPECT_EQ(eq.status, Status::Successful);
  EXPECT_EQ(eq.iterations, 0);
  EXPECT_THROW(find_equilibrium(tl, Eigen::VectorXd::Zero(3)), std::invalid_argument);
  EXPECT_THROW(find_equilibrium(tl, Eigen::VectorXd::Zero(tl.dofs()), {.max_iterations = 0}), std::invalid_argument);
  EXPECT_THROW(find_equilibrium(tl, Eigen::VectorXd::Zero(tl.dofs()), {.load_steps = 0}), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
