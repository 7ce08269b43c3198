#pragma once
/// \file kernel_rows.hpp
/// Internal to src/forms: the rate-form scheme's whole-row kernel functions (W and dW/dr / r of a row of radii: the
/// cubic spline written out and vectorised, the kernel's own functions otherwise). Shared by the row loop
/// (plain_rows.hpp) and the pair loop (pair_loop.hpp).
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "always_inline.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/kernel/kernel_shapes.hpp"
#include "sphstab/numerics/real_part.hpp"

namespace sphstab::rate_form_detail {

/// W(r) and dW/dr(r) / r of a row of radii through the kernel's own functions.
template <int Dim>
struct KernelFunctions {
  const Kernel<Dim>& kernel;
  double h;
  /// w[q] = W(r[q]) for q < len.
  template <class Scalar>
  void row_values(std::size_t len, const Scalar* r, Scalar* w) const {
    for (std::size_t q = 0; q < len; ++q) w[q] = kernel.value(r[q], h);
  }
  /// gf[q] = (dW/dr)(r[q]) / r[q], and w[q] = W(r[q]) when Value.
  template <bool Value, class Scalar>
  void row_slopes(std::size_t len, const Scalar* r, Scalar* w, Scalar* gf) const {
    for (std::size_t q = 0; q < len; ++q) {
      if constexpr (Value) w[q] = kernel.value(r[q], h);
      gf[q] = kernel.d1(r[q], h) / r[q];
    }
  }
};

/// The cubic spline's Kernel::value and Kernel::d1 written out (kernel.hpp, kernel_shapes.hpp: the CubicSpline branch
/// of Kernel::shape, kappa = 1 and native support 2 in both scalings), the same operations, without the family switch
/// and with W and dW/dr from one s = r / h.
template <int Dim>
class CubicFunctions {
 public:
  CubicFunctions(const Kernel<Dim>& kernel, double h)
      : m_h(h),
        m_cw(kernel.normalisation() / (Dim == 1 ? h : (Dim == 2 ? h * h : h * h * h))),
        m_cd(m_cw * (1.0 / h)) {}
  /// w[q] = W(r[q]) for q < len.
  template <class Scalar>
  void row_values(std::size_t len, const Scalar* r, Scalar* w) const {
    if constexpr (std::is_same_v<Scalar, double>) {
      row_real<true, false>(len, r, w, nullptr);
    } else {
      Scalar dw;
      for (std::size_t q = 0; q < len; ++q) eval<true, false>(r[q], w[q], dw);
    }
  }
  /// gf[q] = (dW/dr)(r[q]) / r[q], and w[q] = W(r[q]) when Value.
  template <bool Value, class Scalar>
  SPHSTAB_ALWAYS_INLINE void row_slopes(std::size_t len, const Scalar* r, Scalar* w, Scalar* gf) const {
    if constexpr (std::is_same_v<Scalar, double>) {
      row_real<Value, true>(len, r, w, gf);
    } else {
      for (std::size_t q = 0; q < len; ++q) {
        Scalar wq, dw;
        eval<Value, true>(r[q], wq, dw);
        if constexpr (Value) w[q] = wq;
        gf[q] = dw / r[q];
      }
    }
  }

