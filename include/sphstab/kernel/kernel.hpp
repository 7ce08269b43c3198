#pragma once
/// \file kernel.hpp
/// Smoothing kernels W(r, h) with first and second radial derivatives in 1, 2 and 3 dimensions.
///
/// Every family is written as a shape f(s) on its native variable s (native support s_max) and evaluated at
/// s = kappa * q, q = r / h. With KernelScaling::Support2h (the default, docs/conventions.md §2) kappa = s_max / 2, so
/// every kernel vanishes at r = 2h and h/dx means the same thing for every family (Powell Fig. 3.2 uses equal
/// supports). KernelScaling::Native uses kappa = 1, the convention of the kernel's source:
///   cubic B-spline 2h, quartic 2.5h, quintic 3h (Powell A.1-A.3), Wendland and Lucy h (A.6, A.7),
///   truncated Gaussian exp(-q^2) cut at 3h (A.5), hat 2h (Powell 3.60), modified mollifier h (Ismail 2.19).
/// W = sigma_d / h^d f(kappa q), with sigma_d = kappa^d / (integral of f over R^d).
///
/// \note Wendland functions depend on the dimension: psi_{d/2+k+1,k} is positive definite only in R^d' for
///       d' <= d. 1D uses (1-s)^3(1+3s) (C2), (1-s)^5(1+5s+8s^2) (C4), (1-s)^7(1+7s+19s^2+21s^3) (C6);
///       2D and 3D use (1-s)^4(1+4s), (1-s)^6(1+6s+35/3 s^2), (1-s)^8(1+8s+25s^2+32s^3).
/// \note Lucy's kernel is (1+3s)(1-s)^3 in every dimension (equal to the 1D Wendland C2 shape).
/// \note Derivative functions are templates on the scalar so that complex-step differentiation
///       (Scalar = std::complex<double>) passes through; branches use the real part only.
#include <complex>
#include <string>
#include <vector>

#include "sphstab/numerics/real_part.hpp"

namespace sphstab {

enum class KernelType {
  CubicSpline,
  QuarticSpline,
  QuinticSpline,
  WendlandC2,
  WendlandC4,
  WendlandC6,
  Gaussian,
  Hat,
  Lucy,
  ModifiedMollifier
};

enum class KernelScaling { Support2h, Native };

/// Parses a kernel name ("cubic", "quartic", "quintic", "wendland-c2", "wendland-c4", "wendland-c6", "gaussian",
/// "hat", "lucy", "mollifier"); throws std::invalid_argument naming the valid choices otherwise.
KernelType parse_kernel_type(const std::string& name);
/// The canonical name accepted by parse_kernel_type.
std::string kernel_name(KernelType type);
/// All kernel types, in declaration order.
const std::vector<KernelType>& all_kernel_types();

/// A radial smoothing kernel in Dim dimensions (Dim = 1, 2, 3). Small value type: copy freely.
///
/// \code{.cpp}
/// sphstab::Kernel<1> w(sphstab::KernelType::CubicSpline);
/// double h = 1.3;
/// double value = w.value(0.5, h), slope = w.d1(0.5, h), curvature = w.d2(0.5, h);
/// double support = w.support_radius(h);  // 2h
/// \endcode
template <int Dim>
class Kernel {
  static_assert(Dim >= 1 && Dim <= 3, "Kernel: Dim must be 1, 2 or 3");

 public:
  explicit Kernel(KernelType type, KernelScaling scaling = KernelScaling::Support2h);

  KernelType type() const { return m_type; }
  KernelScaling scaling() const { return m_scaling; }
  /// Radius beyond which W = 0, in units of h (2 for Support2h).
  double support_factor() const { return m_support; }
  double support_radius(double h) const { return m_support * h; }
  /// sigma_d: W(0, h) = sigma_d f(0) / h^d.
  double normalisation() const { return m_sigma; }
  /// True when sigma_d is a closed-form value (false: computed by quadrature at construction).
  bool closed_form_normalisation() const { return m_closed_form; }
  /// q = r/h of the first zero of W'' on (0, support), or 0 when W'' has no sign change (hat).
  double inflection_q() const;

  /// W(r, h), r >= 0.
  template <class Scalar>
  Scalar value(const Scalar& r, double h) const {
    return m_sigma / pow_dim(h) * shape(m_kappa * r / h, 0);
  }
  /// dW/dr.
  template <class Scalar>
  Scalar d1(const Scalar& r, double h) const {
    return m_sigma / pow_dim(h) * (m_kappa / h) * shape(m_kappa * r / h, 1);
  }
  /// d^2W/dr^2.
  template <class Scalar>
  Scalar d2(const Scalar& r, double h) const {
    return m_sigma / pow_dim(h) * (m_kappa / h) * (m_kappa / h) * shape(m_kappa * r / h, 2);
  }

  /// Native shape derivative f^(order)(s), order 0, 1, 2, in the native variable s.
  template <class Scalar>
  Scalar shape(const Scalar& s, int order) const;

 private:
  static double pow_dim(double h) { return Dim == 1 ? h : (Dim == 2 ? h * h : h * h * h); }

  KernelType m_type;
  KernelScaling m_scaling;
  double m_native_support = 0;  // s_max
  double m_kappa = 1;           // s = kappa q
  double m_support = 2;         // support radius / h
  double m_sigma = 1;
  bool m_closed_form = true;
};

}  // namespace sphstab

#include "sphstab/kernel/kernel_shapes.hpp"
