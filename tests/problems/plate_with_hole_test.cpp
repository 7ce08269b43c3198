#include "sphstab/problems/plate_with_hole.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"

namespace sphstab {
namespace plate_with_hole_test {

TEST(PlateWithHole, GeometryImagesAndEdge) {
  // 8 x 8 sites at (i + 1/2) / 4: r < 0.5 removes (0.125, 0.125), (0.375, 0.125), (0.125, 0.375) (r = 0.177, 0.395,
  // 0.395), keeps (0.375, 0.375) (r = 0.530).
  const PlateWithHole p = make_plate_with_hole({.radius = 0.5, .width = 2, .spacing = 0.25, .ghost_depth = 0.6});
  EXPECT_EQ(p.removed, 3);
  EXPECT_EQ(p.real_count, 61);
  ASSERT_EQ(p.edge.size(), 8u);
  EXPECT_NEAR(p.edge_length.sum(), 2.0, 1e-14);
  for (int e : p.edge) EXPECT_DOUBLE_EQ(p.particles.x(e, 0), 1.875);
  // images: within 0.6 of a plane (columns x = 0.125, 0.375) mirrored; none inside the hole
  int across_x = 0, across_both = 0;
  for (std::size_t g = 0; g < p.image_of.size(); ++g) {
    const int i = p.real_count + static_cast<int>(g), k = p.image_of[g];
    EXPECT_GE(p.particles.x.row(i).norm(), 0.5);
    EXPECT_DOUBLE_EQ(p.particles.x(i, 0), p.sign[g][0] * p.particles.x(k, 0));
    EXPECT_DOUBLE_EQ(p.particles.x(i, 1), p.sign[g][1] * p.particles.x(k, 1));
    across_x += p.sign[g][0] < 0 && p.sign[g][1] > 0;
    across_both += p.sign[g][0] < 0 && p.sign[g][1] < 0;
  }
  EXPECT_EQ(across_x, 2 * 8 - 3);  // two columns of 8, less the 3 hole sites
  EXPECT_EQ(across_both, 1);       // (0.375, 0.375) only
  EXPECT_EQ(static_cast<int>(p.image_of.size()), 2 * 13 + 1);
  // the mirror map: identity on the real particles, signed copies on the images
  const SparseMatrix<> T = mirror_map(p);
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(2 * p.real_count, 1, 2 * p.real_count);
  const Eigen::VectorXd ua = T * u;
  EXPECT_EQ((ua.head(2 * p.real_count) - u).norm(), 0.0);
  for (std::size_t g = 0; g < p.image_of.size(); ++g)
    for (int d = 0; d < 2; ++d)
      EXPECT_EQ(ua[2 * (p.real_count + static_cast<int>(g)) + d], p.sign[g][d] * u[2 * p.image_of[g] + d]);
  const Eigen::VectorXd f = lumped_traction(p, 3.0);
  EXPECT_NEAR(f.sum(), 3.0 * 2, 1e-14);
}

TEST(PlateWithHole, RejectsBadInput) {
  EXPECT_THROW(make_plate_with_hole({.radius = 0, .width = 2, .spacing = 0.25}), std::invalid_argument);
  EXPECT_THROW(make_plate_with_hole({.radius = -1, .width = 2, .spacing = 0.25}), std::invalid_argument);
  EXPECT_THROW(make_plate_with_hole({.radius = 2, .width = 2, .spacing = 0.25}), std::invalid_argument);
  EXPECT_THROW(make_plate_with_hole({.radius = 1, .width = 2, .spacing = 0}), std::invalid_argument);
  EXPECT_THROW(make_plate_with_hole({.radius = 1, .width = 2, .spacing = -0.25}), std::invalid_argument);
  EXPECT_THROW(make_plate_with_hole({.radius = 1, .width = 2, .spacing = 0.3}), std::invalid_argument);
  EXPECT_THROW(make_plate_with_hole({.radius = 1, .width = 2, .spacing = 0.25, .ghost_depth = -1}),
               std::invalid_argument);
  EXPECT_THROW(kirsch_polar_stress(1, 0.5, 0, 1), std::invalid_argument);
  EXPECT_THROW(heywood_gross_concentration(1, 1), std::invalid_argument);
}

TEST(PlateWithHole, KirschAndHeywood) {
  const double pi = std::numbers::pi;
  EXPECT_NEAR(kirsch_polar_stress(1, 1, pi / 2, 2.0)[1], 6.0, 1e-14);  // 3 S at the hole, theta = 90 deg
  EXPECT_NEAR(kirsch_polar_stress(1, 1, 0, 2.0)[1], -2.0, 1e-14);      // -S on the load axis
  for (double th : {0.1, 0.7, 1.3}) {                                  // traction-free hole
    EXPECT_NEAR(kirsch_polar_stress(1, 1, th, 2.0)[0], 0.0, 1e-14);
    EXPECT_NEAR(kirsch_polar_stress(1, 1, th, 2.0)[2], 0.0, 1e-14);
  }
  const Eigen::Vector3d far = kirsch_polar_stress(1, 1e5, 0, 2.0);  // remote sigma_xx = S
  EXPECT_NEAR(far[0], 2.0, 1e-9);
  EXPECT_NEAR(far[1], 0.0, 1e-9);
  EXPECT_NEAR(heywood_gross_concentration(1e-6, 1), 3.0, 1e-5);
  EXPECT_NEAR(heywood_gross_concentration(1, 5), (2 + 0.512) / 0.8, 1e-14);
}

/// Newton on the real unknowns: a(T u) + f / m = 0 (A = -da/du, reduced by the chain rule S A T).
Eigen::VectorXd solve_static(const FiniteStrainTotalLagrangian<2>& tl, const SparseMatrix<>& T,
                             const Eigen::VectorXd& f, int steps, double& residual) {
  const int nr = static_cast<int>(T.cols());
  const Eigen::VectorXd m = tl.dof_mass().head(nr);
  const ComplexStepJacobian csj(tl);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(nr), a;
  for (int s = 1; s <= steps; ++s) {
    const Eigen::VectorXd load = (double(s) / steps) * f.cwiseQuotient(m);
    for (int it = 0; it < 10; ++it) {
      tl.acceleration(T * u, a);
      const Eigen::VectorXd r = a.head(nr) + load;
      residual = r.lpNorm<Eigen::Infinity>() / load.lpNorm<Eigen::Infinity>();
      if (residual < 1e-12) break;
      const SparseMatrix<> A = csj.compute(T * u);
      const Eigen::SparseMatrix<double> Ar = SparseMatrix<>(A.topRows(nr)) * T;
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(Ar);
      EXPECT_EQ(lu.info(), Eigen::Success);
      u += lu.solve(r);
    }
  }
  return u;
}

// A plate without hole (a = dx/2 removes no site): the consistent edge load makes the uniaxial stress state an exact
// equilibrium of the NCSPH-strain / Plus-divergence form with mirror planes, so Newton must return P = S e_x (x) e_x at
// EVERY real particle (free edge y = W, corners and mirror planes included) and the affine displacement field.
TEST(PlateWithHole, UniaxialPlateWithoutHoleIsExactlyHomogeneous) {
  const double dx = 1, W = 10, h = 1.3 * dx;
  const Kernel<2> kernel(KernelType::CubicSpline);
  const PlateWithHole p = make_plate_with_hole(
      {.radius = 0.5 * dx, .width = W, .spacing = dx, .ghost_depth = 2 * kernel.support_radius(h) + 0.5 * dx});
  ASSERT_EQ(p.removed, 0);
  ASSERT_EQ(p.real_count, 100);
  const auto disc = make_discretisation(p.particles, kernel, h);
  const SparseMatrix<> T = mirror_map(p);
  const double E = 1, nu = 0.3;
  const auto lame = ElasticMaterial::from_young_poisson(E, nu, 1.0);
  const FiniteStrainOptions<2> opt{.gradient = make_gradient_provider<2>(Correction::Ncsph)};
  // the consistent load's total is S W up to the lattice quadrature of the kernel's edge jump
  const double S = 1e-3;
  const Eigen::VectorXd f = consistent_traction(p, *disc, S);
  // measured in the study: about 1.0105 S per unit length less a corner deficit of 0.25 S dx, so 0.986 at W = 10 dx
  EXPECT_NEAR(f.sum() / (S * W), 0.986, 0.002);
  {  // the load needs the plate's own discretisation, and a hole whose boundary band stays clear of the loaded band
    const PlateWithHole q = make_plate_with_hole({.radius = 6, .width = W, .spacing = dx, .ghost_depth = 6});
    EXPECT_THROW(consistent_traction(q, *disc, S), std::invalid_argument);
    EXPECT_THROW(consistent_traction(q, *make_discretisation(q.particles, kernel, h), S), std::invalid_argument);
  }
  {
    FiniteStrainTotalLagrangian<2> tl(disc, std::make_shared<Hooke<2>>(lame), 1.0, opt);
    double res = 1;
    const Eigen::VectorXd u = solve_static(tl, T, f, 1, res);
    EXPECT_LT(res, 1e-12);
    const Eigen::MatrixXd P = tl.stresses(T * u);
    const double ex = (1 - nu * nu) * S / E, ey = -nu * (1 + nu) * S / E;  // plane strain, sigma_yy = 0
    for (int i = 0; i < p.real_count; ++i) {
      EXPECT_NEAR(P(i, 0) / S, 1.0, 1e-9) << i;
      EXPECT_NEAR(P(i, 1) / S, 0.0, 1e-9) << i;
      EXPECT_NEAR(P(i, 2) / S, 0.0, 1e-9) << i;
      EXPECT_NEAR(P(i, 3) / S, 0.0, 1e-9) << i;
      EXPECT_NEAR(u[2 * i], ex * p.particles.x(i, 0), 1e-9 * ex * W) << i;
      EXPECT_NEAR(u[2 * i + 1], ey * p.particles.x(i, 1), 1e-9 * ex * W) << i;
    }
  }
  {  // finite strain: Neo-Hookean at S = 0.1 E (about 9 % stretch), nominal (dead) traction in 4 load steps
    FiniteStrainTotalLagrangian<2> tl(disc, std::make_shared<NeoHookean<2>>(lame), 1.0, opt);
    const double Sn = 0.1 * E;
    double res = 1;
    const Eigen::VectorXd u = solve_static(tl, T, consistent_traction(p, *disc, Sn), 4, res);
    EXPECT_LT(res, 1e-12);
    const Eigen::MatrixXd P = tl.stresses(T * u), F = tl.deformation_gradients(T * u);
    EXPECT_GT(F(0, 0), 1.05);
    for (int i = 0; i < p.real_count; ++i) {
      EXPECT_NEAR(P(i, 0) / Sn, 1.0, 1e-9) << i;
      EXPECT_NEAR(P(i, 3) / Sn, 0.0, 1e-9) << i;
      EXPECT_NEAR(F(i, 0), F(0, 0), 1e-9) << i;
      EXPECT_NEAR(F(i, 3), F(0, 3), 1e-9) << i;
    }
  }
}

}  // namespace
}  // namespace sphstab
