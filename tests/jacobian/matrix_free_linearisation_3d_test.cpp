// The 3D matrix-free linearisation against independent codings: A0 against the TL acceleration of
// LinearElasticSph<3> (minus gradient, plus divergence: a(u) = -A0 u exactly, a different code path: sparse gradient
// and divergence matrices), A1 of the conservative form with isotropic pre-stress against a central finite difference
// of the kernel-gradient sum F_i = sum_j grad W(x_i - x_j) V_j (A1 v = -(4 s / rho) dF/dt along v, s the pre-stress
// per unit strain); the 3D critical strain by block LOBPCG, with and without the sine preconditioner, against a dense
// reference (Eigen's generalised self-adjoint solver on the matrices assembled by products) and the engine's direct
// route (critical_load) on the same assembled linearisation.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "sphstab/forms/linear_elastic.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/lattice_sine_preconditioner.hpp"
#include "sphstab/stability/lattice_stencil.hpp"
#include "sphstab/stability/matrix_free_critical_load.hpp"
#include "vector_comparison.hpp"

namespace sphstab {
namespace matrix_free_linearisation_3d_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);
constexpr double kH = 1.3;

ParticleSet<3> cubic(int n, double perturbation = 0) {
  const Kernel<3> k(KernelType::CubicSpline);
  return make_lattice<3>(LatticeType::Cubic, n,
                         {.support_radius = k.support_radius(kH), .perturbation = perturbation, .seed = 5});
}

std::shared_ptr<const Discretisation<3>> discretise(const ParticleSet<3>& set) {
  return make_discretisation(set, Kernel<3>(KernelType::CubicSpline), kH);
}

using test::random_vector;
using test::relative_difference;

TEST(MatrixFreeLinearisation3D, A0IsMinusTheTotalLagrangianAcceleration) {
  // Jittered positions: no lattice identity helps; unequal volumes would break nothing here either.
  for (double jitter : {0.0, 0.15}) {
    const ParticleSet<3> set = cubic(5, jitter);
    const auto disc = discretise(set);
    const MatrixFreeLinearisation<3> lin(*disc, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
    const LinearElasticSph<3> tl(
        set, Kernel<3>(KernelType::CubicSpline), kH,
        {.material = kMaterial, .gradient = StrainGradient::Minus, .divergence = StressDivergence::Plus});
    ASSERT_EQ(tl.free_count() * 3, lin.dofs());
    for (std::uint64_t seed : {1, 2, 3}) {
      const Eigen::VectorXd u = random_vector(lin.dofs(), seed);
      Eigen::VectorXd a(lin.dofs()), y(lin.dofs());
      tl.acceleration(u, a);
      lin.apply_A0(u, y);
      EXPECT_LT(relative_difference(y, -a), 1e-13) << "jitter " << jitter << " seed " << seed;
    }
  }
}

TEST(MatrixFreeLinearisation3D, A1IsTheDerivativeOfTheKernelGradientSum) {
  const ParticleSet<3> set = cubic(4, 0.1);
  const auto disc = discretise(set);
  const MatrixFreeLinearisation<3> lin(*disc, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const Kernel<3> kernel(KernelType::CubicSpline);
  const double s = 3 * kMaterial.lambda() + 2 * kMaterial.mu();  // isotropic 3D pre-stress per unit strain
  const int nf = lin.free_count(), n = set.size();
  // F_i(x) over all particles j (fixed ones do not move), brute force over every pair.
  auto kernel_gradient_sum = [&](const Eigen::MatrixXd& x) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * nf);
    for (int fi = 0; fi < nf; ++fi) {
      const int i = lin.free_index()[fi];
      for (int j = 0; j < n; ++j) {
        if (j == i) continue;
        const Eigen::RowVector3d d = x.row(i) - x.row(j);
        const double r = d.norm();
        if (r >= kernel.support_radius(kH)) continue;
        f.segment<3>(3 * fi) += kernel.d1(r, kH) / r * set.volume[j] * d.transpose();
      }
    }
    return f;
  };
  const Eigen::VectorXd v = random_vector(lin.dofs(), 9);
  const double t = 1e-5;
  Eigen::MatrixXd xp = set.x, xm = set.x;
  for (int fi = 0; fi < nf; ++fi) {
    xp.row(lin.free_index()[fi]) += t * v.segment<3>(3 * fi).transpose();
    xm.row(lin.free_index()[fi]) -= t * v.segment<3>(3 * fi).transpose();
  }
  const Eigen::VectorXd lv = (kernel_gradient_sum(xp) - kernel_gradient_sum(xm)) / (2 * t);
  Eigen::VectorXd y(lin.dofs());
  lin.apply_A1(v, y);
  EXPECT_LT(relative_difference(y, -(4 * s / kMaterial.density()) * lv), 1e-7);
  // A1 of the plus form is half the conservative one for isotropic pre-stress (analytic_jacobian_2d.hpp, (iii)).
  const MatrixFreeLinearisation<3> plus(*disc, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic);
  Eigen::VectorXd yp(lin.dofs());
  plus.apply_A1(v, yp);
  EXPECT_LT(relative_difference(2 * yp, y), 1e-14);
}

