// Absorbing particles of the rate-form scheme (RateFormScheme::set_absorbing, [Powell2012, (2.62), (2.67), (2.69)]):
// the condition's acceleration replaces the momentum equation on the declared particles and nothing else changes; the
// velocity gradient is exact for linear velocity fields with NCSPH (full and upwind neighbourhoods) and equals a sum
// written out by hand with the plain gradient; the complex-step rates are the derivative of the real ones; a 1D pulse
// leaves through three absorbing particles and is reflected by a free end without them.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include "forms_fixture.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/numerics/random_vector.hpp"

namespace sphstab {
namespace rate_form_absorbing_test {

const ElasticMaterial kSteel = ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8);  // Powell's g, cm, us
const Kernel<2> kCubic2(KernelType::CubicSpline);
const Kernel<1> kCubic1(KernelType::CubicSpline);
using Vec2 = Eigen::Vector2d;

/// A free nx x ny block at dx = 0.02 (particle (i, j) at ((i + 1/2) dx, (j + 1/2) dx), index j nx + i), h = 1.3 dx.
std::shared_ptr<const Discretisation<2>> block(int nx, int ny) {
  const double dx = 0.02;
  return make_discretisation(test::free_block(nx, ny, dx), kCubic2, 1.3 * dx);
}

/// Powell's 1D bar (2.68): n free particles at x_i = (i + 1/2) dx, h = 1.3 dx, uniaxial E (K = E, mu = 0).
std::shared_ptr<const Discretisation<1>> bar(int n, double dx = 0.01) {
  ParticleSet<1> p;
  p.x.resize(n, 1);
  p.volume = Eigen::VectorXd::Constant(n, dx);
  p.role.assign(n, Role::Free);
  p.spacing = dx;
  for (int i = 0; i < n; ++i) p.x(i, 0) = (i + 0.5) * dx;
  return make_discretisation(p, kCubic1, 1.3 * dx);
}
const ElasticMaterial kBar = ElasticMaterial::from_bulk_shear(2.1, 0, 7.8);

/// The right column of a block (outward normal +x) and its top row (normal +y), corner excluded from the row.
AbsorbingParticles<2> right_and_top(int nx, int ny, AbsorbingCondition condition, bool upwind) {
  AbsorbingParticles<2> b{.condition = condition, .upwind = upwind};
  for (int j = 0; j < ny; ++j) b.particles.push_back(j * nx + nx - 1), b.normals.emplace_back(1, 0);
  for (int i = 0; i + 1 < nx; ++i) b.particles.push_back((ny - 1) * nx + i), b.normals.emplace_back(0, 1);
  return b;
}

TEST(RateFormAbsorbing, LinearVelocityGivesTheConditionExactlyWithNcsph) {
  // v = v0 + A x on an undeformed block at rho0: the NCSPH gradient is exact for linear fields on any neighbourhood
  // with an invertible moment matrix, so every absorbing particle's acceleration is the condition's with L = A.
  const auto disc = block(7, 6);
  const Eigen::Matrix2d A{{0.013, -0.004}, {0.007, -0.011}};
  const Vec2 v0(0.002, -0.003);
  const double c_p = kSteel.p_wave_speed(), c_s = std::sqrt(kSteel.mu() / kSteel.density());
  // The same with a plain-gradient scheme whose absorbing particles normalise their own gradient (`normalised`).
  for (AbsorbingCondition condition : {AbsorbingCondition::ClaytonEngquist, AbsorbingCondition::Sochaki})
    for (bool upwind : {false, true})
      for (int variant = 0; variant < 3; ++variant) {
        const bool convective = variant == 1, plain = variant == 2;
        RateFormScheme<2> s(disc, kSteel, {.gradient = plain ? RateFormGradient::Plain : RateFormGradient::Ncsph});
        AbsorbingParticles<2> b = right_and_top(7, 6, condition, upwind);
        b.convective = convective;
        b.normalised = plain;
        s.set_absorbing(b);
        Eigen::VectorXd y = s.uniform_state(), f;
        for (int i = 0; i < disc->size(); ++i) s.set_velocity(y, i, v0 + A * disc->particles.x.row(i).transpose());
        s.rate(y, f);
        for (std::size_t q = 0; q < b.particles.size(); ++q) {
          const int i = b.particles[q];
          const Vec2 vi = v0 + A * disc->particles.x.row(i).transpose();
          const Vec2 want = absorbing_acceleration(condition, c_p, c_s, b.normals[q], A, vi, convective);
          EXPECT_LT((f.segment<2>(s.velocity_offset(i)) - want).norm(), 1e-12 * (1 + want.norm()))
              << "particle " << i << " upwind " << upwind;
        }
      }
}

TEST(RateFormAbsorbing, OnlyTheAbsorbingAccelerationsChange) {
  // Against the same scheme without absorbing particles, at a busy random state, real and complex: every rate but the
  // absorbing particles' dv/dt is bitwise equal.
  const auto disc = block(6, 5);
  const RateFormScheme<2> plain(disc, kSteel, {.xsph = 0.5, .viscosity = ViscositySwitch::Always});
  RateFormScheme<2> absorbing = plain;
  const AbsorbingParticles<2> b = right_and_top(6, 5, AbsorbingCondition::Sochaki, false);
  absorbing.set_absorbing(b);
  EXPECT_TRUE(absorbing.is_absorbing(5) && !absorbing.is_absorbing(4));
  EXPECT_NE(absorbing.name().find("10 absorbing"), std::string::npos) << absorbing.name();
  Eigen::VectorXd y = plain.uniform_state() + random_vector(plain.size(), 1e-3, 7), f, g;
  plain.rate(y, f);
  absorbing.rate(y, g);
  Eigen::VectorXcd yc = y.cast<std::complex<double>>(), fc, gc;
  plain.rate(yc, fc);
  absorbing.rate(yc, gc);
  std::vector<bool> replaced(y.size(), false);
  for (int i : b.particles) replaced[absorbing.velocity_offset(i)] = replaced[absorbing.velocity_offset(i) + 1] = true;
  int changed = 0;
  for (int k = 0; k < y.size(); ++k) {
    if (replaced[k]) {
      changed += f[k] != g[k];
      continue;
    }
    EXPECT_EQ(f[k], g[k]) << k;
    EXPECT_EQ(fc[k], gc[k]) << k;
  }
  EXPECT_EQ(changed, 20);
}

TEST(RateFormAbsorbing, PlainGradientIsTheHandWrittenSum1D) {
  // (2.69)-(2.70) with the plain gradient: a_i = -c n sum_j V_j (v_j - v_i) dW/dx_i, V_j = m_j / rho_j; the upwind
  // sum (2.67) keeps j <= i at the right end.
  const auto disc = bar(12);
  const double c = kBar.p_wave_speed(), h = disc->h;
  for (bool upwind : {false, true}) {
    RateFormScheme<1> s(disc, kBar);
    AbsorbingParticles<1> b{.upwind = upwind};
    for (int i = 8; i < 12; ++i) b.particles.push_back(i), b.normals.emplace_back(1.0);
    s.set_absorbing(b);
    Eigen::VectorXd y = s.uniform_state() + random_vector(s.size(), 1e-3, 11), f;
    s.rate(y, f);
    for (int i = 8; i < 12; ++i) {
      double dvdx = 0;
      const double xi = y[s.position_offset(i)], vi = y[s.velocity_offset(i)];
      for (int j = 0; j < 12; ++j) {
        const double r = xi - y[s.position_offset(j)];
        if (j == i || std::abs(r) >= 2 * h || (upwind && j > i)) continue;
        const double V = s.mass()[j] / y[s.density_offset(j)];
        dvdx += V * (y[s.velocity_offset(j)] - vi) * kCubic1.d1(std::abs(r), h) * (r > 0 ? 1 : -1);
      }
      EXPECT_NEAR(f[s.velocity_offset(i)], -c * dvdx, 1e-13) << i << " upwind " << upwind;
    }
  }
}

TEST(RateFormAbsorbing, ComplexStepIsTheDerivativeOfTheRealRates) {
  // The absorbing accelerations' complex path (bilinear products, no conjugation) against central differences.
  const auto disc = block(6, 5);
  for (bool upwind : {false, true}) {
    RateFormScheme<2> s(disc, kSteel, {.gradient = RateFormGradient::Ncsph});
    s.set_absorbing(right_and_top(6, 5, AbsorbingCondition::Sochaki, upwind));
    const Eigen::VectorXd y = s.uniform_state() + random_vector(s.size(), 1e-4, 5);
    const Eigen::VectorXd e = random_vector(s.size(), 1.0, 9);
    const double step = 1e-20, eps = 1e-6;
    Eigen::VectorXcd fc;
    s.rate(Eigen::VectorXcd(y.cast<std::complex<double>>() + std::complex<double>(0, step) * e), fc);
    Eigen::VectorXd fp, fm;
    s.rate(Eigen::VectorXd(y + eps * e), fp);
    s.rate(Eigen::VectorXd(y - eps * e), fm);
    const Eigen::VectorXd fd = (fp - fm) / (2 * eps), cs = fc.imag() / step;
    EXPECT_LT((fd - cs).norm(), 1e-5 * cs.norm()) << "upwind " << upwind;
  }
}

TEST(RateFormAbsorbing, PulseLeavesThroughThreeLayersAndReflectsFromAFreeEnd) {
  // Powell (2.68)'s bar without the free-end split: a rightward square pulse (v = 0.01 and sigma = -rho c v on
  // particles 60..74) reaches the right end at t ~ 0.5 us. With 3 absorbing particles (plain SPH + leap-frog) the
  // kinetic energy left at t = 3 us is below 10 % of the pulse's; a free end keeps it in the bar (above 50 %: it comes
  // back).
  const auto disc = bar(100);
  const double c = kBar.p_wave_speed();
  double left[2];
  for (int layers : {0, 3}) {
    RateFormScheme<1> s(disc, kBar, {.continuity = ContinuityForm::Divergence});
    AbsorbingParticles<1> b;
    for (int i = 100 - layers; i < 100; ++i) b.particles.push_back(i), b.normals.emplace_back(1.0);
    s.set_absorbing(b);
    Eigen::VectorXd y = s.uniform_state();
    for (int i = 60; i < 75; ++i) {
      y[s.velocity_offset(i)] = 0.01;
      y[s.density_offset(i)] = kBar.density() * (1 + 0.01 / c);  // compressive: rho = rho0 (1 + v / c)
    }
    const double ke0 = s.kinetic_energy(y);
    const RateFormRunResult r =
        run_rate_form(s, y, {.dt = 0.3 * 0.01 / c, .t_end = 3.0, .integrator = RateFormIntegrator::Leapfrog});
    ASSERT_TRUE(r.completed()) << r.message;
    left[layers ? 1 : 0] = r.kinetic_energy.back() / ke0;
  }
  EXPECT_GT(left[0], 0.5);  // measured 0.74
  EXPECT_LT(left[1], 0.1);  // measured 0.044: plain SPH's dispersive tail and the imperfect absorption
}

TEST(RateFormAbsorbing, StepMatrixPredictsASmallRun) {
  // leapfrog_step_matrix at the rest state, applied k times to the state a run reaches after its start from a small
  // perturbation, gives the run's synchronised state after k steps (v = v^{n+1/2} - dt/2 a^n) to O(perturbation^2):
  // Powell's XSPH, NCSPH and half-step absorbing particles included.
  const auto disc = bar(30);
  RateFormScheme<1> s(disc, kBar, {.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph});
  AbsorbingParticles<1> b;
  for (int i = 27; i < 30; ++i) b.particles.push_back(i), b.normals.emplace_back(1.0);
  s.set_absorbing(b);
  const double dt = 0.3 * 0.01 / kBar.p_wave_speed();
  const RateFormRunOptions o{.dt = dt,
                             .t_end = 20 * dt,
                             .integrator = RateFormIntegrator::Leapfrog,
                             .leapfrog_xsph = 0.1,
                             .absorbing_half_step = true};
  const Eigen::VectorXd rest = s.uniform_state();
  const Eigen::MatrixXd M = leapfrog_step_matrix(s, rest, dt, o);
  const int ny = s.size(), nv = disc->dofs();
  ASSERT_EQ(M.rows(), ny + 2 * nv);
  Eigen::VectorXd y0 = rest;
  const Eigen::VectorXd dv = random_vector(nv, 1e-6, 3);
  for (int i = 0; i < 30; ++i) y0[s.velocity_offset(i)] += dv[i];
  // The run's state after its start: (y0, v0 + dt/2 a0, a0).
  Eigen::VectorXd f0;
  s.rate(y0, f0);
  Eigen::VectorXd z(ny + 2 * nv);
  z.head(ny) = y0 - rest;
  for (int i = 0; i < 30; ++i) {
    const double a0 = f0[s.velocity_offset(i)];
    z[ny + i] = y0[s.velocity_offset(i)] + 0.5 * dt * a0;
    z[ny + nv + i] = a0;
  }
  for (int k = 0; k < 20; ++k) z = M * z;
  Eigen::VectorXd predicted = rest + z.head(ny);
  for (int i = 0; i < 30; ++i) predicted[s.velocity_offset(i)] = z[ny + i] - 0.5 * dt * z[ny + nv + i];
  const RateFormRunResult r = run_rate_form(s, y0, o);
  ASSERT_EQ(r.steps, 20);
  EXPECT_LT((r.y - predicted).norm(), 1e-4 * (r.y - rest).norm()) << (r.y - rest).norm();
  EXPECT_GT((r.y - rest).norm(), 1e-7);
  EXPECT_THROW(leapfrog_step_matrix(s, rest, dt, {}), std::invalid_argument);  // the predictor-corrector
  EXPECT_THROW(leapfrog_step_matrix(s, rest, -dt, o), std::invalid_argument);
}

TEST(RateFormAbsorbing, SpeedScaleIsTheConditionWithScaledSpeeds) {
  // Powell's "H" and Higdon's first-order factor scale c_p and c_s per particle: with NCSPH and a linear velocity
  // field the acceleration equals the condition's with the scaled speeds.
  const auto disc = block(7, 6);
  const Eigen::Matrix2d A{{0.013, -0.004}, {0.007, -0.011}};
  const double c_p = kSteel.p_wave_speed(), c_s = std::sqrt(kSteel.mu() / kSteel.density());
  RateFormScheme<2> s(disc, kSteel, {.gradient = RateFormGradient::Ncsph});
  AbsorbingParticles<2> b = right_and_top(7, 6, AbsorbingCondition::ClaytonEngquist, false);
  for (std::size_t q = 0; q < b.particles.size(); ++q) b.speed_scale.push_back(0.5 + 0.1 * static_cast<double>(q));
  s.set_absorbing(b);
  Eigen::VectorXd y = s.uniform_state(), f;
  for (int i = 0; i < disc->size(); ++i) s.set_velocity(y, i, A * disc->particles.x.row(i).transpose());
  s.rate(y, f);
  for (std::size_t q = 0; q < b.particles.size(); ++q) {
    const int i = b.particles[q];
    const double k = b.speed_scale[q];
    const Vec2 want = absorbing_acceleration(AbsorbingCondition::ClaytonEngquist, k * c_p, k * c_s, b.normals[q], A,
                                             Vec2(A * disc->particles.x.row(i).transpose()));
    EXPECT_LT((f.segment<2>(s.velocity_offset(i)) - want).norm(), 1e-12 * (1 + want.norm())) << i;
  }
}

TEST(RateFormAbsorbing, ViscousTractionAddsTheDashpotToTheMomentumEquation) {
  // Powell (2.75) on the outer face: every rate equals the plain scheme's except the face particles' dv/dt, which gain
  // -(c_p (v.n) n + c_s (v.t) t) / depth exactly (real and complex path).
  const auto disc = block(6, 5);
  const RateFormScheme<2> plain(disc, kSteel, {.viscosity = ViscositySwitch::Always});
  RateFormScheme<2> face = plain;
  AbsorbingParticles<2> b = right_and_top(6, 5, AbsorbingCondition::ViscousTraction, false);
  b.traction_depth = 0.02;
  face.set_absorbing(b);
  const double c_p = kSteel.p_wave_speed(), c_s = std::sqrt(kSteel.mu() / kSteel.density());
  const Eigen::VectorXd y = plain.uniform_state() + random_vector(plain.size(), 1e-3, 3);
  Eigen::VectorXd f, g;
  plain.rate(y, f);
  face.rate(y, g);
  Eigen::VectorXd want = f;
  for (std::size_t q = 0; q < b.particles.size(); ++q) {
    const int i = b.particles[q];
    const Vec2 n = b.normals[q], t(n[1], -n[0]), v = y.segment<2>(plain.velocity_offset(i));
    want.segment<2>(plain.velocity_offset(i)) -= (c_p * v.dot(n) * n + c_s * v.dot(t) * t) / 0.02;
  }
  EXPECT_LT((g - want).norm(), 1e-13 * want.norm());
  Eigen::VectorXcd gc;
  face.rate(Eigen::VectorXcd(y.cast<std::complex<double>>()), gc);
  EXPECT_LT((gc.real() - g).norm(), 1e-15 * g.norm());
  // 1D: the bar's end particle with depth dx, a = -c v / dx.
  const auto rod = bar(10);
  RateFormScheme<1> s1(rod, kBar), p1(rod, kBar);
  s1.set_absorbing({.particles = {9},
                    .normals = {Eigen::Matrix<double, 1, 1>(1.0)},
                    .condition = AbsorbingCondition::ViscousTraction,
                    .traction_depth = 0.01});
  const Eigen::VectorXd y1 = s1.uniform_state() + random_vector(s1.size(), 1e-3, 4);
  Eigen::VectorXd f1, g1;
  p1.rate(y1, f1);
  s1.rate(y1, g1);
  const int k = s1.velocity_offset(9);
  EXPECT_NEAR(g1[k] - f1[k], -kBar.p_wave_speed() * y1[k] / 0.01, 1e-12);
  g1[k] = f1[k];
  EXPECT_EQ((g1 - f1).norm(), 0.0);
}

TEST(RateFormAbsorbing, ViscousEndAbsorbsAPulseInOneDimension) {
  // The dashpot on the last particle of the bar (depth dx) takes out most of a pulse that a free end reflects.
  const auto disc = bar(100);
  const double c = kBar.p_wave_speed();
  RateFormScheme<1> s(disc, kBar, {.continuity = ContinuityForm::Divergence});
  s.set_absorbing({.particles = {99},
                   .normals = {Eigen::Matrix<double, 1, 1>(1.0)},
                   .condition = AbsorbingCondition::ViscousTraction,
                   .traction_depth = 0.01});
  Eigen::VectorXd y = s.uniform_state();
  for (int i = 60; i < 75; ++i) {
    y[s.velocity_offset(i)] = 0.01;
    y[s.density_offset(i)] = kBar.density() * (1 + 0.01 / c);
  }
  const double ke0 = s.kinetic_energy(y);
  const RateFormRunResult r =
      run_rate_form(s, y, {.dt = 0.3 * 0.01 / c, .t_end = 3.0, .integrator = RateFormIntegrator::Leapfrog});
  ASSERT_TRUE(r.completed()) << r.message;
  EXPECT_LT(r.kinetic_energy.back() / ke0, 0.15);  // a free end keeps > 0.5 (test above)
}

TEST(RateFormAbsorbing, BadDeclarationsAreOneLineErrors) {
  const auto disc = block(4, 4);
  RateFormScheme<2> s(disc, kSteel);
  const auto expect_error = [&](AbsorbingParticles<2> b, const std::string& what) {
    try {
      s.set_absorbing(std::move(b));
      ADD_FAILURE() << "no error for " << what;
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(what), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  };
  expect_error({.particles = {3}, .normals = {}}, "1 particles but 0 normals");
  expect_error({.particles = {3}, .normals = {Vec2(1, 1)}}, "normal of length");
  expect_error({.particles = {16}, .normals = {Vec2(1, 0)}}, "out of range");
  expect_error({.particles = {3, 3}, .normals = {Vec2(1, 0), Vec2(1, 0)}}, "listed twice");
  expect_error({.particles = {3}, .normals = {Vec2(1, 0)}, .condition = AbsorbingCondition::Higdon}, "Higdon");
  expect_error({.particles = {3}, .normals = {Vec2(1, 0)}, .speed_scale = {1.0, 1.0}}, "2 speed scales");
  expect_error({.particles = {3}, .normals = {Vec2(1, 0)}, .speed_scale = {-1.0}}, "speed scale -1");
  expect_error({.particles = {3}, .normals = {Vec2(1, 0)}, .condition = AbsorbingCondition::ViscousTraction},
               "traction_depth");
  expect_error({.particles = {3},
                .normals = {Vec2(1, 0)},
                .condition = AbsorbingCondition::ViscousTraction,
                .upwind = true,
                .traction_depth = 0.02},
               "do not apply to the viscous traction");
  s.set_driven({5}, {Vec2(0, 1)});
  expect_error({.particles = {5}, .normals = {Vec2(1, 0)}}, "is driven");
  s.set_driven({}, {});
  s.set_absorbing({.particles = {5}, .normals = {Vec2(1, 0)}});
  EXPECT_THROW(s.set_driven({5}, {Vec2(0, 1)}), std::invalid_argument);
  EXPECT_THROW(run_rate_form(s, s.uniform_state(), {.dt = 1e-3, .t_end = 1e-2, .absorbing_half_step = true}),
               std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
