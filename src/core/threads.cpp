#include "sphstab/core/threads.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string>

#ifdef SPHSTAB_WITH_OPENMP
#include <omp.h>
#endif

namespace sphstab {

void FirstException::keep(std::exception_ptr error) noexcept {
#pragma omp critical(sphstab_first_exception)
  if (!m_error) m_error = std::move(error);
}
namespace {
// 0: never set, then one thread unless OMP_NUM_THREADS asks for more (threads.hpp: why not every core).
std::atomic<int> g_threads{0};
}  // namespace

int max_threads() {
#ifdef SPHSTAB_WITH_OPENMP
  if (const int t = g_threads.load(); t > 0) return t;
  return std::getenv("OMP_NUM_THREADS") ? std::max(1, omp_get_max_threads()) : 1;
#else
  return 1;
#endif
}

void set_threads(int threads) {
  if (threads < 1)
    throw std::invalid_argument("set_threads: thread count must be >= 1, got " + std::to_string(threads));
#ifdef SPHSTAB_WITH_OPENMP
  g_threads.store(threads);
  omp_set_num_threads(threads);
#endif
}

void set_program_wait_policy(char** argv) {
#ifdef SPHSTAB_WITH_OPENMP
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT") || argv == nullptr || argv[0] == nullptr) return;
  if (setenv("OMP_WAIT_POLICY", kProgramWaitPolicy, 1) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure: run on with libgomp's default, already loaded
#else
  (void)argv;
#endif
}

const char* wait_policy() {
  static const std::string policy = [] {
    if (const char* p = std::getenv("OMP_WAIT_POLICY")) return std::string("OMP_WAIT_POLICY=") + p;
    if (const char* s = std::getenv("GOMP_SPINCOUNT")) return std::string("GOMP_SPINCOUNT=") + s;
    return std::string("default");
  }();
  return policy.c_str();
}

namespace {
std::atomic<bool> g_fixed_threads{false};
}  // namespace

void set_fixed_threads(bool fixed) { g_fixed_threads.store(fixed); }
bool fixed_threads() { return g_fixed_threads.load(); }

int thread_index() {
#ifdef SPHSTAB_WITH_OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

bool threads_available() {
#ifdef SPHSTAB_WITH_OPENMP
  return true;
#else
  return false;
#endif
}

int threads_for(long rows) {
  const long by_rows = std::max(1L, rows / kMinRowsPerThread);
  return static_cast<int>(std::min<long>(max_threads(), by_rows));
}

}  // namespace sphstab
