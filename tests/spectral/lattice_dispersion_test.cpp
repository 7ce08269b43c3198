#include "sphstab/spectral/lattice_dispersion.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"

namespace sphstab {
namespace lattice_dispersion_test {

const double pi = M_PI;
const Eigen::Vector2d k_short(pi, 0);  // k = (pi/dp, 0), dp = 1

TEST(LatticeDispersion, SquareCheckValuesAtHEqualsDp) {
  // [GMS2001, (5.20)-(5.29)] lattice sums (units 1/dp^2), to the printed precision.
  Kernel<2> w(KernelType::CubicSpline);
  auto s = lattice_sums(LatticeType::Square, w, 1.0, k_short, {.exponent = 4});
  EXPECT_NEAR(s.Bx, 3.996, 5e-4);
  EXPECT_NEAR(s.By, -0.0969, 5e-5);
  EXPECT_NEAR(s.fxx, 19.12, 5e-3);
  EXPECT_NEAR(s.beta, 0.319, 5e-4);
  EXPECT_NEAR(s.Bx / s.fxx, 0.209, 5e-4);
  EXPECT_NEAR(s.A.norm(), 0.0, 1e-14);  // sin(pi m) = 0 on the square lattice
  EXPECT_NEAR(s.C, 0.0, 1e-14);
  EXPECT_NEAR(s.fxy, 0.0, 1e-14);
  auto nn = lattice_sums(LatticeType::Square, w, 1.0, k_short, {.exponent = 4, .max_distance = 1.0});
  EXPECT_NEAR(nn.fxx, 19.10, 5e-3);
  // Closed forms (GMS 5.21; beta per its definition [GMS2001, (5.5)], recomputed), to rounding.
  const double c = 5 / (14 * pi), r2 = std::sqrt(2.0);
  EXPECT_NEAR(s.Bx, 150 * (2 - r2) / (7 * pi), 1e-13);
  EXPECT_NEAR(s.beta, 10 / (7 * pi) * (0.5 + std::pow(2 - r2, 3)), 1e-14);
  EXPECT_NEAR(s.beta, 2 * c * (1 + 2 * std::pow(2 - r2, 3)), 1e-14);
  for (double n : {0.0, 1.0, 2.0, 4.0, 6.0}) {
    auto nn_n = lattice_sums(LatticeType::Square, w, 1.0, k_short, {.exponent = n, .max_distance = 1.0});
    EXPECT_NEAR(nn_n.fxx, 30 * (3 * n + 2) / (7 * pi), 1e-12) << "n = " << n;
  }
}

TEST(LatticeDispersion, FaceCentredCheckValuesAtHEqualsDp) {
  Kernel<2> w(KernelType::CubicSpline);
  auto s = lattice_sums(LatticeType::FaceCentred, w, 1.0, k_short, {.exponent = 4});
  EXPECT_NEAR(s.A[0], -0.430, 5e-4);
  EXPECT_NEAR(s.A[1], 0.0, 1e-14);
  EXPECT_NEAR(s.Bx, 2.814, 5e-4);
  EXPECT_NEAR(s.By, 0.516, 5e-4);
  EXPECT_NEAR(s.C, 0.0, 1e-14);
  EXPECT_NEAR(s.fxx, 19.68, 5e-3);
  EXPECT_NEAR(s.fyy, 1.579, 5e-4);
  EXPECT_NEAR(s.Bx / s.fxx, 0.143, 5e-4);
  EXPECT_NEAR(s.By / s.fyy, 0.327, 5e-4);
}

TEST(LatticeDispersion, ExponentZeroArtificialStressSumsEqualHessianSums) {
  // n = 0: Z = V, f = V sum (1 - cos) d^2 W = B (an identity of the definitions 5.5, 5.14, 5.15).
  Kernel<2> w(KernelType::CubicSpline);
  for (auto type : {LatticeType::Square, LatticeType::FaceCentred, LatticeType::Hexagonal}) {
    auto s = lattice_sums(type, w, 1.3, Eigen::Vector2d(1.1, 0.7), {.exponent = 0});
    EXPECT_NEAR(s.fxx, s.Bx, 1e-13);
    EXPECT_NEAR(s.fyy, s.By, 1e-13);
    EXPECT_NEAR(s.fxy, s.C, 1e-13);
  }
}

TEST(LatticeDispersion, SumsEqualRowsOfAssembledPeriodicOperators) {
  // Independent route: the same sums from W, G, H matrices of a periodic make_lattice (one row).
  for (auto type : {LatticeType::Square, LatticeType::FaceCentred}) {
    for (double h : {1.0, 1.37, 1.8}) {
      Kernel<2> w(KernelType::CubicSpline);
      const int n = 12;
      auto set = make_lattice<2>(type, n, {.spacing = 1.0, .periodic = true});
      auto nl = find_neighbours(set, w.support_radius(h));
      auto ops = assemble_operators<2, double>(set, nl, w, h, {.kernel = true, .gradient = true, .hessian = true});
      const Eigen::Vector2d k(2 * pi * 5 / n, 2 * pi * 2 / n);  // commensurate with the box
      auto s = lattice_sums(type, w, h, k, {.exponent = 4});
      const int a = 17;
      Eigen::Vector2d A = Eigen::Vector2d::Zero();
      double Bx = 0, By = 0, C = 0, beta = 0;
      for (long q = nl.offsets[a]; q < nl.offsets[a + 1]; ++q) {
        const int b = nl.indices[q];
        if (b == a) continue;
        const auto r = set.separation(a, b);
        const double ph = k[0] * r[0] + k[1] * r[1];
        A[0] += std::sin(ph) * ops.G[0].coeff(a, b);
        A[1] += std::sin(ph) * ops.G[1].coeff(a, b);
        Bx += (1 - std::cos(ph)) * ops.H[0][0].coeff(a, b);
        By += (1 - std::cos(ph)) * ops.H[1][1].coeff(a, b);
        C += (1 - std::cos(ph)) * ops.H[0][1].coeff(a, b);
        beta += 0.5 * (1 - std::cos(ph)) * ops.W.coeff(a, b);
      }
      SCOPED_TRACE(lattice_name(type) + " h = " + std::to_string(h));
      EXPECT_NEAR(s.A[0], A[0], 1e-13);
      EXPECT_NEAR(s.A[1], A[1], 1e-13);
      EXPECT_NEAR(s.Bx, Bx, 1e-13);
      EXPECT_NEAR(s.By, By, 1e-13);
      EXPECT_NEAR(s.C, C, 1e-13);
      EXPECT_NEAR(s.beta, beta, 1e-13);
    }
  }
}

TEST(LatticeDispersion, ArtificialStressSumsMatchFiniteDifferenceHessian) {
  // f_xx etc. from a central-difference Hessian of W^{n+1} (independent of the closed-form derivative).
  Kernel<2> w(KernelType::CubicSpline);
  const double h = 1.25, n = 4, wdp = w.value(1.0, h), d = 1e-4;
  const Eigen::Vector2d k(0.9, 2.1);
  auto s = lattice_sums(LatticeType::FaceCentred, w, h, k, {.exponent = n});
  auto F = [&](double x, double y) { return std::pow(w.value(std::hypot(x, y), h), n + 1); };
  double fxx = 0, fyy = 0, fxy = 0;
  for (int j = -4; j <= 4; ++j)
    for (int i = -5; i <= 5; ++i) {
      const double x = i + ((j & 1) ? 0.5 : 0.0), y = j;
      if (x == 0 && y == 0) continue;
      const double omc = 1 - std::cos(k[0] * x + k[1] * y);
      fxx += omc * (F(x + d, y) - 2 * F(x, y) + F(x - d, y)) / (d * d);
      fyy += omc * (F(x, y + d) - 2 * F(x, y) + F(x, y - d)) / (d * d);
      fxy += omc * (F(x + d, y + d) - F(x + d, y - d) - F(x - d, y + d) + F(x - d, y - d)) / (4 * d * d);
    }
  const double Z = 1.0 / ((n + 1) * std::pow(wdp, n));
  // Central differences: O(d^2) truncation (~1e-8 relative) plus rounding eps/d^2 ~ 1e-8 (relative to W^5 ~ 1e-5).
  EXPECT_NEAR(s.fxx, Z * fxx, 1e-5 * std::abs(s.fxx) + 1e-7);
  EXPECT_NEAR(s.fyy, Z * fyy, 1e-5 * std::abs(s.fyy) + 1e-7);
  EXPECT_NEAR(s.fxy, Z * fxy, 1e-5 * std::abs(s.fxy) + 1e-7);
}

TEST(LatticeDispersion, ShortWaveModesOfGms) {
  // k along x: M is diagonal, omega2[0] is the longitudinal mode (5.20 / 5.25), omega2[1] the transverse (5.24 / 5.28).
  Kernel<2> w(KernelType::CubicSpline);
  UniformState st{.density = 1, .sound_speed = 1, .shear_modulus = 0.3, .pressure = -0.1, .sxx = 0.02, .syy = -0.03};
  st.rxx = -0.01;
  st.ryy = -0.02;
  for (auto type : {LatticeType::Square, LatticeType::FaceCentred}) {
    auto d = lattice_dispersion(type, w, 1.0, k_short, st);
    const auto& s = d.sums;
    const double zeta = 0.5 * (st.sxx - st.syy), ax2 = s.A[0] * s.A[0];
    const double lon = 2 * s.Bx * (st.pressure - st.sxx) +
                       ax2 * (1 + 4 * st.shear_modulus / 3 - 2 * (st.pressure - st.sxx)) - 2 * st.rxx * s.fxx;
    const double tra = 2 * s.By * (st.pressure - st.syy) + ax2 * (st.shear_modulus + zeta) - 2 * st.ryy * s.fyy;
    EXPECT_NEAR(d.M(0, 1), 0.0, 1e-14);
    EXPECT_NEAR(d.M(1, 0), 0.0, 1e-14);
    EXPECT_NEAR(d.omega2[0].real(), (1 - s.beta) * lon, 1e-13);
    EXPECT_NEAR(d.omega2[1].real(), (1 - s.beta) * tra, 1e-13);
    EXPECT_NEAR(d.omega2[0].imag(), 0.0, 1e-15);
    EXPECT_NEAR(std::abs(d.modes(0, 0)), 1.0, 1e-14);
  }
}

TEST(LatticeDispersion, LongWaveLimitIsContinuumWithLatticeMoments) {
  // GMS §5.1: (5.8)/(5.9) -> (4.9)/(4.10) as k -> 0 when the sums are replaced by integrals (W~ = 1). On a
  // lattice M/k^2 converges at O(k^2) to the continuum formula with A = -D1 k and B_ab = 1/2 sum V (k.r)^2 W_,ab,
  // the lattice's discrete moments (D1 = I, B = k k^T for exact moments). Checked here by its Taylor limit.
  Kernel<2> w(KernelType::CubicSpline);
  UniformState st{.density = 1, .sound_speed = 1, .shear_modulus = 0.22, .pressure = -0.05, .sxx = 0.02, .syy = -0.01};
  const Eigen::Vector2d dir(0.8, 0.6);
  auto cont = continuum_dispersion(dir, st);  // M scales as k^2
  EXPECT_NEAR(cont.M(0, 0), 0.64 * (1 + 4 * 0.22 / 3) + 0.36 * (0.22 - 0.015), 1e-15);
  EXPECT_NEAR(cont.M(0, 1), 0.48 * (1 + 0.22 / 3 + 0.015), 1e-15);
  EXPECT_NEAR(cont.M(1, 0), 0.48 * (1 + 0.22 / 3 - 0.015), 1e-15);
  for (auto type : {LatticeType::Square, LatticeType::FaceCentred}) {
    for (double h : {1.0, 1.5, 2.0}) {
      auto m_of = [&](double k) { return Eigen::Matrix2d(lattice_dispersion(type, w, h, k * dir, st).M / (k * k)); };
      const Eigen::Matrix2d m1 = m_of(1e-2), m2 = m_of(5e-3), m3 = m_of(2.5e-3);
      const double d12 = (m1 - m2).norm(), d23 = (m2 - m3).norm();
      EXPECT_NEAR(d12 / d23, 4.0, 0.05) << lattice_name(type) << " h = " << h;  // O(k^2); O(k^4) terms remain
      const Eigen::Matrix2d limit = m3 - (m2 - m3) / 3;                         // Richardson extrapolation to k = 0
      // Taylor limit of the sums, written out independently: sin(k.r) -> k.r, 1 - cos(k.r) -> (k.r)^2 / 2.
      LatticeSums moments;
      const double shift = type == LatticeType::FaceCentred ? 0.5 : 0.0;
      for (int j = -5; j <= 5; ++j)
        for (int i = -6; i <= 6; ++i) {
          const double x = i + ((j & 1) ? shift : 0.0), y = j, r = std::hypot(x, y);
          if (r == 0 || r >= 2 * h) continue;
          const double kr = dir[0] * x + dir[1] * y, w1 = w.d1(r, h), w2 = w.d2(r, h);
          const double ex = x / r, ey = y / r;
          moments.A += kr * w1 * Eigen::Vector2d(ex, ey);
          moments.Bx += 0.5 * kr * kr * (w2 * ex * ex + w1 / r * (1 - ex * ex));
          moments.By += 0.5 * kr * kr * (w2 * ey * ey + w1 / r * (1 - ey * ey));
          moments.C += 0.5 * kr * kr * (w2 - w1 / r) * ex * ey;
        }
      const Eigen::Matrix2d expect = dispersion_matrix(moments, st);
      // Extrapolation leaves O(k^4) = 4e-11 relative; rounding of the k = 2.5e-3 sums ~1e-16 / k^2 ~ 2e-11.
      EXPECT_LT((limit - expect).norm(), 1e-8) << lattice_name(type) << " h = " << h;
      EXPECT_LT((limit - cont.M).norm() / cont.M.norm(), 0.05) << lattice_name(type) << " h = " << h;
    }
  }
}

TEST(LatticeDispersion, LatticeMomentErrorsDecayWithSmoothingLength) {
  // The moment errors |-A_x/k - 1| and |B_x/k^2 - 1| at k -> 0 oscillate in h/dp; their maximum over each
  // window [h, h + 1) falls from window to window (the lattice approaches the continuum of GMS 5.10).
  Kernel<2> w(KernelType::CubicSpline);
  const double k = 1e-4;
  for (auto type : {LatticeType::Square, LatticeType::FaceCentred}) {
    double prev_a = 1e9, prev_b = 1e9;
    for (int window = 1; window <= 5; ++window) {
      double max_a = 0, max_b = 0;
      for (double h = window; h < window + 1 - 1e-9; h += 0.05)
        for (int axis = 0; axis < 2; ++axis) {
          const Eigen::Vector2d kv = axis == 0 ? Eigen::Vector2d(k, 0) : Eigen::Vector2d(0, k);
          auto s = lattice_sums(type, w, h, kv);
          max_a = std::max(max_a, std::abs(-s.A[axis] / k - 1));
          max_b = std::max(max_b, std::abs((axis == 0 ? s.Bx : s.By) / (k * k) - 1));
        }
      SCOPED_TRACE(lattice_name(type) + " window " + std::to_string(window));
      EXPECT_LT(max_a, prev_a);
      EXPECT_LT(max_b, prev_b);
      prev_a = max_a;
      prev_b = max_b;
    }
    EXPECT_LT(prev_a, 5e-4) << lattice_name(type);  // h in [5, 6)
    EXPECT_LT(prev_b, 1e-2) << lattice_name(type);
  }
}

TEST(LatticeDispersion, PressureCancelsInLongWaveContinuum) {
  // (4.9)/(4.10) contain no P: the continuum matrix is the same for any pressure.
  UniformState a{.density = 1, .sound_speed = 1, .shear_modulus = 0.3, .pressure = 0.0, .sxx = 0.01, .syy = -0.01};
  UniformState b = a;
  b.pressure = 0.4;
  const Eigen::Vector2d k(0.3, 0.2);
  EXPECT_NEAR((continuum_dispersion(k, a).M - continuum_dispersion(k, b).M).norm(), 0.0, 1e-15);
}

TEST(LatticeDispersion, WithArtificialStressFollowsGmsRule) {
  UniformState st{.density = 1.2, .pressure = -0.05, .sxx = 0.02, .syy = -0.1};
  auto r = with_artificial_stress(st, 0.3);
  EXPECT_NEAR(r.rxx, -0.3 * 0.07 / 1.44, 1e-15);  // sigma_xx = 0.07 > 0
  EXPECT_EQ(r.ryy, 0.0);                          // sigma_yy = -0.05 < 0
}

TEST(LatticeDispersion, RejectsBadInput) {
  Kernel<2> w(KernelType::CubicSpline);
  const Eigen::Vector2d k(1, 0);
  EXPECT_THROW(lattice_sums(LatticeType::Square, w, 0.0, k), std::invalid_argument);
  EXPECT_THROW(lattice_sums(LatticeType::Square, w, -1.0, k), std::invalid_argument);
  EXPECT_THROW(lattice_sums(LatticeType::Square, w, 1.0, k, {.exponent = -1}), std::invalid_argument);
  EXPECT_THROW(lattice_sums(LatticeType::Square, w, 1.0, k, {.spacing = 0}), std::invalid_argument);
  EXPECT_THROW(lattice_sums(LatticeType::Square, w, 0.4, k), std::invalid_argument);  // W(dp) = 0
  EXPECT_THROW(lattice_sums(LatticeType::Cubic, w, 1.0, k), std::invalid_argument);
  // A support of 2e6 spacings would loop over 1.6e13 lattice points (and overflowed the int reach): refused.
  EXPECT_THROW(lattice_sums(LatticeType::Square, w, 1e6, k), std::length_error);
  EXPECT_THROW(ElasticSymbol2D(LatticeType::Square, w, 1e6, 1.0, ElasticMaterial::from_lame(1, 1, 1),
                               MomentumForm::Conservative, PreStrainKind::Isotropic),
               std::length_error);
  EXPECT_THROW(lattice_sums(LatticeType::Square, w, 1.0, Eigen::Vector2d(NAN, 0)), std::invalid_argument);
  EXPECT_THROW(lattice_dispersion(LatticeType::Square, w, 1.0, k, UniformState{.density = 0}), std::invalid_argument);
  EXPECT_THROW(lattice_dispersion(LatticeType::Square, w, 1.0, k, UniformState{.shear_modulus = -1}),
               std::invalid_argument);
  EXPECT_THROW(with_artificial_stress(UniformState{}, -0.3), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
