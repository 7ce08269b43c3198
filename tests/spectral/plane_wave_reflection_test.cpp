// Plane-wave reflection at absorbing boundaries (spectral/plane_wave_reflection.hpp) against
// [Powell2012, (2.49)] solved exactly for this project (plane strain nu = 0.3, printed to 4 decimals), the scalar
// Engquist-Majda R = tan^2(theta/2), normal incidence (every first-order condition is exact there), and the Rayleigh
// speed against the closed form at nu = 1/4 and 0.92741 at nu = 0.3 (the root of [Powell2012, (A.35)]).
#include "sphstab/spectral/plane_wave_reflection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace sphstab {
namespace plane_wave_reflection_test {

const double kCp = std::sqrt(1.4 / 0.4), kCs = 1.0;  // plane strain nu = 0.3: c_p / c_s = sqrt(2 (1 - nu) / (1 - 2 nu))

double deg(double d) { return d * M_PI / 180; }

struct Row {
  double theta, pp, ps, sp, ss;
};

void expect_table(AbsorbingCondition b, const std::vector<Row>& rows) {
  for (const Row& r : rows) {
    const Reflection p = elastic_reflection(b, kCp, kCs, deg(r.theta), WaveKind::P);
    const Reflection s = elastic_reflection(b, kCp, kCs, deg(r.theta), WaveKind::S);
    // The table has 4 decimals: agreement to half a unit of the last one.
    EXPECT_NEAR(std::abs(p.to_p), r.pp, 5e-5) << r.theta;
    EXPECT_NEAR(std::abs(p.to_s), r.ps, 5e-5) << r.theta;
    EXPECT_NEAR(std::abs(s.to_p), r.sp, 5e-5) << r.theta;
    EXPECT_NEAR(std::abs(s.to_s), r.ss, 5e-5) << r.theta;
  }
}

TEST(PlaneWaveReflection, ClaytonEngquistMatchesTheExactTable) {
  expect_table(AbsorbingCondition::ClaytonEngquist, {{5, .0005, .0204, .0376, .0066},
                                                     {10, .0020, .0417, .0726, .0258},
                                                     {30, .0051, .1439, .1565, .1795},
                                                     {45, .0269, .2320, .0268, .1457}});
}

TEST(PlaneWaveReflection, SochakiMatchesTheExactTable) {
  expect_table(AbsorbingCondition::Sochaki, {{5, .0001, .0002, .0006, .0051},
                                             {10, .0003, .0014, .0050, .0197},
                                             {30, .0098, .0316, .1674, .0871},
                                             {45, .0592, .0818, .3556, .1501}});
}

TEST(PlaneWaveReflection, NormalIncidenceIsAbsorbedAndTheCriticalAngleIsFlagged) {
  for (AbsorbingCondition b :
       {AbsorbingCondition::ClaytonEngquist, AbsorbingCondition::Sochaki, AbsorbingCondition::Higdon})
    for (WaveKind w : {WaveKind::P, WaveKind::S}) {
      const Reflection r = elastic_reflection(b, kCp, kCs, 0.0, w);
      EXPECT_LT(std::abs(r.to_p) + std::abs(r.to_s), 1e-15);
    }
  const double critical = std::asin(kCs / kCp);  // 32.31 degrees at nu = 0.3
  EXPECT_NEAR(critical * 180 / M_PI, 32.31, 0.005);
  EXPECT_FALSE(elastic_reflection(AbsorbingCondition::Sochaki, kCp, kCs, critical - 1e-6, WaveKind::S).p_evanescent);
  EXPECT_TRUE(elastic_reflection(AbsorbingCondition::Sochaki, kCp, kCs, critical + 1e-6, WaveKind::S).p_evanescent);
  EXPECT_FALSE(elastic_reflection(AbsorbingCondition::Sochaki, kCp, kCs, deg(80), WaveKind::P).p_evanescent);
}

TEST(PlaneWaveReflection, ViscousTractionSatisfiesTheStressCondition) {
  // Independent of the displacement-form rewriting in apply(): superpose the incident and reflected waves with the
  // solved amplitudes, form the stress at x = 0 from Hooke's law (rho = 1, mu = c_s^2, lambda = c_p^2 - 2 c_s^2)
  // and check Powell (2.75), sigma_xx = -c_p v_x and sigma_xy = -c_s v_y, to round-off; and the dashpot reflects
  // nothing at normal incidence but does at 30 degrees (Lysmer-Kuhlemeyer).
  using cd = std::complex<double>;
  const cd I(0, 1);
  const double mu = kCs * kCs, lambda = kCp * kCp - 2 * mu;
  for (WaveKind w : {WaveKind::P, WaveKind::S})
    for (double theta_deg : {0.0, 10.0, 30.0, 45.0, 70.0}) {
      const double th = deg(theta_deg), a = std::cos(th), b = std::sin(th);
      const Reflection r = elastic_reflection(AbsorbingCondition::ViscousTraction, kCp, kCs, th, w);
      // Each wave: amplitude A, direction k (complex for evanescent), speed c, polarisation d; u = A d exp(i(k.x/c -
      // t)).
      struct Wave {
        cd amp;
        Eigen::Vector2cd k;
        double c;
        Eigen::Vector2cd d;
      };
      std::vector<Wave> waves;
      const auto p_wave = [&](cd A, Eigen::Vector2cd k) { waves.push_back({A, k, kCp, k}); };
      const auto s_wave = [&](cd A, Eigen::Vector2cd k) { waves.push_back({A, k, kCs, {-k[1], k[0]}}); };
      if (w == WaveKind::P) {
        p_wave(1.0, {a, b});
        p_wave(r.to_p, {-a, b});
        const double eta = kCs / kCp * b;
        s_wave(r.to_s, {-std::sqrt(1 - eta * eta), eta});
      } else {
        s_wave(1.0, {a, b});
        s_wave(r.to_s, {-a, b});
        const double xi = kCp / kCs * b;
        p_wave(r.to_p, {xi > 1 ? cd(0, -std::sqrt(xi * xi - 1)) : cd(-std::sqrt(1 - xi * xi)), xi});
      }
      Eigen::Matrix2cd grad = Eigen::Matrix2cd::Zero();  // du_a / dx_b at x = 0, t = 0
      Eigen::Vector2cd v = Eigen::Vector2cd::Zero();
      for (const Wave& q : waves) {
        grad += q.amp * (I / q.c) * q.d * q.k.transpose();
        v += q.amp * (-I) * q.d;
      }
      const cd sxx = (lambda + 2 * mu) * grad(0, 0) + lambda * grad(1, 1), sxy = mu * (grad(0, 1) + grad(1, 0));
      EXPECT_LT(std::abs(sxx + kCp * v[0]) + std::abs(sxy + kCs * v[1]), 1e-13) << theta_deg;
      // Energy: the flux the reflected waves carry back is the incident flux less the dashpot's dissipation,
      // <c_p v_x^2 + c_s v_y^2> = (c_p |v_x|^2 + c_s |v_y|^2) / 2 (rho = omega = 1; incident flux c_in cos(theta) / 2).
      const double c_in = w == WaveKind::P ? kCp : kCs;
      const double absorbed = (kCp * std::norm(v[0]) + kCs * std::norm(v[1])) / (c_in * a);
      EXPECT_NEAR(reflected_energy(AbsorbingCondition::ViscousTraction, kCp, kCs, th, w), 1 - absorbed, 1e-13)
          << theta_deg;
      if (theta_deg == 0) EXPECT_LT(std::abs(r.to_p) + std::abs(r.to_s), 1e-15);
      if (theta_deg == 30) EXPECT_GT(std::abs(r.to_p) + std::abs(r.to_s), 1e-2);
    }
}

TEST(PlaneWaveReflection, SpeedScaleScalesTheConditionOnly) {
  // Powell's H (scale cos theta) and Higdon's factor (1 / cos theta) on ClaytonEngquist: the superposed field satisfies
  // (d_t + s c_p d_x) u_x = 0 and (d_t + s c_s d_x) u_y = 0 at x = 0 to round-off; scale 1 is the default; a bad
  // scale is an error.
  using cd = std::complex<double>;
  const cd I(0, 1);
  for (double theta_deg : {15.0, 30.0, 50.0}) {
    const double th = deg(theta_deg), a = std::cos(th), b = std::sin(th);
    for (double scale : {a, 1 / a}) {
      const Reflection r = elastic_reflection(AbsorbingCondition::ClaytonEngquist, kCp, kCs, th, WaveKind::P, scale);
      const double eta = kCs / kCp * b, zeta = std::sqrt(1 - eta * eta);
      // u = sum A d exp(i (k.x / c - t)): d_t -> -i, d_x -> i k_x / c.
      const Eigen::Vector2cd ut =
          -I * (Eigen::Vector2cd(a, b) + r.to_p * Eigen::Vector2cd(-a, b) + r.to_s * Eigen::Vector2cd(-eta, -zeta));
      const Eigen::Vector2cd ux =
          I * (a / kCp * Eigen::Vector2cd(a, b) + r.to_p * (-a / kCp) * Eigen::Vector2cd(-a, b) +
               r.to_s * (-zeta / kCs) * Eigen::Vector2cd(-eta, -zeta));
      EXPECT_LT(std::abs(ut[0] + scale * kCp * ux[0]) + std::abs(ut[1] + scale * kCs * ux[1]), 1e-13) << theta_deg;
    }
    const Reflection one = elastic_reflection(AbsorbingCondition::Sochaki, kCp, kCs, th, WaveKind::S, 1.0);
    const Reflection def = elastic_reflection(AbsorbingCondition::Sochaki, kCp, kCs, th, WaveKind::S);
    EXPECT_EQ(one.to_p, def.to_p);
    EXPECT_EQ(one.to_s, def.to_s);
  }
  EXPECT_THROW(elastic_reflection(AbsorbingCondition::ClaytonEngquist, kCp, kCs, 0.1, WaveKind::P, 0.0),
               std::invalid_argument);
}

TEST(PlaneWaveReflection, ScalarEngquistMajdaAndHigdon) {
  // The values of tan^2(theta / 2) and the second-order tan^4 at 45 degrees.
  const double expected[] = {0.0077, 0.0718, 0.1716, 0.3333};
  const double angles[] = {10, 30, 45, 60};
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(scalar_reflection(deg(angles[k])), expected[k], 5e-5);
    EXPECT_NEAR(scalar_reflection(deg(angles[k])), std::pow(std::tan(deg(angles[k]) / 2), 2), 1e-15);
  }
  EXPECT_NEAR(scalar_reflection(deg(45), {0.0, 0.0}), 0.0294, 5e-5);
  // Higdon's factors absorb exactly at their own angles.
  EXPECT_LT(scalar_reflection(deg(30), {0.0, deg(30)}), 1e-15);
  EXPECT_THROW(scalar_reflection(M_PI / 2), std::invalid_argument);
  EXPECT_THROW(scalar_reflection(0.1, {-0.1}), std::invalid_argument);
}

