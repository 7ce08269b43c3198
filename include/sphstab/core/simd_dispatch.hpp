#pragma once
/// \file simd_dispatch.hpp
/// Runtime choice between a hot loop's portable build and its AVX2 clone. The library is compiled for the x86-64
/// baseline (SSE2: 2 doubles per vector; no -march, so one binary runs on any x86-64 machine); a loop that is
/// compute-bound on whole-grid arrays is compiled a second time for AVX2 (4 doubles per vector) by a function target
/// attribute (SPHSTAB_TARGET_AVX2), and avx2_enabled() picks the clone at run time.
///
/// The clones enable AVX2 only, not FMA: no multiply-add is contracted, and a vectorised loop does in every lane the
/// operations a scalar iteration does, in the same order. So both builds give the same bits (tested by running both:
/// tests/jacobian/matrix_free_linearisation_test.cpp). Only loops over plain arrays are cloned: Eigen's fixed-size
/// types keep the alignment and packet size of the baseline build (an object compiled whole with -mavx2 would not
/// link safely with the rest).
namespace sphstab {

/// True when the CPU and the operating system support AVX2, the environment does not set SPHSTAB_SIMD=baseline (read
/// once; "auto" or unset: the CPU decides; another value is named on stderr and ignored) and no PortableSimdGuard is
/// alive.
bool avx2_enabled();

/// Forces the portable loops while alive (for tests comparing the two builds; not thread-safe against running loops).
class PortableSimdGuard {
 public:
  PortableSimdGuard();
  ~PortableSimdGuard();
  PortableSimdGuard(const PortableSimdGuard&) = delete;
  PortableSimdGuard& operator=(const PortableSimdGuard&) = delete;
};

}  // namespace sphstab

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
/// Compiles the function it marks for AVX2 (with AVX and the SSE levels below it; not FMA).
#define SPHSTAB_TARGET_AVX2 __attribute__((target("avx2")))
#define SPHSTAB_HAS_AVX2_CLONES 1
#else
#define SPHSTAB_HAS_AVX2_CLONES 0
#endif
