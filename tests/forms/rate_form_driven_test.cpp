// Driven particles of the rate-form scheme (RateFormScheme::set_driven, [GMS2001, §7.3]): a prescribed constant
// acceleration replaces the SPH force and the particle moves with its own velocity, so it follows x0 + v0 t + a t^2/2
// exactly with every integrator (neighbour rebuilds included); density and stress evolve as usual, and a block pulled
// at both ends goes into tension.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/numerics/random_vector.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace rate_form_driven_test {

const ElasticMaterial kGms = ElasticMaterial::from_bulk_shear(1.0, 0.22, 1.0);
const Kernel<2> kCubic(KernelType::CubicSpline);
using Vec2 = Eigen::Vector2d;

/// A free nx x ny block at dx = 1 (particle (i, j) at (i + 1/2, j + 1/2), index j nx + i), h = 1.5 dx.
std::shared_ptr<const Discretisation<2>> free_block(int nx, int ny) {
  ParticleSet<2> p;
  p.x.resize(nx * ny, 2);
  p.volume = Eigen::VectorXd::Ones(nx * ny);
  p.role.assign(nx * ny, Role::Free);
  p.spacing = 1.0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) p.x.row(j * nx + i) << i + 0.5, j + 0.5;
  return make_discretisation(p, kCubic, 1.5);
}

/// Moving, compressed and sheared state: every particle feels a force.
Eigen::VectorXd busy_state(const RateFormScheme<2>& s, std::uint64_t seed) {
  Eigen::VectorXd y = s.uniform_state() + random_vector(s.size(), 0.02, seed);
  for (int i = 0; i < s.discretisation().size(); ++i) y[s.density_offset(i)] += 0.03;
  return y;
}

const std::vector<int> kDriven{7, 20};
const std::vector<Vec2> kAcceleration{Vec2(0.01, -0.004), Vec2(-0.006, 0.012)};

TEST(RateFormDriven, RatesReplaceTheForceAndKeepTheRest) {
  // Without XSPH the driven scheme's rates are the undriven scheme's except the driven particles' dv/dt, which are
  // the prescribed accelerations (all exact). With XSPH the driven particles' dx/dt is their own v; the other
  // particles' dx/dt is unchanged (XSPH reads v_j, not vhat_j), their rho and S rates change (L reads vhat_j).
  for (double xsph : {0.0, 0.5}) {
    const auto disc = free_block(6, 6);
    const RateFormScheme<2> plain(disc, kGms, {.xsph = xsph, .viscosity = ViscositySwitch::Always});
    RateFormScheme<2> driven = plain;
    driven.set_driven(kDriven, kAcceleration);
    EXPECT_TRUE(driven.is_driven(7) && driven.is_driven(20) && !driven.is_driven(8));
    const Eigen::VectorXd y = busy_state(plain, 3);
    Eigen::VectorXd f, g;
    plain.rate(y, f);
    driven.rate(y, g);
    for (int q = 0; q < 2; ++q) {
      const int i = kDriven[q];
      EXPECT_EQ(Vec2(g.segment<2>(driven.velocity_offset(i))), kAcceleration[q]);
      EXPECT_EQ(Vec2(g.segment<2>(driven.position_offset(i))), Vec2(y.segment<2>(driven.velocity_offset(i))));
      EXPECT_GT((f.segment<2>(plain.velocity_offset(i)) - kAcceleration[q]).norm(), 1e-3);  // the test can tell
      if (xsph > 0)
        EXPECT_GT((f.segment<2>(plain.position_offset(i)) - g.segment<2>(plain.position_offset(i))).norm(), 1e-6);
    }
    for (int i = 0; i < disc->size(); ++i) {
      if (driven.is_driven(i)) continue;
      EXPECT_EQ(Vec2(g.segment<2>(driven.position_offset(i))), Vec2(f.segment<2>(plain.position_offset(i)))) << i;
      if (xsph == 0)
        EXPECT_EQ(Vec2(g.segment<2>(driven.velocity_offset(i))), Vec2(f.segment<2>(plain.velocity_offset(i))));
    }
    if (xsph == 0) {
      for (int i = 0; i < disc->size(); ++i)
        EXPECT_EQ(Eigen::Vector4d(g.segment<4>(driven.density_offset(i))),
                  Eigen::Vector4d(f.segment<4>(plain.density_offset(i))));
    }
  }
}

