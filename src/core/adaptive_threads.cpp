#include "sphstab/core/adaptive_threads.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <utility>

#include "sphstab/core/threads.hpp"

namespace sphstab {

namespace {
double adaptive_threads_clock() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

AdaptiveThreads::AdaptiveThreads(int most, std::function<double()> clock)
    : m_clock(clock ? std::move(clock) : std::function<double()>(adaptive_threads_clock)), m_saved(max_threads()) {
  if (most < 1) throw std::invalid_argument("AdaptiveThreads: thread count must be >= 1, got " + std::to_string(most));
  m_counts = {most, 1};
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
  m_block_seconds += m_clock() - m_step_start;
  ++m_steps[m_current];
  if (most() <= 1 || ++m_in_block < m_block_steps) return;
  // The block is complete: a block too short to measure doubles the next ones and is still taken (the first blocks
  // of a run are short by design: a run of a few steps should not wait to choose).
  if (m_block_seconds < kMinBlockSeconds) m_block_steps *= 2;
  m_per_step[m_current] = m_block_seconds / static_cast<double>(m_in_block);
  if (m_per_step[1 - m_current] < 0) return start_block(1 - m_current);  // measure the other count first
  const int best = m_per_step[0] <= m_per_step[1] ? 0 : 1;
  if (m_probe) {  // a probe block: the choice is confirmed (probe less often) or changed (probe soon)
    m_interval = best == m_best ? std::min(2 * m_interval, kMaxInterval) : kFirstInterval;
    m_until_probe = m_interval;
    m_probe = false;
  } else if (best != m_best) {  // the chosen count got slower than the other's last measurement
    m_interval = kFirstInterval;
    m_until_probe = m_interval;
  } else if (--m_until_probe <= 0) {
    m_probe = true;
    return start_block(1 - best);
  }
  m_best = best;
  start_block(best);
}

}  // namespace sphstab
