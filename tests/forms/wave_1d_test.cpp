#include "sphstab/forms/wave_1d.hpp"

#include <gtest/gtest.h>

#include <random>

#include "forms_fixture.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace wave_1d_test {

std::shared_ptr<const Discretisation<1>> line(int n, KernelType type, double h, bool periodic = false,
                                              double perturbation = 0.0) {
  return test::lattice_discretisation<1>(
      {.n = n, .kernel = type, .h = h, .periodic = periodic, .perturbation = perturbation, .seed = 7});
}

using test::random_vector;

/// Powell (3.40), written independently of the force code: A(T) = G_f G_f^T - n T L with
/// L = diag(sum_{j != i} H_ij) - H on the free block (operators at the reference positions).
Eigen::MatrixXd analytic_jacobian(const Discretisation<1>& d, double T, int n) {
  auto ops = assemble_operators(d.particles, d.neighbours, d.kernel, d.h,
                                {.kernel = false, .gradient = true, .hessian = true});
  Eigen::MatrixXd G = ops.G[0], H = ops.H[0][0];
  const int nf = d.free_count();
  Eigen::MatrixXd Gf(nf, d.size()), L(nf, nf);
  for (int f = 0; f < nf; ++f) Gf.row(f) = G.row(d.free[f]);
  for (int f = 0; f < nf; ++f)
    for (int g = 0; g < nf; ++g) L(f, g) = -H(d.free[f], d.free[g]);
  for (int f = 0; f < nf; ++f) {
    const int i = d.free[f];
    L(f, f) += H.row(i).sum() - H(i, i);
  }
  return Gf * Gf.transpose() - n * T * L;
}

using test::max_abs;

TEST(WaveForm1D, GenericJacobianEqualsAnalyticFormula) {
  // Several kernels, h/dx, N and T; every form (Powell 3.38, 3.40).
  for (KernelType type : {KernelType::CubicSpline, KernelType::QuinticSpline, KernelType::WendlandC2,
                          KernelType::WendlandC6, KernelType::Gaussian})
    for (double h : {1.0, 1.3, 1.8})
      for (int n : {12, 31}) {
        auto d = line(n, type, h);
        for (double T : {-0.3, 0.7})
          for (MomentumForm form : all_momentum_forms()) {
            WaveForm1D force(d, form, T);
            Eigen::MatrixXd A = jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
            Eigen::MatrixXd ref = analytic_jacobian(*d, T, initial_stress_multiplier(form));
            EXPECT_LE(max_abs(A - ref), 1e-10 * max_abs(ref))
                << kernel_name(type) << " h=" << h << " n=" << n << " T=" << T << " " << force.name();
          }
      }
}

TEST(WaveForm1D, MinusFormHasNoTensionDependence) {
  auto d = line(25, KernelType::CubicSpline, 1.3);
  WaveForm1D force(d, MomentumForm::Minus, 0.4);
  auto at_rest = affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
  EXPECT_EQ(at_rest.A1.norm(), 0.0);  // exact: Im(s_j - s_i) does not contain T at all
  // At a displaced state T cancels up to the rounding of Re(s_j - s_i) = (a_j + T) - (a_i + T).
  auto moved = affine_jacobian(force, random_vector(force.dofs(), 0.1, 3));
  EXPECT_LE(moved.A1.norm(), 1e-13 * moved.A0.norm());
}

TEST(WaveForm1D, TensionTermsScaleOneTwoFour) {
  for (KernelType type : {KernelType::CubicSpline, KernelType::WendlandC4}) {
    auto d = line(20, type, 1.4);
    const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(d->dofs());
    Eigen::MatrixXd A1u = affine_jacobian(WaveForm1D(d, MomentumForm::Uncorrected, 0.1), u0).A1;
    Eigen::MatrixXd A1p = affine_jacobian(WaveForm1D(d, MomentumForm::Plus, 0.1), u0).A1;
    Eigen::MatrixXd A1c = affine_jacobian(WaveForm1D(d, MomentumForm::Conservative, 0.1), u0).A1;
    ASSERT_GT(max_abs(A1u), 0.1);  // the T-term exists (cubic and Wendland have W'' != 0 at neighbours)
    EXPECT_LE(max_abs(A1p - 2 * A1u), 1e-12 * max_abs(A1u));
    EXPECT_LE(max_abs(A1c - 4 * A1u), 1e-12 * max_abs(A1u));
  }
}

