// MCM's bulk viscosity in the rate-form scheme (RateFormOptions::bulk_viscosity_quadratic / _linear): its defining
// properties, checked against an independent evaluation in the test:
//   - it is a pressure q_i = rho_i h (Q1 h d_i^2 - Q2 c0 d_i) on the velocity divergence d_i where d_i < 0, 0 where
//     the particle expands: the change of the accelerations it makes is exactly the SPH pressure force of that q
//     (d_i read back from the divergence-form continuity, rho_i' = -rho_i d_i);
//   - it only dissipates: its power sum_i m_i v_i . da_i is <= 0;
//   - it leaves the density and stress rates alone, and the linearisation at rest (the switch is off at d = 0);
//   - the row and pair loops agree to rounding; bad coefficients are refused.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "forms_fixture.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace sphstab {
namespace rate_form_bulk_viscosity_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_bulk_shear(1.0, 0.3, 1.0);
constexpr double kQ1 = 1.5, kQ2 = 0.06;  // the MCM deck's QBVC, LBVC

/// A moving state on a perturbed periodic lattice: velocities of both signs of divergence.
Eigen::VectorXd moving_state(const RateFormScheme<2>& s) {
  Eigen::VectorXd y = s.uniform_state();
  const auto& p = s.discretisation().particles;
  const Eigen::VectorXd noise = test::random_vector(2 * p.size(), 0.02, 11);
  for (int i = 0; i < p.size(); ++i) {
    const double x = p.x(i, 0), yy = p.x(i, 1), L = p.box_length()[0];
    const Eigen::Vector2d v(0.1 * std::sin(2 * M_PI * x / L) + noise[2 * i], 0.05 * std::cos(2 * M_PI * yy / L) +
                                                                                noise[2 * i + 1]);
    s.set_velocity(y, i, v);
  }
  return y;
}

TEST(RateFormBulkViscosity, IsThePressureForceOfQOnTheVelocityDivergence) {
  const auto disc = test::lattice_discretisation<2>({.n = 8, .h = 1.3, .periodic = true, .perturbation = 0.1});
  const double density = 1.0 / 1.02;
  for (PairLoop loop : {PairLoop::Rows, PairLoop::Pairs}) {
    const RateFormOptions off{.continuity = ContinuityForm::Divergence, .pair_loop = loop};
    RateFormOptions on = off;
    on.bulk_viscosity_quadratic = kQ1;
    on.bulk_viscosity_linear = kQ2;
    const RateFormScheme<2> s0(disc, kMaterial, off, density), s1(disc, kMaterial, on, density);
    const Eigen::VectorXd y = moving_state(s0);
    Eigen::VectorXd f0, f1;
    s0.rate(y, f0);
    s1.rate(y, f1);
    const auto& p = disc->particles;
    const int n = p.size();
    const double h = disc->h, c0 = kMaterial.sound_speed();
    // q from the divergence the scheme itself uses (rho' = -rho d), at the positions of y.
    std::vector<double> q(n), rho(n);
    int compressed = 0;
    for (int i = 0; i < n; ++i) {
      rho[i] = y[s0.density_offset(i)];
      const double d = -f0[s0.density_offset(i)] / rho[i];
      q[i] = d < 0 ? rho[i] * h * (kQ1 * h * d * d - kQ2 * c0 * d) : 0.0;
      compressed += d < 0;
    }
    ASSERT_GT(compressed, n / 4);
    ASSERT_LT(compressed, 3 * n / 4);
    double power = 0, scale = 0, err = 0;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d xi = y.segment<2>(s0.position_offset(i));
      Eigen::Vector2d da = Eigen::Vector2d::Zero();
      for (int j = 0; j < n; ++j) {
        if (j == i) continue;
        Eigen::Vector2d r = xi - y.segment<2>(s0.position_offset(j));
        for (int a = 0; a < 2; ++a) r[a] -= p.box_length()[a] * std::round(r[a] / p.box_length()[a]);
        const double rr = r.norm();
        if (rr >= disc->kernel.support_radius(h)) continue;
        da -= s0.mass()[j] * (q[i] / (rho[i] * rho[i]) + q[j] / (rho[j] * rho[j])) * disc->kernel.d1(rr, h) / rr * r;
      }
      const Eigen::Vector2d got = (f1 - f0).segment<2>(s0.velocity_offset(i));
      err = std::max(err, (got - da).cwiseAbs().maxCoeff());
      scale = std::max(scale, da.cwiseAbs().maxCoeff());
      power += s0.mass()[i] * y.segment<2>(s0.velocity_offset(i)).dot(got);
      // Nothing but the accelerations changes.
      EXPECT_EQ(f1[s0.density_offset(i)], f0[s0.density_offset(i)]);
      EXPECT_EQ(f1.segment<3>(s0.stress_offset(i)), f0.segment<3>(s0.stress_offset(i)));
      EXPECT_EQ(f1.segment<2>(s0.position_offset(i)), f0.segment<2>(s0.position_offset(i)));
    }
    ASSERT_GT(scale, 1e-4);
    EXPECT_LT(err, 1e-12 * scale) << "loop " << static_cast<int>(loop);
    EXPECT_LT(power, 0.0);
    std::printf("loop %d: %d of %d particles compressed, max |da| %.3e, error %.2e, power %.3e\n",
                static_cast<int>(loop), compressed, n, scale, err, power);
  }
}