 private:
  /// eval() on real r[q] >= +0 (square roots): s = r / h >= +0 or NaN, so the branch on the sign of s is never taken
  /// and the sign factors are 1 (1 * f = f). Both pieces are computed and one is selected (the values of eval()'s
  /// branches, NaN included: it fails both tests, as there), two pairs at a time with SSE2 (the same IEEE operations
  /// per lane).
  template <bool Value, bool Slope>
  SPHSTAB_ALWAYS_INLINE void row_real(std::size_t len, const double* __restrict r, double* __restrict w,
                                      double* __restrict gf) const {
    const double h = m_h, cw = m_cw, cd = m_cd;
    std::size_t q = 0;
#if defined(__SSE2__)
    const __m128d vh = _mm_set1_pd(h), two = _mm_set1_pd(2.0), one = _mm_set1_pd(1.0);
    for (; q + 2 <= len; q += 2) {
      const __m128d rq = _mm_loadu_pd(r + q), s = _mm_div_pd(rq, vh), a = _mm_sub_pd(two, s);
      // s >= 2 and s < 1: a NaN lane is neither (the outer piece, as in eval()).
      const __m128d outside = _mm_cmpge_pd(s, two), near = _mm_cmplt_pd(s, one), aa = _mm_mul_pd(a, a);
      if constexpr (Value) {
        // 1 - 1.5 s s + 0.75 s s s = (1 - (1.5 s) s) + ((0.75 s) s) s; 0.25 (a (a a))
        const __m128d inner = _mm_add_pd(_mm_sub_pd(one, _mm_mul_pd(_mm_mul_pd(_mm_set1_pd(1.5), s), s)),
                                         _mm_mul_pd(_mm_mul_pd(_mm_mul_pd(_mm_set1_pd(0.75), s), s), s));
        const __m128d outer = _mm_mul_pd(_mm_set1_pd(0.25), _mm_mul_pd(a, aa));
        const __m128d f = _mm_andnot_pd(outside, _mm_or_pd(_mm_and_pd(near, inner), _mm_andnot_pd(near, outer)));
        _mm_storeu_pd(w + q, _mm_mul_pd(_mm_set1_pd(cw), f));
      }
      if constexpr (Slope) {
        // -3 s + 2.25 s s = (-3 s) + (2.25 s) s; 0.25 (-3 (a a))
        const __m128d inner =
            _mm_add_pd(_mm_mul_pd(_mm_set1_pd(-3.0), s), _mm_mul_pd(_mm_mul_pd(_mm_set1_pd(2.25), s), s));
        const __m128d outer = _mm_mul_pd(_mm_set1_pd(0.25), _mm_mul_pd(_mm_set1_pd(-3.0), aa));
        const __m128d f = _mm_andnot_pd(outside, _mm_or_pd(_mm_and_pd(near, inner), _mm_andnot_pd(near, outer)));
        _mm_storeu_pd(gf + q, _mm_div_pd(_mm_mul_pd(_mm_set1_pd(cd), f), rq));
      }
    }
#endif
    for (; q < len; ++q) {
      double wq, dw;
      eval<Value, Slope>(r[q], wq, dw);
      if constexpr (Value) w[q] = wq;
      if constexpr (Slope) gf[q] = dw / r[q];
    }
  }

  template <bool Value, bool Slope, class Scalar>
  void eval(const Scalar& r, Scalar& w, Scalar& dw) const {
    constexpr double kappa = 1.0;
    const Scalar s_in = kappa * r / m_h;
    const double sr = detail::re(s_in);
    const Scalar s = sr < 0 ? Scalar(-s_in) : s_in;
    const double sign = sr < 0 ? -1.0 : 1.0;  // of the odd derivative; the value's sign is 1
    const double x = std::abs(sr);
    if (x >= 2.0) {
      if constexpr (Value) w = m_cw * Scalar(0.0);
      if constexpr (Slope) dw = m_cd * Scalar(0.0);
      return;
    }
    Scalar f0 = 0.0, f1 = 0.0;
    if (x < 1.0) {
      if constexpr (Value) f0 = 1.0 - 1.5 * s * s + 0.75 * s * s * s;
      if constexpr (Slope) f1 = -3.0 * s + 2.25 * s * s;
    } else {
      if constexpr (Value) f0 = 0.25 * detail::power_term(Scalar(2.0 - s), 3, 0);
      if constexpr (Slope) f1 = 0.25 * detail::power_term(Scalar(2.0 - s), 3, 1);
    }
    if constexpr (Value) w = m_cw * (1.0 * f0);
    if constexpr (Slope) dw = m_cd * (sign * f1);
  }

  double m_h, m_cw, m_cd;

 public:
  /// row_pairs()'s constants: 1 / h, c_w, c_d / h, -0.75 c_d (pair_lanes.hpp computes the same values by lanes).
  std::array<double, 4> pair_constants() const {
    const double inv_h = 1.0 / m_h;
    return {inv_h, m_cw, m_cd * inv_h, -0.75 * m_cd};
  }