TEST(WaveForm1D, JacobianIsAffineInTension) {
  auto d = line(18, KernelType::QuarticSpline, 1.3);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.08, 11);
  for (MomentumForm form : all_momentum_forms()) {
    WaveForm1D force(d, form, 0.0);
    auto split = affine_jacobian(force, u);
    for (double T : {0.37, -1.9}) {
      Eigen::MatrixXd direct = jacobian(*force.with_load(T), u);
      Eigen::MatrixXd affine = split.at(T);
      EXPECT_LE(max_abs(direct - affine), 1e-12 * max_abs(direct)) << force.name() << " T=" << T;
    }
  }
}

TEST(WaveForm1D, ConservativeForceIsMinusEnergyGradient) {
  // a = -M^{-1} dU/du, dU/du by complex step of U, at a displaced state with displaced fixed particles and
  // unequal volumes (perturbed lattice keeps volumes equal, so scale a few by hand).
  for (KernelType type : {KernelType::CubicSpline, KernelType::WendlandC2, KernelType::Gaussian}) {
    auto base = line(15, type, 1.3, false, 0.1);
    ParticleSet<1> set = base->particles;
    for (int i = 0; i < set.size(); i += 3) set.volume[i] *= 1.2;
    auto d = make_discretisation(set, base->kernel, base->h);
    WaveForm1D force(d, MomentumForm::Conservative, 0.3);
    force.set_fixed_displacement(random_vector(d->size() - d->free_count(), 0.05, 5));
    const Eigen::VectorXd u = random_vector(force.dofs(), 0.1, 4);
    Eigen::VectorXd a;
    force.acceleration(u, a);
    const Eigen::VectorXd m = force.dof_mass(), dU = test::energy_gradient(force, u);
    for (int k = 0; k < force.dofs(); ++k)
      EXPECT_NEAR(-dU[k] / m[k], a[k], 1e-12 * a.cwiseAbs().maxCoeff()) << kernel_name(type) << " dof " << k;
    // The plus form is not the gradient of this energy (Powell Example 3.9).
    WaveForm1D plus(d, MomentumForm::Plus, 0.3);
    Eigen::VectorXd ap;
    plus.acceleration(u, ap);
    EXPECT_GT((ap - a).cwiseAbs().maxCoeff(), 1e-4 * a.cwiseAbs().maxCoeff());
  }
}

TEST(WaveForm1D, ConservativeJacobianIsSymmetricPlusIsNot) {
  auto d = line(20, KernelType::CubicSpline, 1.3);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.1, 8);
  for (MomentumForm form : all_momentum_forms()) {
    WaveForm1D force(d, form, 0.5);
    // At the lattice equilibrium every form is symmetric: K and L are (Powell 3.40).
    EXPECT_LE(relative_asymmetry(jacobian(force, Eigen::VectorXd::Zero(force.dofs()))), 1e-14) << force.name();
    const double asym = relative_asymmetry(jacobian(force, u));
    if (form == MomentumForm::Conservative)
      EXPECT_LE(asym, 1e-14);  // Thm 3.8 (equal volumes: M = V I)
    else
      EXPECT_GT(asym, 1e-3) << force.name();  // Example 3.9: not integrable
  }
}

TEST(WaveForm1D, PlusIsSymmetricAtRestOnADisorderedSet) {
  // u = 0, s = T uniform: A_plus = D^T D - 2 T L with D = G - diag(G 1) (G antisymmetric, equal volumes), while
  // the uncorrected form keeps the non-symmetric G D.
  auto d = line(20, KernelType::CubicSpline, 1.3, false, 0.15);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(d->dofs());
  EXPECT_LE(relative_asymmetry(jacobian(WaveForm1D(d, MomentumForm::Plus, 0.5), zero)), 1e-14);
  EXPECT_GT(relative_asymmetry(jacobian(WaveForm1D(d, MomentumForm::Uncorrected, 0.5), zero)), 1e-3);
}