TEST(RateFormBulkViscosity, CorrectedGradientsDissipateAndTheRestStateIsUnchanged) {
  const auto disc = test::lattice_discretisation<2>({.n = 6, .h = 1.3, .perturbation = 0.05});
  for (const RateFormOptions& base :
       {RateFormOptions{}, RateFormOptions{.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph},
        RateFormOptions{.momentum = RateFormMomentum::Cij}}) {
    RateFormOptions on = base;
    on.bulk_viscosity_quadratic = kQ1;
    on.bulk_viscosity_linear = kQ2;
    const RateFormScheme<2> s0(disc, kMaterial, base, 1.0 / 1.02), s1(disc, kMaterial, on, 1.0 / 1.02);
    // At rest: q = 0, the same rates and the same Jacobian (complex step sees the switch off at d = 0).
    const Eigen::VectorXd rest = s0.uniform_state();
    Eigen::VectorXd f0, f1;
    s0.rate(rest, f0);
    s1.rate(rest, f1);
    EXPECT_EQ(f0, f1) << s1.name();
    ComplexStepJacobian j0(s0), j1(s1);
    EXPECT_EQ(Eigen::MatrixXd(j0.compute(rest)), Eigen::MatrixXd(j1.compute(rest))) << s1.name();
    // Moving: only dissipation. The free particles carry the motion; fixed layers stay at rest.
    Eigen::VectorXd y = rest;
    const Eigen::VectorXd noise = test::random_vector(2 * disc->size(), 0.05, 5);
    for (int i = 0; i < disc->size(); ++i)
      if (s0.velocity_offset(i) >= 0) s0.set_velocity(y, i, noise.segment<2>(2 * i));
    s0.rate(y, f0);
    s1.rate(y, f1);
    double power = 0;
    for (int i = 0; i < disc->size(); ++i)
      if (s0.velocity_offset(i) >= 0)
        power += s0.mass()[i] * y.segment<2>(s0.velocity_offset(i)).dot((f1 - f0).segment<2>(s0.velocity_offset(i)));
    EXPECT_LT(power, 0.0) << s1.name();
    EXPECT_GT((f1 - f0).cwiseAbs().maxCoeff(), 0.0) << s1.name();
  }
}

TEST(RateFormBulkViscosity, BadCoefficientsAreRefusedAndNamed) {
  const auto disc = test::lattice_discretisation<2>({.n = 4, .h = 1.3});
  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(RateFormScheme<2>(disc, kMaterial, {.bulk_viscosity_quadratic = bad}), std::invalid_argument);
    EXPECT_THROW(RateFormScheme<2>(disc, kMaterial, {.bulk_viscosity_linear = bad}), std::invalid_argument);
  }
  const RateFormScheme<2> s(disc, kMaterial, {.bulk_viscosity_quadratic = 1.5, .bulk_viscosity_linear = 0.06});
  EXPECT_NE(s.name().find("bulk viscosity 1.5/0.06"), std::string::npos) << s.name();
}

}  // namespace
}  // namespace sphstab
