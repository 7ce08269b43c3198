#pragma once
/// \file progress.hpp
/// A throttled one-line progress report on stderr for long runs ("\r"-updated when stderr is a terminal,
/// one line per report otherwise so that logs stay readable).
#include <chrono>
#include <string>

namespace sphstab {

class ProgressLine {
 public:
  /// `label` prefixes every line; reports are printed at most every `interval_seconds` (>= 0).
  explicit ProgressLine(std::string label, double interval_seconds = 2.0, bool enabled = true);
  ~ProgressLine();

  /// Reports `done` out of `total` units (total <= 0: unknown) with a free-form `detail`; prints only when the
  /// interval has elapsed since the last report. Returns true if it printed.
  bool update(double done, double total, const std::string& detail = {});
  /// Prints a last report with the elapsed time and ends the line (called by the destructor if needed).
  void finish(const std::string& detail = {});
  double elapsed_seconds() const;

 private:
  std::string m_label;
  double m_interval;
  bool m_enabled, m_tty, m_open = false, m_finished = false;
  std::chrono::steady_clock::time_point m_start, m_last;
};

}  // namespace sphstab
