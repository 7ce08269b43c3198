#include "sphstab/kernel/kernel.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sphstab/core/named_values.hpp"
#include "sphstab/numerics/instantiation.hpp"
#include "sphstab/numerics/quadrature.hpp"

namespace sphstab {

namespace {

constexpr NamedValue<KernelType> kKernels[] = {
    {KernelType::CubicSpline, "cubic"},
    {KernelType::QuarticSpline, "quartic"},
    {KernelType::QuinticSpline, "quintic"},
    {KernelType::WendlandC2, "wendland-c2"},
    {KernelType::WendlandC4, "wendland-c4"},
    {KernelType::WendlandC6, "wendland-c6"},
    {KernelType::Gaussian, "gaussian"},
    {KernelType::Hat, "hat"},
    {KernelType::Lucy, "lucy"},
    {KernelType::ModifiedMollifier, "mollifier"},
};

double native_support(KernelType type) {
  switch (type) {
    case KernelType::CubicSpline:
    case KernelType::Hat:
      return 2.0;
    case KernelType::QuarticSpline:
      return 2.5;
    case KernelType::QuinticSpline:
    case KernelType::Gaussian:
      return 3.0;
    default:
      return 1.0;
  }
}

/// Native scaling of each family: W = sigma f(r/h)/h^d with support native_support * h, except the hat,
/// whose native variable is s = r/(2h) (Powell 3.60), i.e. native support 2h with s_max = 1.
double native_kappa(KernelType type) { return type == KernelType::Hat ? 0.5 : 1.0; }

/// Closed-form 1 / (integral of f over R^d) in the native variable, where one exists; 0 otherwise.
double closed_form_inverse_integral(KernelType type, int dim) {
  using std::numbers::pi;
  switch (type) {
    case KernelType::CubicSpline:
      return dim == 1 ? 2.0 / 3.0 : dim == 2 ? 10.0 / (7.0 * pi) : 1.0 / pi;
    case KernelType::QuarticSpline:
      return dim == 1 ? 1.0 / 24.0 : dim == 2 ? 96.0 / (1199.0 * pi) : 1.0 / (20.0 * pi);
    case KernelType::QuinticSpline:
      return dim == 1 ? 1.0 / 120.0 : dim == 2 ? 7.0 / (478.0 * pi) : 1.0 / (120.0 * pi);
    case KernelType::WendlandC2:
      return dim == 1 ? 5.0 / 4.0 : dim == 2 ? 7.0 / pi : 21.0 / (2.0 * pi);
    case KernelType::WendlandC4:
      return dim == 1 ? 3.0 / 2.0 : dim == 2 ? 9.0 / pi : 495.0 / (32.0 * pi);
    case KernelType::WendlandC6:
      return dim == 1 ? 55.0 / 32.0 : dim == 2 ? 78.0 / (7.0 * pi) : 1365.0 / (64.0 * pi);
    case KernelType::Lucy:
      return dim == 1 ? 5.0 / 4.0 : dim == 2 ? 5.0 / pi : 105.0 / (16.0 * pi);
    case KernelType::Hat:  // 1 - s on s < 1: integrals 1, pi/3, pi/3
      return dim == 1 ? 1.0 : 3.0 / pi;
    default:
      return 0.0;  // truncated Gaussian and mollifier: computed
  }
}

}  // namespace

KernelType parse_kernel_type(const std::string& name) { return parse_named(name, kKernels, "kernel"); }
std::string kernel_name(KernelType type) { return name_of(type, kKernels); }
const std::vector<KernelType>& all_kernel_types() {
  static const std::vector<KernelType> types = values_of(kKernels);
  return types;
}

template <int Dim>
Kernel<Dim>::Kernel(KernelType type, KernelScaling scaling) : m_type(type), m_scaling(scaling) {
  m_native_support = type == KernelType::Hat ? 1.0 : native_support(type);
  // s = kappa q: Support2h puts the end of the native support at q = 2.
  m_kappa = scaling == KernelScaling::Support2h ? m_native_support / 2.0 : native_kappa(type);
  m_support = m_native_support / m_kappa;
  double inverse = closed_form_inverse_integral(type, Dim);
  m_closed_form = inverse > 0.0;
  if (!m_closed_form) {
    // Radial integral of f over R^d: omega_d * int_0^smax f(s) s^(d-1) ds.
    const double omega = Dim == 1 ? 2.0 : Dim == 2 ? 2.0 * std::numbers::pi : 4.0 * std::numbers::pi;
    double integral = omega * integrate_gauss_legendre([&](double s) { return shape(s, 0) * std::pow(s, Dim - 1); },
                                                       0.0, m_native_support, 400);
    inverse = 1.0 / integral;
  }
  m_sigma = inverse * std::pow(m_kappa, Dim);
}

template <int Dim>
double Kernel<Dim>::inflection_q() const {
  // First sign change of f'' on (0, s_max), refined by bisection; f'' of the hat is 0 everywhere.
  const int samples = 4000;
  double prev_s = 1e-9, prev = shape(prev_s, 2);
  for (int k = 1; k <= samples; ++k) {
    double s = m_native_support * k / samples * (1.0 - 1e-12);
    double v = shape(s, 2);
    if (prev != 0.0 && v != 0.0 && (prev < 0) != (v < 0)) {
      double a = prev_s, b = s;
      for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
        double m = 0.5 * (a + b);
        if ((shape(m, 2) < 0) == (prev < 0))
          a = m;
        else
          b = m;
      }
      return 0.5 * (a + b) / m_kappa;
    }
    prev_s = s;
    prev = v;
  }
  return 0.0;
}

#define SPHSTAB_INSTANTIATE(D) template class Kernel<D>;
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