TEST(WaveForm1D, EquilibriumHasZeroForce) {
  for (KernelType type : {KernelType::CubicSpline, KernelType::QuinticSpline, KernelType::WendlandC4})
    for (double h : {1.1, 1.6}) {
      auto d = line(17, type, h);
      for (MomentumForm form : all_momentum_forms()) {
        WaveForm1D force(d, form, 0.8);
        Eigen::VectorXd a;
        force.acceleration(Eigen::VectorXd::Zero(force.dofs()), a);
        // scale of the individual terms: T * sum_j |G_ij| ~ T / h
        EXPECT_LE(a.cwiseAbs().maxCoeff(), 1e-14 * 0.8 / h * 10) << force.name();
      }
    }
}

TEST(WaveForm1D, PlusAndConservativeConserveMomentumOnPeriodicSet) {
  auto d = line(24, KernelType::WendlandC2, 1.5, /*periodic=*/true, 0.1);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.1, 21);
  for (MomentumForm form : all_momentum_forms()) {
    WaveForm1D force(d, form, 0.6);
    Eigen::VectorXd a;
    force.acceleration(u, a);
    const double p = force.dof_mass().dot(a), scale = force.dof_mass().dot(a.cwiseAbs());
    if (form == MomentumForm::Plus || form == MomentumForm::Conservative)
      EXPECT_LE(std::abs(p), 1e-13 * scale) << force.name();
    else
      EXPECT_GT(std::abs(p), 1e-6 * scale) << force.name();  // no antisymmetric pair force
  }
}

TEST(WaveForm1D, TranslationWithFixedParticlesGivesTheRestForce) {
  auto d = line(14, KernelType::CubicSpline, 1.3, false, 0.1);
  for (MomentumForm form : all_momentum_forms()) {
    WaveForm1D force(d, form, 0.5);
    Eigen::VectorXd a0, a1;
    force.acceleration(Eigen::VectorXd::Zero(force.dofs()), a0);
    force.set_fixed_displacement(Eigen::VectorXd::Constant(d->size() - d->free_count(), 0.37));
    force.acceleration(Eigen::VectorXd::Constant(force.dofs(), 0.37), a1);
    EXPECT_LE((a1 - a0).cwiseAbs().maxCoeff(), 1e-13) << force.name();
  }
}

TEST(WaveForm1D, MinusGradientProviderEqualsMinusForm) {
  auto d = line(20, KernelType::QuinticSpline, 1.2, false, 0.05);
  auto minus_gradient = std::make_shared<MinusGradient<1>>();
  WaveForm1D via_provider(d, MomentumForm::Uncorrected, 0.3, minus_gradient);
  WaveForm1D minus(d, MomentumForm::Minus, 0.3);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.1, 2);
  Eigen::VectorXd a1, a2;
  via_provider.acceleration(u, a1);
  minus.acceleration(u, a2);
  EXPECT_LE((a1 - a2).cwiseAbs().maxCoeff(), 1e-13 * a2.cwiseAbs().maxCoeff());
  Eigen::MatrixXd A1 = jacobian(via_provider, u), A2 = jacobian(minus, u);
  EXPECT_LE(max_abs(A1 - A2), 1e-12 * max_abs(A2));
  // The conservative form can only take the correction into its strain, where the minus correction changes nothing
  // (sum_j (u_j - u_i) (G - diag(G 1))_ij = sum_j (u_j - u_i) G_ij): the dual-number energy gradient must then
  // reproduce the closed form (3.27).
  EXPECT_THROW(
      WaveForm1D(d, MomentumForm::Conservative, 0.3, minus_gradient, {.corrected = CorrectedOperator::Divergence}),
      std::invalid_argument);
  WaveForm1D cons_minus(d, MomentumForm::Conservative, 0.3, minus_gradient);
  WaveForm1D cons(d, MomentumForm::Conservative, 0.3);
  EXPECT_TRUE(cons_minus.strain_corrected());
  cons_minus.acceleration(u, a1);
  cons.acceleration(u, a2);
  EXPECT_LE((a1 - a2).cwiseAbs().maxCoeff(), 1e-13 * a2.cwiseAbs().maxCoeff());
  EXPECT_LE(max_abs(Eigen::MatrixXd(jacobian(cons_minus, u)) - Eigen::MatrixXd(jacobian(cons, u))),
            1e-12 * max_abs(jacobian(cons, u)));
}

