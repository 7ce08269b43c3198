#include "sphstab/spectral/rate_form_symbol.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "../forms/forms_fixture.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"
#include "sphstab/spectral/lattice_dispersion.hpp"

namespace sphstab {
namespace rate_form_symbol_test {

using test::kGms;

template <int Dim>
RateFormScheme<Dim> periodic_scheme(int n, double h, const RateFormOptions& o, double xi, LatticeType type,
                                    const Eigen::VectorXd& deviator = {}) {
  const auto disc = test::lattice_discretisation<Dim>({.n = n, .h = h, .type = type, .periodic = true});
  return RateFormScheme<Dim>(disc, kGms, o, kGms.density() / xi, deviator);
}

/// Every eigenvalue of the periodic lattice's whole J is an eigenvalue of the symbol at one of the box's wavevectors
/// and vice versa (the acoustic ones to 1e-9; the zero ones by count: the dense route splits their Jordan blocks).
template <int Dim>
void expect_symbols_tile_the_dense_spectrum(const RateFormScheme<Dim>& scheme, int n) {
  const Eigen::VectorXd y = scheme.uniform_state();
  const RateFormSymbol<Dim> symbol = rate_form_symbol(scheme, y);
  EXPECT_LT(symbol.invariance_residual, 1e-14);
  const Eigen::MatrixXd J = Eigen::MatrixXd(jacobian(scheme, y));
  const Eigen::VectorXcd dense = Eigen::EigenSolver<Eigen::MatrixXd>(J, false).eigenvalues();
  const double scale = dense.cwiseAbs().maxCoeff(), zero = 1e-5 * scale;
  std::vector<std::complex<double>> from_symbols;
  const double L = scheme.discretisation().particles.box_length()[0];
  for (int mx = 0; mx < n; ++mx)
    for (int my = 0; my < (Dim == 2 ? n : 1); ++my) {
      typename RateFormSymbol<Dim>::Wavevector k;
      k[0] = 2 * M_PI * mx / L;
      if constexpr (Dim == 2) k[1] = 2 * M_PI * my / scheme.discretisation().particles.box_length()[1];
      const RateFormDispersion d = rate_form_dispersion(symbol, k);
      for (int i = 0; i < d.lambda.size(); ++i) from_symbols.push_back(d.lambda[i]);
    }
  ASSERT_EQ(static_cast<Eigen::Index>(from_symbols.size()), dense.size());
  int zeros_dense = 0, zeros_symbol = 0;
  double worst = 0;
  for (int i = 0; i < dense.size(); ++i) {
    if (std::abs(dense[i]) < zero) ++zeros_dense;
    if (std::abs(from_symbols[i]) < zero) ++zeros_symbol;
  }
  for (const auto& l : from_symbols) {
    if (std::abs(l) < zero) continue;
    double best = 1e300;
    for (int i = 0; i < dense.size(); ++i) best = std::min(best, std::abs(dense[i] - l));
    worst = std::max(worst, best);
  }
  for (int i = 0; i < dense.size(); ++i) {
    if (std::abs(dense[i]) < zero) continue;
    double best = 1e300;
    for (const auto& l : from_symbols) best = std::min(best, std::abs(dense[i] - l));
    worst = std::max(worst, best);
  }
  EXPECT_EQ(zeros_dense, zeros_symbol);
  EXPECT_LT(worst, 1e-9 * scale);
}

TEST(RateFormSymbol, SymbolsAtTheBoxWavevectorsTileTheDenseSpectrum1D) {
  for (double xi : {0.97, 1.03}) {
    expect_symbols_tile_the_dense_spectrum(periodic_scheme<1>(16, 1.3, {}, xi, LatticeType::Line), 16);
    expect_symbols_tile_the_dense_spectrum(
        periodic_scheme<1>(
            20, 1.7,
            {.xsph = 0.5, .viscosity = ViscositySwitch::Always, .viscosity_alpha = 0.3, .artificial_stress = 0.3}, xi,
            LatticeType::Line),
        20);
  }
}

TEST(RateFormSymbol, SymbolsAtTheBoxWavevectorsTileTheDenseSpectrum2D) {
  Eigen::VectorXd dev(3);
  dev << 0.004, -0.002, 0.001;
  // Boxes of 10 (XSPH's two supports, the smallest allowed) and 8 (NCSPH without XSPH: one support and its
  // correction's): the dense spectrum is O(N^3), so the smallest boxes keep the test short under the sanitizers.
  expect_symbols_tile_the_dense_spectrum(
      periodic_scheme<2>(10, 1.3, {.xsph = 0.5, .artificial_stress = 0.3}, 1.02, LatticeType::Square, dev), 10);
  expect_symbols_tile_the_dense_spectrum(
      periodic_scheme<2>(8, 1.2, {.gradient = RateFormGradient::Ncsph}, 0.98, LatticeType::Square, dev), 8);
}

TEST(RateFormSymbol, IndependentOfTheBoxAtAnyWavevector) {
  Eigen::VectorXd dev(3);
  dev << 0.01, -0.003, 0.002;
  const RateFormOptions o{.xsph = 0.5, .artificial_stress = 0.3, .gradient = RateFormGradient::Ncsph};
  const auto a = periodic_scheme<2>(14, 1.3, o, 1.03, LatticeType::Hexagonal, dev);
  const auto b = periodic_scheme<2>(18, 1.3, o, 1.03, LatticeType::Hexagonal, dev);
  const auto sa = rate_form_symbol(a, a.uniform_state()), sb = rate_form_symbol(b, b.uniform_state());
  for (const Eigen::Vector2d k : {Eigen::Vector2d(0.37, 1.91), Eigen::Vector2d(2.9, -0.4), Eigen::Vector2d(1e-3, 0)}) {
    const Eigen::MatrixXcd ja = sa.at(k), jb = sb.at(k);
    EXPECT_LT((ja - jb).cwiseAbs().maxCoeff(), 1e-13 * ja.cwiseAbs().maxCoeff()) << k.transpose();
  }
}

TEST(RateFormSymbol, RefusesABoxSmallerThanTheStencilAndNonPeriodicLattices) {
  // Plain SPH couples one support (2.6 dx: offsets up to 2 dx), so a box of 6 holds it (the neighbour search refuses
  // smaller ones); XSPH couples two supports (offsets up to 4 dx per axis): a box of 10 holds it, in a box of 8 or 7
  // the particle at offset 4 is also at -4 or -3 and couples through both images.
  for (auto [n, xsph, ok] : {std::tuple{6, 0.0, true}, {10, 0.5, true}, {8, 0.5, false}, {7, 0.5, false}}) {
    const auto s = periodic_scheme<2>(n, 1.3, {.xsph = xsph}, 1.0, LatticeType::Square);
    if (ok)
      EXPECT_NO_THROW(rate_form_symbol(s, s.uniform_state())) << n;
    else
      EXPECT_THROW(rate_form_symbol(s, s.uniform_state()), std::invalid_argument) << n;
  }
  const auto block = RateFormScheme<1>(test::lattice_discretisation<1>({.n = 20, .h = 1.3}), kGms);
  EXPECT_THROW(rate_form_symbol(block, block.uniform_state()), std::invalid_argument);
  const auto ok = periodic_scheme<1>(16, 1.3, {}, 1.0, LatticeType::Line);
  Eigen::VectorXd y = ok.uniform_state();
  y[ok.density_offset(3)] *= 1.01;  // not uniform
  EXPECT_THROW(rate_form_symbol(ok, y), std::invalid_argument);
}

TEST(RateFormSymbol, OneDimensionalPlainSphIsTheInitialStressForm) {
  // 1D plain SPH at rest, derived by hand: with V = m/rho, a = sum_j G_0j e^{ik d_j}, l = sum_j W''(d_j)(1 - cos k
  // d_j), drho = -rho V a u, dsigma = V a (K rho/rho0 + 4mu/3) u and the momentum's 1/rho^2 and dG_ij terms,
  //   rho omega^2 = (K rho/rho0 + 4mu/3 + 2 sigma0)|g|^2 - 2 sigma0 L = (M + sigma0)|g|^2 - 2 sigma0 L,
  // M = K + 4mu/3, sigma0 = -p (tension positive), g and L the lattice symbols of fourier_symbol.hpp: the 1D
  // initial-stress form of rate_form_critical_stress.hpp.
  const Kernel<1> w(KernelType::CubicSpline);
  for (double h : {1.3, 1.7})
    for (double xi : {0.96, 1.04}) {
      const auto scheme = periodic_scheme<1>(20, h, {}, xi, LatticeType::Line);
      const auto symbol = rate_form_symbol(scheme, scheme.uniform_state());
      const double rho = kGms.density() / xi, p = kGms.bulk_modulus() * (rho / kGms.density() - 1), sigma0 = -p;
      const double M = kGms.bulk_modulus() + 4 * kGms.mu() / 3;
      for (double k : {0.1, 0.9, 1.7, 2.6, M_PI}) {
        const auto d = rate_form_dispersion(symbol, Eigen::Matrix<double, 1, 1>(k));
        const FourierSymbol1D f = fourier_symbol_1d(w, h, 1.0, k);
        const double expected = ((M + sigma0) * f.g_abs2 - 2 * sigma0 * f.l_hat) / rho;
        EXPECT_NEAR(d.omega2[0].real(), expected, 1e-12 * (M + std::abs(sigma0)) * 4) << h << " " << xi << " " << k;
        EXPECT_NEAR(d.omega2[0].imag(), 0.0, 1e-14);
        EXPECT_LT(d.slaved_lambda, 1e-12);
        EXPECT_LT(d.structure_residual, 1e-15);
      }
    }
}

TEST(RateFormSymbol, GmsTermsGiveTheirDispersionRelation) {
  // XSPH 1/2, summation continuity, Jaumann rate, artificial stress 0.3, n = 4: GMS (5.8)/(5.9) with the
  // perturbed artificial stress (lattice_dispersion.hpp, derived independently) on square and face-centred lattices.
  const Kernel<2> w(KernelType::CubicSpline);
  for (LatticeType type : {LatticeType::Square, LatticeType::FaceCentred})
    for (double h : {1.2, 1.5}) {
      Eigen::VectorXd dev(3);
      dev << 0.006, -0.004, 0.0;
      const double xi = 1.03, rho = kGms.density() / xi;
      // A box of 12, the smallest that holds XSPH's two supports at h = 1.5 (2 x 2.0 x 1.5 dx, plus the face-centred
      // lattice's half offset): the symbol does not depend on the box (IndependentOfTheBoxAtAnyWavevector).
      const auto scheme = periodic_scheme<2>(12, h, {.xsph = 0.5, .artificial_stress = 0.3}, xi, type, dev);
      const auto symbol = rate_form_symbol(scheme, scheme.uniform_state());
      UniformState st{.density = rho,
                      .sound_speed = std::sqrt(kGms.bulk_modulus() / kGms.density()),
                      .shear_modulus = kGms.mu(),
                      .pressure = kGms.bulk_modulus() * (rho / kGms.density() - 1),
                      .sxx = dev[0],
                      .syy = dev[1]};
      st = with_artificial_stress(st, 0.3);
      for (const Eigen::Vector2d k : {Eigen::Vector2d(M_PI, 0), Eigen::Vector2d(0.4, 1.3), Eigen::Vector2d(2.2, 2.9),
                                      Eigen::Vector2d(0.05, 0.02)}) {
        const auto gms = lattice_dispersion(type, w, h, k, st, {.exponent = 4, .perturbed_artificial_stress = true});
        const auto d = rate_form_dispersion(symbol, k);
        std::array<double, 2> a{gms.omega2[0].real(), gms.omega2[1].real()};
        std::sort(a.begin(), a.end(), std::greater<>());
        const double scale = std::abs(a[0]) + std::abs(a[1]);
        EXPECT_NEAR(d.omega2[0].real(), a[0], 1e-10 * scale)
            << lattice_name(type) << " h " << h << " k " << k.transpose();
        EXPECT_NEAR(d.omega2[1].real(), a[1], 1e-10 * scale)
            << lattice_name(type) << " h " << h << " k " << k.transpose();
      }
    }
}

TEST(RateFormSymbol, LongWavesTendToTheContinuumAtSecondOrder) {
  // NCSPH's gradient is exact for linear fields, so its long-wave limit is the continuum GMS (4.9)/(4.10) with the
  // prestress (zeta != 0), and the error falls as k^2.
  Eigen::VectorXd dev(3);
  dev << 0.01, -0.006, 0.0;
  const double xi = 1.02, rho = kGms.density() / xi;
  const auto scheme = periodic_scheme<2>(16, 1.3, {.gradient = RateFormGradient::Ncsph}, xi, LatticeType::Square, dev);
  const auto symbol = rate_form_symbol(scheme, scheme.uniform_state());
  const UniformState st{.density = rho,
                        .sound_speed = std::sqrt(kGms.bulk_modulus() / kGms.density()),
                        .shear_modulus = kGms.mu(),
                        .pressure = kGms.bulk_modulus() * (rho / kGms.density() - 1),
                        .sxx = dev[0],
                        .syy = dev[1]};
  const Eigen::Vector2d dir = Eigen::Vector2d(2, 1).normalized();
  std::array<double, 2> err{};
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d k = (i == 0 ? 0.04 : 0.02) * dir;
    const auto c = continuum_dispersion(k, st);
    std::array<double, 2> a{c.omega2[0].real(), c.omega2[1].real()};
    std::sort(a.begin(), a.end(), std::greater<>());
    const auto d = rate_form_dispersion(symbol, k);
    err[i] = std::max(std::abs(d.omega2[0].real() - a[0]), std::abs(d.omega2[1].real() - a[1])) / a[0];
  }
  EXPECT_LT(err[1], 1e-3);
  EXPECT_NEAR(std::log2(err[0] / err[1]), 2.0, 0.1) << err[0] << " " << err[1];
}

}  // namespace
}  // namespace sphstab