TEST(PlaneWaveReflection, RayleighSpeed) {
  // nu = 1/4 (c_p^2 = 3 c_s^2): c_r^2 / c_s^2 = 2 - 2 / sqrt(3) exactly.
  EXPECT_NEAR(rayleigh_speed(std::sqrt(3.0), 1.0), std::sqrt(2 - 2 / std::sqrt(3.0)), 1e-14);
  EXPECT_NEAR(rayleigh_speed(kCp, kCs), 0.92741, 5e-6);
  // Steel of the impact test (rho 7.8, E 2.1 Mbar, nu 0.3): c_s = sqrt(E / (2 (1 + nu) rho)) = 0.32179 cm/us, so
  // (A.35) gives c_r = 0.29843 cm/us; the 0.2985 is the approximation (A.36), 0.92769 c_s (0.03 % higher).
  const double cs = std::sqrt(2.1 / (2 * 1.3 * 7.8));
  EXPECT_NEAR(rayleigh_speed(kCp * cs, cs), 0.29843, 5e-6);
  EXPECT_NEAR(0.92769 * cs, 0.2985, 5e-5);
  EXPECT_THROW(rayleigh_speed(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(rayleigh_speed(1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(elastic_reflection(AbsorbingCondition::Sochaki, 1.0, 2.0, 0.1, WaveKind::P), std::invalid_argument);
  EXPECT_THROW(elastic_reflection(AbsorbingCondition::Sochaki, 2.0, 1.0, 2.0, WaveKind::P), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