TEST(WaveForm1D, ComplexPathEqualsRealPath) {
  auto d = line(16, KernelType::WendlandC6, 1.7, false, 0.1);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.1, 9);
  for (MomentumForm form : all_momentum_forms()) {
    WaveForm1D force(d, form, -0.4);
    Eigen::VectorXd a;
    Eigen::VectorXcd ac;
    force.acceleration(u, a);
    force.acceleration(Eigen::VectorXcd(u.cast<std::complex<double>>()), ac);
    // complex sqrt/pow round differently from the real ones: agreement to a few ulps, not bitwise
    EXPECT_LE((ac.real() - a).cwiseAbs().maxCoeff(), 1e-13 * a.cwiseAbs().maxCoeff());
    EXPECT_EQ(ac.imag().cwiseAbs().maxCoeff(), 0.0);
    EXPECT_NEAR(force.strain_energy(Eigen::VectorXcd(u.cast<std::complex<double>>())).real(), force.strain_energy(u),
                1e-13 * force.strain_energy(u));
  }
}

TEST(WaveForm1D, AccelerationFunctionAdapterAndEnergy) {
  auto d = line(10, KernelType::CubicSpline, 1.3);
  auto force = std::make_shared<WaveForm1D>(d, MomentumForm::Conservative, 0.2);
  AccelerationFunction rhs = acceleration_function(force);
  const Eigen::VectorXd u = random_vector(force->dofs(), 0.1, 1);
  Eigen::VectorXd a1, a2;
  rhs(u, a1);
  force->acceleration(u, a2);
  EXPECT_EQ(a1, a2);
  // U(0) = 1/2 T^2 sum_i V_i over all particles (s = T everywhere at rest).
  EXPECT_NEAR(force->strain_energy(Eigen::VectorXd(Eigen::VectorXd::Zero(force->dofs()))),
              0.5 * 0.04 * d->particles.volume.sum(), 1e-15);
  const Eigen::VectorXd v = Eigen::VectorXd::Constant(force->dofs(), 2.0);
  EXPECT_NEAR(total_energy(*force, u, v), 2.0 * force->dof_mass().sum() + force->strain_energy(u), 1e-13);
}

TEST(WaveForm1D, RejectsBadInput) {
  auto d = line(10, KernelType::CubicSpline, 1.3);
  EXPECT_THROW(WaveForm1D(nullptr, MomentumForm::Plus, 0.0), std::invalid_argument);
  EXPECT_THROW(WaveForm1D(d, MomentumForm::Plus, std::nan("")), std::invalid_argument);
  WaveForm1D force(d, MomentumForm::Plus, 0.1);
  Eigen::VectorXd a;
  EXPECT_THROW(force.acceleration(Eigen::VectorXd::Zero(3), a), std::invalid_argument);
  EXPECT_THROW(force.set_fixed_displacement(Eigen::VectorXd::Zero(1)), std::invalid_argument);
  EXPECT_THROW(force.with_load(INFINITY), std::invalid_argument);
  EXPECT_THROW(parse_momentum_form("lagrangian"), std::invalid_argument);
  EXPECT_EQ(parse_momentum_form("conservative"), MomentumForm::Conservative);
  EXPECT_THROW(momentum_form_alpha(MomentumForm::Conservative), std::invalid_argument);
  EXPECT_THROW(acceleration_function(nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
