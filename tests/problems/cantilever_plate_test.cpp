#include "sphstab/problems/cantilever_plate.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace sphstab {
namespace cantilever_plate_test {

TEST(CantileverPlate, FundamentalRootAndTheNotesRecomputedPeriods) {
  const double kl = cantilever_fundamental_kl();
  EXPECT_NEAR(std::cos(kl) * std::cosh(kl), -1.0, 1e-14);
  EXPECT_NEAR(kl, 1.8751040687119611, 1e-13);
  // [GMS2001, (7.1)], K = rho = 1, kL = 1.8751: H = 2: 1448.8 / 1275.0 / 978.8, H = 1: 2897.5 / 2550.1 / 1957.6.
  const double mus[3] = {0.22, 0.30, 0.60}, h2[3] = {1448.8, 1275.0, 978.8}, h1[3] = {2897.5, 2550.1, 1957.6};
  for (int i = 0; i < 3; ++i) {
    const IsotropicModuli m = isotropic_moduli(1.0, mus[i]);
    EXPECT_NEAR(thin_plate_period(m.youngs, m.poisson, 1.0, 2.0, 20.0), h2[i], 0.06) << mus[i];
    EXPECT_NEAR(thin_plate_period(m.youngs, m.poisson, 1.0, 1.0, 20.0), h1[i], 0.06) << mus[i];
  }
  // The recomputed Poisson ratios 0.398 / 0.364 / 0.25 and E from K and mu: 3K = E/(1 - 2 nu), 2mu = E/(1 + nu).
  const IsotropicModuli m = isotropic_moduli(1.0, 0.22);
  EXPECT_NEAR(m.poisson, 0.398, 5e-4);
  EXPECT_NEAR(m.youngs / (1 - 2 * m.poisson), 3.0, 1e-13);
  EXPECT_NEAR(m.youngs / (1 + m.poisson), 0.44, 1e-13);
  // Period scales as L^2 / H.
  EXPECT_NEAR(thin_plate_period(1.0, 0.3, 1.0, 1.0, 40.0) / thin_plate_period(1.0, 0.3, 1.0, 2.0, 20.0), 8.0, 1e-12);
}

/// Fundamental angular frequency of a clamped-free Timoshenko beam by finite elements (an independent method): linear
/// w and phi, one-point (reduced) shear integration, consistent mass, dense generalised eigenproblem.
double timoshenko_fe_omega(double D, double kG, double rho, double H, double L, int elements) {
  const double A = H, I = H * H * H / 12, le = L / elements;
  const int n = 2 * elements;  // (w, phi) of nodes 1..elements; node 0 clamped
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  for (int e = 0; e < elements; ++e) {
    const int dof[4] = {2 * e - 2, 2 * e - 1, 2 * e, 2 * e + 1};  // w1, phi1, w2, phi2 (negative: clamped)
    Eigen::Matrix4d ke = Eigen::Matrix4d::Zero(), me = Eigen::Matrix4d::Zero();
    const Eigen::Vector4d bs(-1 / le, -0.5, 1 / le, -0.5);  // w' - phi at the element centre
    ke += kG * A * le * bs * bs.transpose();
    const double kb = D * I / le;
    ke(1, 1) += kb, ke(3, 3) += kb, ke(1, 3) -= kb, ke(3, 1) -= kb;
    for (int a = 0; a < 2; ++a)  // w (a = 0) and phi (a = 1) consistent masses
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) me(2 * i + a, 2 * j + a) = rho * (a == 0 ? A : I) * le / 6 * (i == j ? 2 : 1);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (dof[i] >= 0 && dof[j] >= 0) K(dof[i], dof[j]) += ke(i, j), M(dof[i], dof[j]) += me(i, j);
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  return std::sqrt(es.eigenvalues()(0));
}

TEST(CantileverPlate, TimoshenkoPeriodAgreesWithFiniteElementsAndTendsToThinPlate) {
  // The GMS plate, mu = 0.22: plane-strain bending modulus E / (1 - nu^2), G = mu, kappa = 5/6, H / L = 0.1.
  const IsotropicModuli m = isotropic_moduli(1.0, 0.22);
  const double D = m.youngs / (1 - m.poisson * m.poisson), kG = 5.0 / 6 * 0.22;
  for (double H : {2.0, 1.0}) {
    const double T = timoshenko_cantilever_period(D, 0.22, 5.0 / 6, 1.0, H, 20.0);
    // Linear elements converge at order 2: Richardson from 200 and 400 elements.
    const double w1 = timoshenko_fe_omega(D, kG, 1.0, H, 20.0, 200), w2 = timoshenko_fe_omega(D, kG, 1.0, H, 20.0, 400);
    const double w_fe = (4 * w2 - w1) / 3;
    EXPECT_NEAR(2 * M_PI / w_fe / T, 1.0, 1e-7) << H;
    EXPECT_GT(T, thin_plate_period(m.youngs, m.poisson, 1.0, H, 20.0)) << H;  // shear and rotary inertia soften
  }
  // Thin limit: T_timoshenko / T_thin - 1 = c (H/L)^2 + O((H/L)^4).
  auto excess = [&](double H) {
    return timoshenko_cantilever_period(D, 0.22, 5.0 / 6, 1.0, H, 1.0) /
               thin_plate_period(m.youngs, m.poisson, 1.0, H, 1.0) -
           1;
  };
  EXPECT_NEAR(excess(0.01) / excess(0.005), 4.0, 1e-3);
  EXPECT_LT(excess(0.001), 1e-4);
  EXPECT_THROW(timoshenko_cantilever_period(D, 0.22, 5.0 / 6, 1.0, 0.0, 20.0), std::invalid_argument);
  EXPECT_THROW(timoshenko_cantilever_period(D, -1.0, 5.0 / 6, 1.0, 2.0, 20.0), std::invalid_argument);
  EXPECT_THROW(timoshenko_cantilever_period(D, 0.22, 5.0 / 6, 1.0, 30.0, 20.0), std::invalid_argument);
}

TEST(CantileverPlate, InitialVelocityIsTheClampedFreeModeShape) {
  // v(0) = v'(0) = 0 (clamped), v''(L) = v'''(L) = 0 (free), v(L) = V_f; derivatives by central differences.
  const double L = 20, Vf = 0.05, d = 1e-2;
  auto v = [&](double x) { return cantilever_mode_velocity(x, L, Vf); };
  EXPECT_NEAR(v(0), 0.0, 1e-15);
  EXPECT_NEAR(v(L), Vf, 1e-12);
  const double k = cantilever_fundamental_kl() / L;
  EXPECT_LT(std::abs((v(d) - v(-d)) / (2 * d)), 1e-6 * Vf * k);  // O(d^2) of v''' = O(Vf k^3)
  const double v2 = (v(L + d) - 2 * v(L) + v(L - d)) / (d * d);
  const double v3 = (v(L + 2 * d) - 2 * v(L + d) + 2 * v(L - d) - v(L - 2 * d)) / (2 * d * d * d);
  EXPECT_LT(std::abs(v2), 1e-5 * Vf * k * k);
  EXPECT_LT(std::abs(v3), 1e-4 * Vf * k * k * k);
  // The mode solves v'''' = k^4 v in the interior.
  const double x = 7.3, h = 0.05;
  const double v4 = (v(x + 2 * h) - 4 * v(x + h) + 6 * v(x) - 4 * v(x - h) + v(x - 2 * h)) / std::pow(h, 4);
  EXPECT_NEAR(v4 / (std::pow(k, 4) * v(x)), 1.0, 1e-4);
}

TEST(CantileverPlate, GeometryAndBadInput) {
  const ParticleSet<2> s = make_cantilever_plate({.length = 20, .thickness = 2, .across = 10, .clamp_layers = 3});
  EXPECT_EQ(s.size(), (100 + 3) * 10);
  EXPECT_EQ(s.count(Role::Fixed), 30);
  EXPECT_DOUBLE_EQ(s.spacing, 0.2);
  for (int i = 0; i < s.size(); ++i) {
    EXPECT_EQ(s.role[i] == Role::Fixed, s.x(i, 0) < 0) << i;
    EXPECT_LT(std::abs(s.x(i, 1)), 1.0);
  }
  EXPECT_NEAR(s.x.col(0).maxCoeff(), 20 - 0.1, 1e-12);
  EXPECT_NEAR(s.x.col(0).minCoeff(), -0.6 + 0.1, 1e-12);
  EXPECT_NEAR(s.volume.sum(), 103 * 10 * 0.04, 1e-10);
  EXPECT_EQ(*std::max_element(s.depth.begin(), s.depth.end()), 4);
  EXPECT_THROW(make_cantilever_plate({.length = 20.1, .thickness = 2, .across = 10}), std::invalid_argument);
  EXPECT_THROW(make_cantilever_plate({.length = -1}), std::invalid_argument);
  EXPECT_THROW(make_cantilever_plate({.clamp_layers = 0}), std::invalid_argument);
  EXPECT_THROW(isotropic_moduli(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(thin_plate_period(1.0, 0.5, 1.0, 1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
