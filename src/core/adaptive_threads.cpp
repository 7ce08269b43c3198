#include "sphstab/core/adaptive_threads.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <unistd.h>

#include "sphstab/core/threads.hpp"

namespace sphstab {

namespace {
double adaptive_threads_clock() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double unknown_others() { return std::numeric_limits<double>::quiet_NaN(); }
}  // namespace

double others_cpu_seconds() {
  std::ifstream f("/proc/stat");
  std::string cpu;
  unsigned long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  f >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
  timespec own{};
  if (!f || cpu != "cpu" || clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &own) != 0)
    return std::numeric_limits<double>::quiet_NaN();
  const double busy = static_cast<double>(user + nice + system + irq + softirq + steal) /
                      static_cast<double>(sysconf(_SC_CLK_TCK));
  return busy - (static_cast<double>(own.tv_sec) + 1e-9 * static_cast<double>(own.tv_nsec));
}

AdaptiveThreads::AdaptiveThreads(int most, std::function<double()> clock, std::function<double()> others)
    : m_saved(max_threads()) {
  if (most < 1) throw std::invalid_argument("AdaptiveThreads: thread count must be >= 1, got " + std::to_string(most));
  m_counts = {most, 1};
  // Real time and /proc/stat belong together; a given clock with the real others' CPU would compare two time lines.
  if (others) m_others = std::move(others);
  else m_others = clock ? unknown_others : others_cpu_seconds;
  m_clock = clock ? std::move(clock) : std::function<double()>(adaptive_threads_clock);
  m_others_start = m_others();
  m_others_clock = m_clock();
}

AdaptiveThreads::AdaptiveThreads() : AdaptiveThreads(max_threads()) {}

AdaptiveThreads::~AdaptiveThreads() {
  if (most() > 1) set_threads(m_saved);
}

void AdaptiveThreads::start_block(int which) {
  m_current = which;
  m_in_block = 0;
  m_block_seconds = 0;
}

void AdaptiveThreads::before_step() {
  if (most() > 1) set_threads(current());
  m_step_start = m_clock();
}

void AdaptiveThreads::after_step() {
  const double seconds = m_clock() - m_step_start;
  ++m_steps[m_current];
  // The run's first step is not a measurement: it pays for first touches (workspaces, page faults, waking threads).
  if (most() <= 1 || m_steps[0] + m_steps[1] == 1) return;
  m_block_seconds += seconds;
  ++m_in_block;
  if (m_block_seconds < kMinBlockSeconds) return;  // a block is one measurement: a few scheduler time slices at least
  m_per_step[m_current] = m_block_seconds / static_cast<double>(m_in_block);
  if (m_per_step[1 - m_current] < 0) return start_block(1 - m_current);  // measure the other count first
  // The other count must be kMargin faster to replace the chosen one: timings of a shared machine are noisy, and
  // each change costs blocks of measuring.
  const int other = 1 - m_best;
  const int best = m_per_step[other] < (1 - kMargin) * m_per_step[m_best] ? other : m_best;
  if (m_probe) {  // a probe block: the choice is confirmed (probe less often) or changed (probe soon)
    m_interval = best == m_best ? std::min(2 * m_interval, kMaxInterval) : kFirstInterval;
    m_until_probe = m_interval;
    m_probe = false;
  } else if (best != m_best) {  // the chosen count got slower than the other's last measurement
    m_interval = kFirstInterval;
    m_until_probe = m_interval;
  } else if (--m_until_probe <= 0) {
    // A probe of one thread is for another process's arrival: skipped while the others used < kBusyCores since the
    // last one (NaN, unknown: taken).
    const double now = m_clock(), others = m_others();
    const bool idle = best == 0 && (others - m_others_start) < kBusyCores * (now - m_others_clock);
    m_others_start = others, m_others_clock = now;
    if (!idle) {
      m_probe = true;
      return start_block(1 - best);
    }
    ++m_skipped;
    m_interval = std::min(2 * m_interval, kMaxInterval);
    m_until_probe = m_interval;
  }
  m_best = best;
  start_block(best);
}

}  // namespace sphstab
