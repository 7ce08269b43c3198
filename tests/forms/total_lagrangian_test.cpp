#include "sphstab/forms/total_lagrangian.hpp"

#include <gtest/gtest.h>

#include <random>

#include "forms_fixture.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace total_lagrangian_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2, 0.8, 7.8);

std::shared_ptr<const Discretisation<2>> block(int n, int fixed_layers = -1) {
  return test::lattice_discretisation<2>({.n = n, .fixed_layers = fixed_layers});
}

using test::random_vector;

using test::max_abs;

TEST(TotalLagrangianForm2D, EquilibriumAtThePreStrainedLatticeWithCompleteNeighbourhoods) {
  auto d = block(7);
  for (double xi : {0.96, 1.0, 1.04}) {
    TotalLagrangianForm2D tl(d, kMaterial, PreStrain::from_area_ratio(xi));
    Eigen::VectorXd a;
    tl.acceleration(Eigen::VectorXd::Zero(tl.dofs()), a);
    EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-14) << xi;
  }
}

TEST(TotalLagrangianForm2D, JacobianIsThePreStressFreeJacobianOfBasicSph) {
  // A = K for every pre-strain, equal to -da/du of ElasticForm2D(Plus) at u = 0 without pre-stress.
  auto d = block(6);
  ElasticForm2D plus(d, kMaterial, MomentumForm::Plus, PreStrain{});
  const Eigen::MatrixXd K(jacobian(plus, Eigen::VectorXd::Zero(plus.dofs())));
  for (double xi : {0.95, 1.05}) {
    TotalLagrangianForm2D tl(d, kMaterial, PreStrain::from_area_ratio(xi));
    const Eigen::MatrixXd A(jacobian(tl, random_vector(tl.dofs(), 0.1, 2)));  // linear: any u
    EXPECT_LT(max_abs(A - K), 1e-12 * max_abs(K)) << xi;
  }
}

TEST(TotalLagrangianForm2D, LinearAndConservativeWithAnOffset) {
  auto d = block(5, 1);  // one fixed layer: incomplete neighbourhoods, a0 != 0
  TotalLagrangianForm2D tl(d, kMaterial, PreStrain::uniaxial_x(0.02));
  ASSERT_GT(tl.offset().cwiseAbs().maxCoeff(), 1e-6);
  const Eigen::VectorXd u = random_vector(tl.dofs(), 0.1, 4), w = random_vector(tl.dofs(), 0.1, 5);
  Eigen::VectorXd au, aw, auw, a0;
  tl.acceleration(u, au);
  tl.acceleration(w, aw);
  tl.acceleration(Eigen::VectorXd(u + w), auw);
  tl.acceleration(Eigen::VectorXd::Zero(tl.dofs()), a0);
  EXPECT_LT((auw - au - aw + a0).cwiseAbs().maxCoeff(), 1e-13 * au.cwiseAbs().maxCoeff());
  // M a = -dU/du (complex-step gradient of the energy)
  const Eigen::VectorXd mau = tl.dof_mass().cwiseProduct(au);
  EXPECT_LT(max_abs(mau + test::energy_gradient(tl, u)), 1e-12 * max_abs(mau));
  // complex overload: real part a(Re u), imaginary part a(Im u) - a0
  Eigen::VectorXcd z(tl.dofs()), az;
  z.real() = u;
  z.imag() = w;
  tl.acceleration(z, az);
  EXPECT_LT((az.real() - au).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((az.imag() - (aw - a0)).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(TotalLagrangianForm2D, BadInput) {
  auto d = block(4);
  EXPECT_THROW(TotalLagrangianForm2D(nullptr, kMaterial), std::invalid_argument);
  EXPECT_THROW(TotalLagrangianForm2D(d, ElasticMaterial::from_lame(1, -1, 1)), std::invalid_argument);
  EXPECT_THROW(TotalLagrangianForm2D(d, kMaterial, PreStrain{PreStrainKind::Isotropic, NAN}), std::invalid_argument);
  TotalLagrangianForm2D tl(d, kMaterial);
  Eigen::VectorXd a;
  EXPECT_THROW(tl.acceleration(Eigen::VectorXd::Zero(3), a), std::invalid_argument);
  EXPECT_THROW(tl.with_load(INFINITY), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