  /// W and dW/dr / r for the pair loop (pair_loop.hpp), within rounding of row_slopes<true>(), not bitwise:
  /// s = r (1/h), and dW/dr / r = (c_d / h)(-3 + 2.25 s) on the inner piece (no division), -0.75 c_d (2 - s)^2 / r on
  /// the outer one. r[q] >= 0; r = 0 gives the inner piece's finite limit.
  void row_pairs(std::size_t len, const double* __restrict r, double* __restrict w, double* __restrict gf) const {
    const auto [inv_h, cw, cd_h, cd_out] = pair_constants();
    std::size_t q = 0;
#if defined(__SSE2__)
    const __m128d vinv_h = _mm_set1_pd(inv_h), two = _mm_set1_pd(2.0), one = _mm_set1_pd(1.0);
    for (; q + 2 <= len; q += 2) {
      const __m128d rq = _mm_loadu_pd(r + q), s = _mm_mul_pd(rq, vinv_h), a = _mm_sub_pd(two, s);
      const __m128d outside = _mm_cmpge_pd(s, two), near = _mm_cmplt_pd(s, one), aa = _mm_mul_pd(a, a),
                    ss = _mm_mul_pd(s, s);
      const __m128d w_in = _mm_add_pd(_mm_sub_pd(one, _mm_mul_pd(_mm_set1_pd(1.5), ss)),
                                      _mm_mul_pd(_mm_mul_pd(_mm_set1_pd(0.75), ss), s));
      const __m128d w_out = _mm_mul_pd(_mm_set1_pd(0.25), _mm_mul_pd(a, aa));
      const __m128d wf = _mm_andnot_pd(outside, _mm_or_pd(_mm_and_pd(near, w_in), _mm_andnot_pd(near, w_out)));
      _mm_storeu_pd(w + q, _mm_mul_pd(_mm_set1_pd(cw), wf));
      const __m128d g_in =
          _mm_mul_pd(_mm_set1_pd(cd_h), _mm_add_pd(_mm_set1_pd(-3.0), _mm_mul_pd(_mm_set1_pd(2.25), s)));
      const __m128d g_out = _mm_div_pd(_mm_mul_pd(_mm_set1_pd(cd_out), aa), rq);
      _mm_storeu_pd(gf + q, _mm_andnot_pd(outside, _mm_or_pd(_mm_and_pd(near, g_in), _mm_andnot_pd(near, g_out))));
    }
#endif
    for (; q < len; ++q) {
      const double s = r[q] * inv_h, a = 2.0 - s;
      if (s >= 2.0) {
        w[q] = gf[q] = 0.0;
      } else if (s < 1.0) {
        w[q] = cw * ((1.0 - 1.5 * (s * s)) + (0.75 * (s * s)) * s);
        gf[q] = cd_h * (-3.0 + 2.25 * s);
      } else {
        w[q] = cw * (0.25 * (a * (a * a)));
        gf[q] = cd_out * (a * a) / r[q];
      }
    }
  }
};

/// KernelFunctions' row_pairs: its row_slopes<true>().
template <int Dim>
void row_pairs(const KernelFunctions<Dim>& kf, std::size_t len, const double* r, double* w, double* gf) {
  kf.template row_slopes<true>(len, r, w, gf);
}
template <int Dim>
void row_pairs(const CubicFunctions<Dim>& kf, std::size_t len, const double* r, double* w, double* gf) {
  kf.row_pairs(len, r, w, gf);
}

/// Calls body(functions) with the kernel's W, dW/dr: written out for the cubic spline, the kernel's own otherwise.
template <int Dim, class Body>
void with_kernel_functions(const Kernel<Dim>& kernel, double h, Body&& body) {
  if (kernel.type() == KernelType::CubicSpline)
    body(CubicFunctions<Dim>(kernel, h));
  else
    body(KernelFunctions<Dim>{kernel, h});
}

}  // namespace sphstab::rate_form_detail
