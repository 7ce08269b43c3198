#pragma once
/// \file adaptive_threads.hpp
/// A thread count chosen while the work runs: between a run's thread count and one thread, by the measured wall time
/// per unit of work (a time step), so that asking for a second thread never makes a run much slower than one thread.
///
/// Why: on a shared machine a second thread can cost more than it brings. With another process on one of the two
/// cores, each barrier waits for the thread that is descheduled: `sphstab --threads 2 scene rings` measured 1.2-3x
/// slower than one thread (issue 35; results/threads-speed). A wait policy (core/threads.hpp) stops the spinning but
/// not the waiting. Because sphstab's threaded loops give the same bits for any thread count (core/threads.hpp), the
/// count can change between steps without changing the result; so the run measures both counts and uses the faster.
///
/// How: steps are taken in blocks of one count, each block ending with the step that brings it to kMinBlockSeconds of
/// stepping, however many steps that takes with its count (the run's first step, which pays for first touches, is not
/// timed). So a block of the slower count is no longer than a measurement needs: with the block length in steps carried
/// over from the faster count (doubling until 0.05 s), the SI rings on two threads measured one thread for 16 steps (12
/// two-thread steps made 0.05 s: the next doubling) where 8 measure 0.075 s, in a run of 300 steps. The first two
/// blocks measure both counts; then the faster count runs (the other must be kMargin faster to replace the chosen one,
/// `most` at first), and one block of the other is measured after `interval` blocks of it: 4 after a change of choice,
/// doubling up to 64 while the choice holds. Worst case, when the other count is k times slower: one block in interval
/// + 1 at k times the cost (e.g. 2x slower: 1/65 = 1.5 % extra once settled). A probe of one thread while `most` is
/// chosen is skipped (and counts as a confirmation) when the other processes used less than kBusyCores of the machine
/// since the last probe (/proc/stat): on an idle machine only the first measurement of one thread is paid
/// (results/threads-speed measured the probes' cost at 0.1-0.15 of the idle speed-up in runs of 2-3 s); a slower `most`
/// block than the last one-thread measurement still switches at once.
/// \code{.cpp}
/// AdaptiveThreads threads;               // max_threads() now; nothing to choose with one
/// while (more()) {
///   threads.before_step();               // sets this step's count
///   stepper.step(dt);
///   threads.after_step();                // measures it
/// }                                      // the destructor restores the count it found
/// \endcode
#include <array>
#include <functional>

namespace sphstab {

class AdaptiveThreads {
 public:
  /// Shortest block of steps that counts as a measurement: several scheduler time slices (~4 ms each).
  static constexpr double kMinBlockSeconds = 0.05;
  static constexpr long kFirstInterval = 4, kMaxInterval = 64;
  /// How much faster (relative) the other count must measure to replace the chosen one.
  static constexpr double kMargin = 0.03;
  /// Below this many cores used by other processes (averaged since the last probe) the machine counts as idle.
  static constexpr double kBusyCores = 0.3;

  /// Chooses between `most` threads and one (most <= 1: nothing to choose, every step on one thread). `clock`:
  /// seconds, monotonic (default: std::chrono::steady_clock). `others`: CPU seconds used by other processes since
  /// any fixed origin, NaN when unknown (default: others_cpu_seconds() with the default clock; with a given clock,
  /// unknown, so that every probe is taken). Throws std::invalid_argument for most < 1.
  explicit AdaptiveThreads(int most, std::function<double()> clock = {}, std::function<double()> others = {});
  /// max_threads() as found.
  AdaptiveThreads();
  ~AdaptiveThreads();  ///< restores the thread count found at construction
  AdaptiveThreads(const AdaptiveThreads&) = delete;
  AdaptiveThreads& operator=(const AdaptiveThreads&) = delete;

  /// Before a step: sets the thread count for it (set_threads).
  void before_step();
  /// After the step begun by before_step(): adds its wall time to the block and, at the block's end, chooses the
  /// next block's count.
  void after_step();

  int most() const { return m_counts[0]; }
  /// The count of the current (or next) step.
  int current() const { return m_counts[m_current]; }
  /// Steps taken with `most` threads and with one.
  long steps_with_most() const { return m_steps[0]; }
  long steps_with_one() const { return most() == 1 ? m_steps[0] : m_steps[1]; }
  /// Probes of one thread skipped because the machine was idle.
  long probes_skipped() const { return m_skipped; }

 private:
  void start_block(int which);
  std::array<int, 2> m_counts{1, 1};  // [0]: most, [1]: one
  std::function<double()> m_clock;
  int m_saved = 1;
  int m_current = 0;          // index into m_counts of the current block
  int m_best = 0;             // the faster count so far
  bool m_probe = false;       // the current block measures the other count
  long m_in_block = 0;        // steps done in the current block
  double m_block_seconds = 0;  // their wall time
  double m_step_start = 0;
  std::array<double, 2> m_per_step{-1, -1};  // latest seconds per step of each count (< 0: not measured)
  long m_interval = kFirstInterval, m_until_probe = kFirstInterval;
  std::array<long, 2> m_steps{0, 0};
  std::function<double()> m_others;
  double m_others_start = 0, m_others_clock = 0;  // others' CPU seconds and the clock at the last probe
  long m_skipped = 0;
};

/// CPU seconds used since boot by every process but this one (/proc/stat's busy time, steal included, less this
/// process's CPU time); NaN where /proc/stat cannot be read.
double others_cpu_seconds();

}  // namespace sphstab
