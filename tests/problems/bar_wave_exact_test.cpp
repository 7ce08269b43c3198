#include "sphstab/problems/bar_wave_exact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace sphstab {
namespace bar_wave_exact_test {

/// Midpoint rule with m cells: the integrands here are piecewise constant with a few jumps, so the error is
/// at most (number of jumps) x (jump size) x (b - a) / m.
template <class F>
double midpoint(F f, double a, double b, int m) {
  double s = 0, h = (b - a) / m;
  for (int k = 0; k < m; ++k) s += f(a + (k + 0.5) * h);
  return s * h;
}

TEST(BarJumpExact, InitialAndBoundaryConditions) {
  for (BarEnd left : {BarEnd::Free, BarEnd::Fixed})
    for (BarEnd right : {BarEnd::Free, BarEnd::Fixed}) {
      BarJumpProblem p;
      p.left = left;
      p.right = right;
      BarJumpExact ex(p);
      for (double x : {0.01, 0.2, 0.349, 0.351, 0.7, 0.99}) {
        EXPECT_EQ(ex.velocity(x, 0.0), x < 0.35 ? 0.01 : -0.01);
        EXPECT_EQ(ex.stress(x, 0.0), 0.0);
        EXPECT_NEAR(ex.displacement(x, 0.0), 0.0, 1e-18);
      }
      for (double t = 0.013; t < 12.0; t += 0.377) {
        if (left == BarEnd::Free) {
          EXPECT_EQ(ex.stress(0.0, t), 0.0) << t;
        } else {
          EXPECT_EQ(ex.velocity(0.0, t), 0.0) << t;
          EXPECT_NEAR(ex.displacement(0.0, t), 0.0, 1e-16) << t;
        }
        if (right == BarEnd::Free) {
          EXPECT_NEAR(ex.stress(1.0, t), 0.0, 1e-15) << t;
        } else {
          EXPECT_NEAR(ex.velocity(1.0, t), 0.0, 1e-15) << t;
          EXPECT_NEAR(ex.displacement(1.0, t), 0.0, 1e-16) << t;
        }
      }
      // Time periodicity: 2L/c for equal end types, 4L/c for mixed (and then v(t + 2L/c) = -v(t)).
      const double P = ex.period(), c = ex.wave_speed();
      EXPECT_NEAR(P, (left == right ? 2.0 : 4.0) / c, 1e-14);
      // Free-free: the bar drifts with its mean velocity (0.35 x 0.01 - 0.65 x 0.01 = -0.003 cm/µs) per period.
      const double drift = (left == BarEnd::Free && right == BarEnd::Free) ? -0.003 * P : 0.0;
      for (double x : {0.123, 0.5, 0.876}) {
        EXPECT_NEAR(ex.velocity(x, 0.7 + P), ex.velocity(x, 0.7), 1e-15);
        EXPECT_NEAR(ex.displacement(x, 0.7 + P), ex.displacement(x, 0.7) + drift, 1e-14);
        if (left != right) EXPECT_NEAR(ex.velocity(x, 0.7 + 2.0 / c), -ex.velocity(x, 0.7), 1e-15);
      }
    }
}

TEST(BarJumpExact, JumpConditionsAndIntegralBalanceLaws) {
  BarJumpProblem p;  // Powell's values: rho = 7.8, E = 2.1, c = 0.518875 cm/µs, free ends
  BarJumpExact ex(p);
  const double rho = p.density, c = ex.wave_speed();
  EXPECT_NEAR(c, 0.5188745216627708, 1e-15);
  // Rankine-Hugoniot [sigma] = -rho s [v] at every discontinuity, s = +c for x - ct at a jump of ĝ, -c for x + ct.
  for (double t : {0.3, 1.5, 2.9, 5.1}) {
    int found = 0;
    const double d = 1e-10;
    for (double x0 = 0.0; x0 < 1.0 - 1e-12; x0 += 0.001) {
      // Locate a jump inside [x0, x0 + 0.001] by bisection.
      double a = x0, b = x0 + 0.001;
      if (std::abs(ex.velocity(a, t) - ex.velocity(b, t)) < 1e-6) continue;
      while (b - a > 1e-13) {
        const double mid = 0.5 * (a + b);
        (std::abs(ex.velocity(a, t) - ex.velocity(mid, t)) > 1e-6 ? b : a) = mid;
      }
      const double x = 0.5 * (a + b);
      const double dv = ex.velocity(x + d, t) - ex.velocity(x - d, t);
      ++found;
      const double ds = ex.stress(x + d, t) - ex.stress(x - d, t);
      const bool right_moving =
          std::abs(ex.extended_velocity(x - c * t + d) - ex.extended_velocity(x - c * t - d)) > 1e-6;
      const double s = right_moving ? c : -c;
      EXPECT_NEAR(ds, -rho * s * dv, 1e-12) << "x " << x << " t " << t;
    }
    EXPECT_EQ(found, 2) << "t " << t;  // one left- and one right-moving front (reflected as needed)
  }
  // Weak form on space-time boxes [x1, x2] x [t1, t2] (valid across the discontinuities):
  //   momentum:        ∫ rho v dx |_{t1}^{t2} = ∫ sigma dt |_{x1}^{x2}
  //   compatibility:   ∫ (sigma/E) dx |_{t1}^{t2} = ∫ v dt |_{x1}^{x2}
  // Midpoint error <= jump x cell / 2 per discontinuity: rho [v] <= 0.156 and [sigma]/E <= 0.039 with cells
  // <= 5e-6 and up to 8 discontinuities on the two time levels: <= 3.2e-6 and 8e-7.
  const int m = 200000;
  for (const std::array<double, 4>& box : std::vector<std::array<double, 4>>{
           {0.1, 0.6, 0.2, 1.1}, {0.0, 1.0, 0.0, 3.0}, {0.37, 0.91, 1.4, 4.2}, {0.05, 0.3, 0.0, 0.9}}) {
    const double x1 = box[0], x2 = box[1], t1 = box[2], t2 = box[3];  // captured below: named, not bound
    const double lhs_m = midpoint([&](double x) { return rho * (ex.velocity(x, t2) - ex.velocity(x, t1)); }, x1, x2, m);
    const double rhs_m = midpoint([&](double t) { return ex.stress(x2, t) - ex.stress(x1, t); }, t1, t2, m);
    EXPECT_NEAR(lhs_m, rhs_m, 4e-6) << x1 << " " << x2 << " " << t1 << " " << t2;
    const double lhs_c =
        midpoint([&](double x) { return (ex.stress(x, t2) - ex.stress(x, t1)) / p.youngs_modulus; }, x1, x2, m);
    const double rhs_c = midpoint([&](double t) { return ex.velocity(x2, t) - ex.velocity(x1, t); }, t1, t2, m);
    EXPECT_NEAR(lhs_c, rhs_c, 1e-6) << x1 << " " << x2 << " " << t1 << " " << t2;
  }
}

TEST(BarJumpExact, MomentumAndEnergyAreConservedWithFreeEnds) {
  BarJumpProblem p;
  BarJumpExact ex(p);
  const double m0 = p.density * (0.35 * 0.01 - 0.65 * 0.01);
  const double e0 = 0.5 * p.density * 0.01 * 0.01 * 1.0;
  for (double t : {0.0, 0.4, 1.5, 2.2, 3.3, 7.7}) {
    const double mom = midpoint([&](double x) { return p.density * ex.velocity(x, t); }, 0.0, 1.0, 100000);
    EXPECT_NEAR(mom, m0, 1e-7) << t;  // quadrature: 4 jumps x 0.078 / 1e5
    EXPECT_NEAR(ex.momentum(t), m0, 1e-15) << t;
    const double en = midpoint(
        [&](double x) {
          const double v = ex.velocity(x, t), s = ex.stress(x, t);
          return 0.5 * p.density * v * v + 0.5 * s * s / p.youngs_modulus;
        },
        0.0, 1.0, 100000);
    EXPECT_NEAR(en, e0, 1e-8) << t;
  }
}

TEST(BarJumpExact, DisplacementIsConsistentWithVelocityAndStress) {
  for (BarEnd right : {BarEnd::Free, BarEnd::Fixed}) {
    BarJumpProblem p;
    p.right = right;
    BarJumpExact ex(p);
    const double d = 1e-6;
    for (double t : {0.25, 1.3, 4.4})
      for (double x : {0.05, 0.21, 0.48, 0.66, 0.93}) {
        // Skip points within d of a discontinuity (central differences straddle it there).
        const double vl = ex.velocity(x - 2 * d, t), vr = ex.velocity(x + 2 * d, t);
        if (std::abs(vl - vr) > 1e-12) continue;
        const double dudt = (ex.displacement(x, t + d) - ex.displacement(x, t - d)) / (2 * d);
        const double dudx = (ex.displacement(x + d, t) - ex.displacement(x - d, t)) / (2 * d);
        EXPECT_NEAR(dudt, ex.velocity(x, t), 1e-9) << x << " " << t;  // u is piecewise linear: only round-off
        EXPECT_NEAR(p.youngs_modulus * dudx, ex.stress(x, t), 1e-8) << x << " " << t;
      }
  }
}

TEST(BarJumpExact, ReproducesPowellsParticle80History) {
  // Powell §3.1 (semi-infinite bar; an 8 cm bar is semi-infinite for x = 0.795 until t = 28 µs):
  // v = -0.01 for t < 0.858, 0 until 2.207, then -0.01 (the exact solution of [Powell2012, (2.68)] at x = 0.795).
  BarJumpProblem p;
  p.length = 8.0;
  BarJumpExact ex(p);
  const double c = ex.wave_speed(), x = 0.795;
  EXPECT_NEAR((x - 0.35) / c, 0.858, 5e-4);
  EXPECT_NEAR((x + 0.35) / c, 2.207, 5e-4);
  for (double t = 0.0; t < 20.0; t += 0.01) {
    double expected = (t < (x - 0.35) / c || t > (x + 0.35) / c) ? -0.01 : 0.0;
    if (std::abs(t - (x - 0.35) / c) < 1e-9 || std::abs(t - (x + 0.35) / c) < 1e-9) continue;
    EXPECT_EQ(ex.velocity(x, t), expected) << t;
  }
  EXPECT_THROW(BarJumpExact(BarJumpProblem{.jump_position = 1.5}), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