TEST(RateFormDriven, ComplexStepJacobianHasTheDrivenRows) {
  // J = dF/dy by the complex step: the driven particles' dv/dt rows are zero and their dx/dt rows read only their own
  // v (identity block), with XSPH on; the complex rate's real part is the real rate (to the rounding of complex
  // arithmetic).
  const auto disc = free_block(5, 5);
  RateFormScheme<2> s(disc, kGms, {.xsph = 0.5, .viscosity = ViscositySwitch::Compression, .artificial_stress = 0.3});
  s.set_driven({7}, {Vec2(0.01, -0.004)});
  const Eigen::VectorXd y = busy_state(s, 5);
  const Eigen::MatrixXd J(jacobian(s, y));
  const int xo = s.position_offset(7), vo = s.velocity_offset(7);
  EXPECT_EQ(J.middleRows(vo, 2).cwiseAbs().maxCoeff(), 0.0);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(2, s.size());
  expected.middleCols(vo, 2).setIdentity();
  EXPECT_EQ(Eigen::MatrixXd(J.middleRows(xo, 2)), expected);
  // An undriven neighbour's rows do depend on particle 7 (the test can tell).
  EXPECT_GT(J.middleRows(s.velocity_offset(8), 2).middleCols(xo, 2).cwiseAbs().maxCoeff(), 1e-3);
  Eigen::VectorXd f;
  Eigen::VectorXcd fc;
  s.rate(y, f);
  s.rate(Eigen::VectorXcd(y.cast<std::complex<double>>()), fc);
  EXPECT_LE((fc.real() - f).cwiseAbs().maxCoeff(), 1e-15 * f.cwiseAbs().maxCoeff());  // complex rounding
}

TEST(RateFormDriven, DrivenParticleFollowsItsParabola) {
  // x(t) = x0 + v0 t + a t^2/2 and v(t) = v0 + a t, to rounding, while its neighbours move, with every integrator, GMS
  // XSPH, Powell's XSPH and a neighbour rebuild (the driven particles move ~2 dx in 40 steps of 0.5; 24-26 builds).
  // Measured <= 9.6e-16 (position, relative to |x|) and <= 1.4e-16 (velocity); the densities of the driven particles
  // change by 0.12-0.40 (the compressed free block expands).
  const auto disc = free_block(6, 6);
  RateFormScheme<2> s(disc, kGms, {.xsph = 0.5});
  s.set_driven(kDriven, kAcceleration);
  const Eigen::VectorXd y0 = busy_state(s, 9);
  struct Case {
    RateFormIntegrator integrator;
    PositionUpdate positions;
    double leapfrog_xsph, skin;
  };
  for (const Case& c : {Case{RateFormIntegrator::PredictorCorrector, PositionUpdate::Gms, 0, 0},
                        Case{RateFormIntegrator::PredictorCorrector, PositionUpdate::Trapezoid, 0, 0},
                        Case{RateFormIntegrator::PredictorCorrector, PositionUpdate::Gms, 0, 0.2},
                        Case{RateFormIntegrator::Leapfrog, PositionUpdate::Gms, 0, 0},
                        Case{RateFormIntegrator::Leapfrog, PositionUpdate::Gms, 0.1, 0},
                        Case{RateFormIntegrator::Leapfrog, PositionUpdate::Gms, 0.1, 0.2}}) {
    RateFormRunOptions o{.dt = 0.5, .positions = c.positions, .t_end = 20.0, .integrator = c.integrator};
    o.leapfrog_xsph = c.leapfrog_xsph;
    o.neighbour_skin = c.skin;
    double worst_x = 0, worst_v = 0;
    o.observer = [&](long, double t, const Eigen::VectorXd& y) {
      for (int q = 0; q < 2; ++q) {
        const int xo = s.position_offset(kDriven[q]), vo = s.velocity_offset(kDriven[q]);
        const Vec2 x = y0.segment<2>(xo) + y0.segment<2>(vo) * t + 0.5 * kAcceleration[q] * t * t;
        const Vec2 v = y0.segment<2>(vo) + kAcceleration[q] * t;
        worst_x = std::max(worst_x, (y.segment<2>(xo) - x).cwiseAbs().maxCoeff() / x.norm());
        worst_v = std::max(worst_v, (y.segment<2>(vo) - v).cwiseAbs().maxCoeff());
      }
    };
    const RateFormRunResult r = run_rate_form(s, y0, o);
    ASSERT_TRUE(r.completed()) << r.message;
    if (c.skin > 0) EXPECT_GT(r.neighbour_builds, 2);
    EXPECT_LE(worst_x, 1e-14);
    EXPECT_LE(worst_v, 1e-15);
    for (int i : kDriven) EXPECT_GT(std::abs(r.y[s.density_offset(i)] - y0[s.density_offset(i)]), 1e-3);
  }
}