TEST(MatrixFreeLinearisation3D, CriticalStrainAgreesWithTheDenseReference) {
  const int n = 6;
  const auto disc = discretise(cubic(n));
  const MatrixFreeLinearisation<3> lin(*disc, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  ASSERT_TRUE(lin.symmetric());
  const Linearisation assembled = assemble_by_products(lin);
  ASSERT_EQ(assembled.dofs_per_particle, 3);
  const Eigen::MatrixXd k = Eigen::MatrixXd(assembled.A0), l = -Eigen::MatrixXd(assembled.A1);
  EXPECT_LT((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-13 * k.cwiseAbs().maxCoeff());
  EXPECT_LT((l - l.transpose()).cwiseAbs().maxCoeff(), 1e-13 * l.cwiseAbs().maxCoeff());
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(0.5 * (l + l.transpose()),
                                                                      0.5 * (k + k.transpose()));
  ASSERT_EQ(ges.info(), Eigen::Success);
  const double lambda_max = ges.eigenvalues().maxCoeff();
  ASSERT_GT(lambda_max, 0);

  MatrixFreeCriticalLoadOptions o{.method = MatrixFreeEigenMethod::BlockLobpcg,
                                  .residual_tol = 1e-9,
                                  .max_iterations = 20000,
                                  .preconditioner = MatrixFreePreconditioner::None};
  const MatrixFreeCriticalLoad plain = matrix_free_critical_load(lin, LoadDirection::Tension, o);
  ASSERT_EQ(plain.status, Status::Successful) << plain.reason;
  EXPECT_NEAR(plain.load, 1 / lambda_max, 1e-10 / lambda_max);

  // The sine preconditioner with the stencil of a larger lattice (n = 11 is the smallest that can be probed).
  const auto big = discretise(cubic(11));
  const MatrixFreeLinearisation<3> big_lin(*big, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const LatticeStencil<3> st = probe_lattice_stencil(big_lin, LoadDirection::Tension);
  EXPECT_EQ(st.radius, 4);  // A0 couples neighbours of neighbours: two lattice hops shorter than 2.6 dx reach 4 dx
  EXPECT_LT(lattice_stencil_deviation(big_lin, LoadDirection::Tension, st, {5 + 11 * 5 + 121 * 5}), 1e-14);
  const LatticeSinePreconditioner<3> t(st, n);
  const MatrixFreeCriticalLoad pre = matrix_free_critical_load(lin, LoadDirection::Tension, o, t);
  ASSERT_EQ(pre.status, Status::Successful) << pre.reason;
  EXPECT_NEAR(pre.load, 1 / lambda_max, 1e-10 / lambda_max);
  EXPECT_LT(pre.iterations, plain.iterations);

  // The engine's direct route (critical_load: definiteness, eigen route) on the assembled 3D linearisation.
  CriticalLoadOptions direct = CriticalLoadOptions::strain_2d();
  direct.method = CriticalLoadMethod::Eigen;
  const CriticalLoad d = critical_load(assembled, LoadDirection::Tension, direct);
  ASSERT_EQ(d.status, Status::Successful) << d.reason;
  EXPECT_NEAR(d.load, 1 / lambda_max, 1e-10 / lambda_max);
}

}  // namespace
}  // namespace sphstab
