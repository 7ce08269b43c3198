#pragma once
/// \file threads.hpp
/// The thread count of sphstab's OpenMP loops (CMake option SPHSTAB_WITH_OPENMP, ON by default).
///
/// Which loops run threaded: the rate-form evaluation (RateFormScheme::rate, every gradient and momentum form) and
/// the operator passes and pair loops of LinearElasticSph (small-strain TL and UL). Each thread owns whole particle
/// rows and every row is summed in the same order as in one thread, so results are the same bits for any thread count
/// (tested with 1 and 2 threads: tests/forms/threads_determinism_test.cpp). Eigen's own parallel products are switched
/// off (EIGEN_DONT_PARALLELIZE): its dense GEMM chooses its blocking by the thread count, which would change rounding.
///
/// The count: set_threads() (`sphstab --threads N`), else OMP_NUM_THREADS, else one thread. Not every core by
/// default: with another process on one of the cores, a thread that is descheduled stalls every barrier (measured on
/// the 2-core machine with a compile running: TL SpMV stepping at 1e4 particles 50x slower with 2 threads), and the
/// rate-form speed-up varied between runs (results/gms-speed/benchmark.md). Without OpenMP every function here
/// reports one thread.
#include <exception>

namespace sphstab {

/// The first exception thrown in the body of an OpenMP loop, kept and rethrown after the region: an exception must
/// not leave a parallel region (std::terminate; a model that refuses a state, e.g. the artificial stress at rho <= 0,
/// would abort the program instead of stopping the run).
/// \code{.cpp}
/// FirstException first;
/// #pragma omp parallel for
/// for (int i = 0; i < n; ++i) first.run([&] { row(i); });
/// first.rethrow();
/// \endcode
class FirstException {
 public:
  template <class F>
  void run(F&& f) noexcept {
    try {
      f();
    } catch (...) {
      keep(std::current_exception());
    }
  }
  /// Rethrows the kept exception, if any.
  void rethrow() const {
    if (m_error) std::rethrow_exception(m_error);
  }

 private:
  void keep(std::exception_ptr error) noexcept;
  std::exception_ptr m_error;
};

/// Threads a parallel loop uses from here on (>= 1).
int max_threads();

/// Sets the threads of later parallel loops. Throws std::invalid_argument (one line) for threads < 1.
void set_threads(int threads);

/// Whether a run keeps its thread count on every step (true) or measures its steps with max_threads() and with one
/// thread and uses the faster (false, the default; core/adaptive_threads.hpp: the same bits either way). Process-wide
/// like set_threads (`sphstab --fixed-threads`).
void set_fixed_threads(bool fixed);
bool fixed_threads();

/// The calling thread's index within its parallel region (0 outside one).
int thread_index();

/// True when sphstab was built with OpenMP.
bool threads_available();

/// Rows below which a loop runs on one thread (its start-up would cost more than it saves).
inline constexpr int kMinRowsPerThread = 512;

/// The threads a loop over `rows` rows uses: max_threads(), fewer when rows < kMinRowsPerThread per thread, at least 1.
int threads_for(long rows);

/// The OpenMP wait policy this program runs with, chosen by the program rather than left to the user's environment.
///
/// Why: libgomp's default lets a thread that reaches a barrier spin for about 3 ms before it sleeps. With another
/// process on one of the two cores, the partner the spinner waits for is descheduled, and the spin burns the time
/// slice it needs: issue 35 measured `sphstab --threads 2 scene rings` three times slower than one thread beside one
/// CPU-bound process, and 1.15x slower with OMP_WAIT_POLICY=passive. libgomp reads OMP_WAIT_POLICY and GOMP_SPINCOUNT
/// once, when it is loaded, before main() runs; so the only way a program sets them is to set the variable and
/// execute itself again. The policy is passive, a waiting thread sleeps at once: beside a CPU-bound process it is the
/// spin that costs least, while on an idle machine a spin is a few per cent faster (results/threads-speed measures
/// passive, a short spin and libgomp's default in every report run); a shared machine is the case to protect.
inline constexpr const char* kProgramWaitPolicy = "passive";

/// Call first in main(). If the environment sets neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT (the user's choice is
/// kept), sets OMP_WAIT_POLICY=kProgramWaitPolicy and re-executes the program (/proc/self/exe) with the same
/// arguments; returns only when no re-execution happened (a policy was already set, the build has no OpenMP, or exec
/// failed, which leaves libgomp's default). The variable stays set in the new process, so this runs at most once.
void set_program_wait_policy(char** argv);

/// The wait policy in force: "OMP_WAIT_POLICY=<v>", "GOMP_SPINCOUNT=<v>" or "default" (for reports).
const char* wait_policy();

/// Restores the thread count on scope exit (tests and benchmarks that compare counts).
class ThreadCountGuard {
 public:
  ThreadCountGuard() : m_saved(max_threads()) {}
  explicit ThreadCountGuard(int threads) : m_saved(max_threads()) { set_threads(threads); }
  ~ThreadCountGuard() { set_threads(m_saved); }
  ThreadCountGuard(const ThreadCountGuard&) = delete;
  ThreadCountGuard& operator=(const ThreadCountGuard&) = delete;

 private:
  int m_saved;
};

}  // namespace sphstab