/// Mean axial stress sigma_xx = S_xx - p over the particles within 2 dx of the middle of a 24 x 6 block.
double middle_axial_stress(const RateFormScheme<2>& s, const Eigen::VectorXd& y) {
  double sum = 0;
  int count = 0;
  for (int i = 0; i < s.discretisation().size(); ++i)
    if (std::abs(s.discretisation().particles.x(i, 0) - 12.0) < 2) {
      const int r = s.density_offset(i);
      sum += y[r + 1] - kGms.bulk_modulus() * (y[r] / kGms.density() - 1);
      ++count;
    }
  return sum / count;
}

TEST(RateFormDriven, BlockPulledAtBothEndsIsInTensionInTheMiddle) {
  // GMS §7.3 in small: the particles within 2 dx of each end of a 24 x 6 free block get an axial acceleration
  // -+2e-3 (GMS units, XSPH 0.5). By t = 20 the tension has reached the middle: measured sigma_xx = 0.0174 (both
  // integrators, with and without a rebuilding list: 3 builds) while the block has grown by a t^2 = 0.8 (to 1.5e-13:
  // rounding of x ~ 23 over 100 steps). The undriven block stays unstressed (exactly 0).
  const auto disc = free_block(24, 6);
  RateFormScheme<2> s(disc, kGms, {.xsph = 0.5});
  const Eigen::VectorXd y0 = s.uniform_state();
  std::vector<int> ends;
  std::vector<Vec2> pull;
  for (int i = 0; i < disc->size(); ++i) {
    const double x = disc->particles.x(i, 0);
    if (x < 2 || x > 22) {
      ends.push_back(i);
      pull.push_back(Vec2(x < 2 ? -2e-3 : 2e-3, 0));
    }
  }
  ASSERT_EQ(ends.size(), 24u);
  for (RateFormIntegrator integrator : {RateFormIntegrator::PredictorCorrector, RateFormIntegrator::Leapfrog}) {
    const RateFormRunOptions o{.dt = 0.2, .t_end = 20.0, .integrator = integrator};
    const RateFormRunResult rest = run_rate_form(s, y0, o);
    EXPECT_EQ(middle_axial_stress(s, rest.y), 0.0);
    RateFormScheme<2> pulled = s;
    pulled.set_driven(ends, pull);
    for (double skin : {0.0, 0.3}) {
      RateFormRunOptions os = o;
      os.neighbour_skin = skin;
      const RateFormRunResult r = run_rate_form(pulled, y0, os);
      ASSERT_TRUE(r.completed()) << r.message;
      EXPECT_GT(middle_axial_stress(pulled, r.y), 0.01);
      const double length = r.y[pulled.position_offset(23)] - r.y[pulled.position_offset(0)];
      EXPECT_NEAR(length, 23.0 + 2e-3 * 20 * 20, 1e-12);
    }
  }
}

TEST(RateFormDriven, RejectsBadInput) {
  const auto disc = make_discretisation(
      make_lattice<2>(LatticeType::Square, 4, {.spacing = 1.0, .support_radius = kCubic.support_radius(1.3)}), kCubic,
      1.3);
  RateFormScheme<2> s(disc, kGms);
  const int fixed = disc->free_count();  // the free block comes first
  ASSERT_LT(s.position_offset(fixed), 0);
  const Vec2 a(1, 0);
  EXPECT_THROW(s.set_driven({0, 1}, {a}), std::invalid_argument);
  EXPECT_THROW(s.set_driven({-1}, {a}), std::invalid_argument);
  EXPECT_THROW(s.set_driven({disc->size()}, {a}), std::invalid_argument);
  EXPECT_THROW(s.set_driven({fixed}, {a}), std::invalid_argument);
  EXPECT_THROW(s.set_driven({3, 5, 3}, {a, a, a}), std::invalid_argument);
  EXPECT_THROW(s.set_driven({3}, {Vec2(std::numeric_limits<double>::quiet_NaN(), 0)}), std::invalid_argument);
  EXPECT_THROW(s.set_driven({3}, {Vec2(0, std::numeric_limits<double>::infinity())}), std::invalid_argument);
  EXPECT_TRUE(s.driven_particles().empty());  // a rejected declaration changes nothing
  s.set_driven({3, 5}, {a, a});
  EXPECT_EQ(s.driven_particles().size(), 2u);
  EXPECT_THROW(s.set_driven({3}, {}), std::invalid_argument);
  EXPECT_EQ(s.driven_particles().size(), 2u);
  s.set_driven({}, {});
  EXPECT_TRUE(s.driven_particles().empty() && !s.is_driven(3));
}

}  // namespace
}  // namespace sphstab
