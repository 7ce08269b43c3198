#pragma once
/// \file pair_lanes.hpp
/// Internal to src/forms: the pair loop's per-pair scalars of one row (pair_loop.hpp) as whole-row vector loops,
/// compiled twice: for the x86-64 baseline (SSE2, 2 pairs per vector) and for AVX2 (4 pairs per vector), the clone
/// chosen at run time (core/simd_dispatch.hpp). From the squared distances r2 (and v_ij . r_ij, rho_j):
///   W and dW/dr / r of the cubic spline (kernel_rows.hpp, CubicFunctions::row_pairs),
///   f^n = (W (1 / W(dp)))^4 for GMS's n = 4 (artificial_stress.hpp, PairFactor::row_by_reciprocal),
///   1 / rhobar_ij = 2 / (rho_i + rho_j), and Pi_ij / rhobar_ij (pair_viscosity.hpp).
/// Every lane does the operations of those functions' scalar code, in the same order, and no multiply-add is formed
/// (the clone enables AVX2, not FMA). So both builds give those functions' bits (tests/forms/
/// threads_determinism_test.cpp runs both).
///
/// One body (pair_lanes_body.hpp) is included twice, in a namespace per instruction set; the AVX2 copy inside a
/// region that gives every function defined there the target attribute (GCC's target pragma, Clang's attribute
/// region), so that 4-wide vectors are only ever passed between AVX2 functions.
#include <cmath>
#include <cstddef>
#include <cstring>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "always_inline.hpp"
#include "sphstab/core/simd_dispatch.hpp"
#include "sphstab/forms/rate_form.hpp"

namespace sphstab::rate_form_detail {

/// The constants of one evaluation.
struct PairLaneConstants {
  double inv_h = 0, cw = 0, cd_h = 0, cd_out = 0;  // CubicFunctions::row_pairs: 1 / h, c_w, c_d / h, -0.75 c_d
  double inv_w_dp = 0;                             // 1 / W(dp), for f^4
  double h = 0, eta2 = 0, alpha_c0 = 0, beta = 0;  // the viscosity (pair_viscosity.hpp)
};

/// One row's arrays: `len` pairs in, the scalars out (f: with the artificial stress; ib: with viscosity or XSPH; c:
/// with viscosity). Every array holds len rounded up to a multiple of kMaxPairLanes: the last vector reads and writes
/// its lanes past len too (whatever they hold, finite or not; their results are not read), which keeps a row's tail
/// in registers (a padded copy through the stack stalled on store forwarding: a fifth of these loops' time).
inline constexpr std::size_t kMaxPairLanes = 4;
struct PairLaneRow {
  std::size_t len = 0;
  double rho_i = 0;
  const double *r2 = nullptr, *vr = nullptr, *rhoj = nullptr;
  double *w = nullptr, *gf = nullptr, *f = nullptr, *ib = nullptr, *c = nullptr;
};

namespace lanes {
using v2d = double __attribute__((vector_size(16)));
using v2l = long long __attribute__((vector_size(16)));
using v4d = double __attribute__((vector_size(32)));
using v4l = long long __attribute__((vector_size(32)));
}  // namespace lanes

namespace pair_lanes_baseline {
using V = lanes::v2d;
using Mask = lanes::v2l;
SPHSTAB_ALWAYS_INLINE inline V vsqrt(V x) {
#if defined(__SSE2__)
  return reinterpret_cast<V>(_mm_sqrt_pd(reinterpret_cast<__m128d>(x)));
#else
  return V{std::sqrt(x[0]), std::sqrt(x[1])};
#endif
}
#include "pair_lanes_body.hpp"
}  // namespace pair_lanes_baseline

#if SPHSTAB_HAS_AVX2_CLONES
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
namespace pair_lanes_avx2 {
using V = lanes::v4d;
using Mask = lanes::v4l;
SPHSTAB_ALWAYS_INLINE inline V vsqrt(V x) { return reinterpret_cast<V>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(x))); }
#include "pair_lanes_body.hpp"
}  // namespace pair_lanes_avx2
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#endif

/// The row's scalars by the clone `avx2` names (true only where SPHSTAB_HAS_AVX2_CLONES and avx2_enabled()).
template <ViscositySwitch kViscosity, bool kStress, bool kXsph>
inline void pair_lanes(bool avx2, const PairLaneConstants& k, const PairLaneRow& row) {
#if SPHSTAB_HAS_AVX2_CLONES
  if (avx2) return pair_lanes_avx2::row<kViscosity, kStress, kXsph>(k, row);
#else
  (void)avx2;
#endif
  pair_lanes_baseline::row<kViscosity, kStress, kXsph>(k, row);
}

}  // namespace sphstab::rate_form_detail
