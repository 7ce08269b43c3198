#include "sphstab/core/simd_dispatch.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace sphstab {

namespace {
std::atomic<int> g_portable_guards{0};
}  // namespace

bool avx2_enabled() {
#if SPHSTAB_HAS_AVX2_CLONES
  // GCC's and Clang's cpu model checks the OS's saving of the YMM registers (XGETBV) before it reports AVX2.
  // SPHSTAB_SIMD=baseline in the environment keeps the baseline build (to compare the two in one binary).
  static const bool cpu =
      __builtin_cpu_supports("avx2") &&
      !(std::getenv("SPHSTAB_SIMD") != nullptr && std::strcmp(std::getenv("SPHSTAB_SIMD"), "baseline") == 0);
  return cpu && g_portable_guards.load(std::memory_order_relaxed) == 0;
#else
  return false;
#endif
}

PortableSimdGuard::PortableSimdGuard() { g_portable_guards.fetch_add(1, std::memory_order_relaxed); }
PortableSimdGuard::~PortableSimdGuard() { g_portable_guards.fetch_sub(1, std::memory_order_relaxed); }

}  // namespace sphstab
