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

/// The calling thread's index within its parallel region (0 outside one).
int thread_index();

/// True when sphstab was built with OpenMP.
bool threads_available();

/// Rows below which a loop runs on one thread (its start-up would cost more than it saves).
inline constexpr int kMinRowsPerThread = 512;

/// The threads a loop over `rows` rows uses: max_threads(), fewer when rows < kMinRowsPerThread per thread, at least 1.
int threads_for(long rows);

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
