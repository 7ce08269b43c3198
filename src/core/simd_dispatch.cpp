#include "sphstab/core/simd_dispatch.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace sphstab {

namespace {
std::atomic<int> g_portable_guards{0};
}  // namespace

bool avx2_enabled() {
#if SPHSTAB_HAS_AVX2_CLONES
  // GCC's and Clang's cpu model checks the OS's saving of the YMM registers (XGETBV) before it reports AVX2.
  // SPHSTAB_SIMD=baseline in the environment keeps the baseline build (to compare the two in one binary); "auto" or
  // unset lets the CPU decide; any other value is named on stderr once and ignored (a hot loop's choice is no place
  // to stop a run).
  static const bool cpu = [] {
    const char* v = std::getenv("SPHSTAB_SIMD");
    const std::string choice = v && *v ? v : "auto";
    if (choice != "auto" && choice != "baseline")
      std::fprintf(stderr, "sphstab: SPHSTAB_SIMD='%s' is not auto or baseline; ignored (auto)\n", choice.c_str());
    return choice != "baseline" && __builtin_cpu_supports("avx2");
  }();
  return cpu && g_portable_guards.load(std::memory_order_relaxed) == 0;
#else
  return false;
#endif
}

PortableSimdGuard::PortableSimdGuard() { g_portable_guards.fetch_add(1, std::memory_order_relaxed); }
PortableSimdGuard::~PortableSimdGuard() { g_portable_guards.fetch_sub(1, std::memory_order_relaxed); }

}  // namespace sphstab
