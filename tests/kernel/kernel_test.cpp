#include "sphstab/kernel/kernel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "sphstab/numerics/quadrature.hpp"

namespace sphstab {
namespace kernel_test {

template <int Dim>
double radial_integral(const Kernel<Dim>& k, double h) {
  const double omega = Dim == 1 ? 2.0 : Dim == 2 ? 2.0 * std::numbers::pi : 4.0 * std::numbers::pi;
  // Panels of width h/40 put every spline break (multiples of h/2 for support-2h scalings) on a panel edge.
  const double R = k.support_radius(h);
  int panels = static_cast<int>(std::ceil(R / h * 120));
  return omega *
         integrate_gauss_legendre([&](double r) { return k.value(r, h) * std::pow(r, Dim - 1); }, 0.0, R, panels);
}

template <int Dim>
void check_integral(KernelScaling scaling) {
  for (KernelType t : all_kernel_types()) {
    Kernel<Dim> k(t, scaling);
    for (double h : {0.7, 1.3}) {
      SCOPED_TRACE(kernel_name(t) + " dim " + std::to_string(Dim));
      EXPECT_NEAR(radial_integral(k, h), 1.0, 1e-10);
    }
  }
}

TEST(Kernel, IntegratesToOneInEveryDimension) {
  for (auto s : {KernelScaling::Support2h, KernelScaling::Native}) {
    check_integral<1>(s);
    check_integral<2>(s);
    check_integral<3>(s);
  }
}

TEST(Kernel, SupportIsTwoHByDefault) {
  for (KernelType t : all_kernel_types()) {
    Kernel<2> k(t);
    EXPECT_DOUBLE_EQ(k.support_radius(1.5), 3.0);
    EXPECT_EQ(k.value(3.0 + 1e-12, 1.5), 0.0);
  }
}

template <int Dim>
void check_derivatives() {
  // First and second derivatives against complex-step differentiation of value() and d1().
  const double eps = 1e-30;
  for (KernelType t : all_kernel_types()) {
    Kernel<Dim> k(t);
    const double h = 1.1;
    for (double q = 0.05; q < 2.0; q += 0.0731) {
      const double r = q * h;
      std::complex<double> rc(r, eps);
      double d1_cs = k.value(rc, h).imag() / eps;
      double d2_cs = k.d1(rc, h).imag() / eps;
      double scale1 = std::abs(k.d1(0.5 * h, h)) + 1e-300, scale2 = std::abs(k.d2(0.0, h)) + std::abs(d1_cs);
      SCOPED_TRACE(kernel_name(t) + " q=" + std::to_string(q));
      EXPECT_NEAR(k.d1(r, h), d1_cs, 1e-8 * scale1);
      if (t != KernelType::Hat) EXPECT_NEAR(k.d2(r, h), d2_cs, 1e-8 * scale2);
    }
  }
}

TEST(Kernel, DerivativesMatchComplexStep) {
  check_derivatives<1>();
  check_derivatives<2>();
  check_derivatives<3>();
}

TEST(Kernel, DerivativesMatchHighOrderFiniteDifferences) {
  // Independent of the complex-step path: 4th-order central differences, step 1e-3 h.
  for (KernelType t : all_kernel_types()) {
    Kernel<1> k(t);
    const double h = 1.0, e = 1e-3;
    for (double q : {0.3, 0.77, 1.21, 1.63}) {
      auto fd = [&](auto f) { return (-f(q + 2 * e) + 8 * f(q + e) - 8 * f(q - e) + f(q - 2 * e)) / (12 * e); };
      double d1 = fd([&](double r) { return k.value(r, h); });
      double d2 = fd([&](double r) { return k.d1(r, h); });
      SCOPED_TRACE(kernel_name(t) + " q=" + std::to_string(q));
      EXPECT_NEAR(k.d1(q, h), d1, 1e-8);
      EXPECT_NEAR(k.d2(q, h), d2, 1e-8 * (1 + std::abs(d2)));
    }
  }
}

TEST(Kernel, CubicSplineExactShapeValues) {
  Kernel<1> k(KernelType::CubicSpline);
  const double h = 1.0;
  EXPECT_DOUBLE_EQ(k.value(0.0, h), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(k.value(1.0, h), 2.0 / 3.0 * 0.25);
  EXPECT_NEAR(k.d2(2.0 / 3.0, h), 0.0, 1e-15);  // inflection at q = 2/3: f'' = -3 + 4.5 q
  EXPECT_NEAR(k.inflection_q(), 2.0 / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(k.d1(1.0, h), -2.0 / 3.0 * 0.75);
  Kernel<2> k2(KernelType::CubicSpline);
  EXPECT_DOUBLE_EQ(k2.value(0.0, 1.0), 10.0 / (7.0 * std::numbers::pi));
  Kernel<3> k3(KernelType::CubicSpline);
  EXPECT_DOUBLE_EQ(k3.value(0.0, 1.0), 1.0 / std::numbers::pi);
}

TEST(Kernel, MollifierNormalisationMatchesIsmail) {
  // Native scaling (support h): W(0) = G_d f(0) / h^d with f(0) = 1/e.
  const double expected[] = {4.809677, 8.746220, 16.32221};
  Kernel<1> k1(KernelType::ModifiedMollifier, KernelScaling::Native);
  Kernel<2> k2(KernelType::ModifiedMollifier, KernelScaling::Native);
  Kernel<3> k3(KernelType::ModifiedMollifier, KernelScaling::Native);
  EXPECT_NEAR(k1.normalisation(), expected[0], 5e-6);
  EXPECT_NEAR(k2.normalisation(), expected[1], 5e-6);
  EXPECT_NEAR(k3.normalisation(), expected[2], 5e-5);
  EXPECT_FALSE(k1.closed_form_normalisation());
}

TEST(Kernel, WendlandHasPositiveFourierTransformIn1D) {
  // F(k) = 2 int_0^R W(r) cos(k r) dr sampled on 0 <= k h <= 60: positive for Wendland, not for the cubic.
  auto min_transform = [](KernelType t) {
    Kernel<1> w(t);
    double lo = 1e300;
    for (double kk = 0.0; kk <= 60.0; kk += 0.05) {
      double f =
          2 * integrate_gauss_legendre([&](double r) { return w.value(r, 1.0) * std::cos(kk * r); }, 0.0, 2.0, 200);
      lo = std::min(lo, f);
    }
    return lo;
  };
  for (auto t : {KernelType::WendlandC2, KernelType::WendlandC4, KernelType::WendlandC6})
    EXPECT_GT(min_transform(t), 0.0) << kernel_name(t);
  // sinc^5: the quartic B-spline's transform changes sign.
  EXPECT_LT(min_transform(KernelType::QuarticSpline), 0.0);
  // Powell cites the Gaussian as positive-transform; truncating it at 2h (W jumps by ~e^-9 W(0)) breaks that
  // at high wavenumber, so the truncated Gaussian is NOT covered by Bochner's theorem.
  EXPECT_LT(min_transform(KernelType::Gaussian), 0.0);
}

TEST(Kernel, UnknownNameIsRejected) {
  EXPECT_THROW(parse_kernel_type("cubik"), std::invalid_argument);
  for (KernelType t : all_kernel_types()) EXPECT_EQ(parse_kernel_type(kernel_name(t)), t);
}

}  // namespace
}  // namespace sphstab
