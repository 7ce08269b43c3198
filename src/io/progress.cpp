#include "sphstab/io/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "sphstab/core/threads.hpp"

namespace sphstab {

ProgressLine::ProgressLine(std::string label, double interval_seconds, bool enabled)
    : m_label(std::move(label)),
      m_interval(interval_seconds < 0 ? 0 : interval_seconds),
      m_enabled(enabled),
      m_tty(isatty(fileno(stderr)) != 0),
      m_start(std::chrono::steady_clock::now()),
      m_last(m_start) {}

ProgressLine::~ProgressLine() {
  if (m_open && !m_finished) std::fputc('\n', stderr);
}

double ProgressLine::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

bool ProgressLine::update(double done, double total, const std::string& detail) {
  if (!m_enabled) return false;
  auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - m_last).count() < m_interval) return false;
  m_last = now;
  const double elapsed = std::chrono::duration<double>(now - m_start).count();
  char eta[64] = "";
  if (total > 0 && done > 0 && done < total)
    std::snprintf(eta, sizeof(eta), ", eta %.1f s", elapsed * (total - done) / done);
  char pct[32] = "";
  if (total > 0) std::snprintf(pct, sizeof(pct), " %5.1f%%", 100.0 * done / total);
  std::fprintf(stderr, "%s[%s]%s %s (%.1f s%s)%s", m_tty ? "\r" : "", m_label.c_str(), pct, detail.c_str(), elapsed,
               eta, m_tty ? "\033[K" : "\n");
  std::fflush(stderr);
  m_open = m_tty;
  return true;
}

void ProgressLine::finish(const std::string& detail) {
  if (!m_enabled || m_finished) return;
  m_finished = true;
  // The threads and the OpenMP wait policy beside the time: a timing means little without them.
  const int threads = max_threads();
  std::fprintf(stderr, "%s[%s] done %s (%.2f s, %d thread%s, wait policy %s)%s\n", m_tty ? "\r" : "", m_label.c_str(),
               detail.c_str(), elapsed_seconds(), threads, threads == 1 ? "" : "s", wait_policy(),
               m_tty ? "\033[K" : "");
  std::fflush(stderr);
  m_open = false;
}

}  // namespace sphstab
