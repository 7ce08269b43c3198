#pragma once
/// \file study.hpp
/// Helpers shared by the study drivers (studies/<name>/main.cpp): wall and CPU time, parallel runs, fits, random
/// vectors, h grids and the number formats of summaries. Drivers compute and write data (CSV, summary.json); the prose
/// of a study lives in its README.md and summary.md.in (rendered by scripts/render_summary.py).
#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "sphstab/core/format.hpp"
#include "sphstab/integrate/run.hpp"
#include "sphstab/numerics/random_vector.hpp"

namespace sphstab::study {

using Clock = std::chrono::steady_clock;

/// Steps `stepper` by exactly dt until its clock reaches t_end (the last step passes it), with `probe` seeing the
/// state at step 0 and after every step: the run loop (integrate/run.hpp) in the shape of a study's measurement loop.
/// A run that stops (non-finite state, an exception, the probe's own stop rule) is said on stderr and returned.
inline RunResult run_probed(Stepper& stepper, double dt, double t_end, RunObserver& probe) {
  RunOptions o{.dt = dt, .t_end = t_end, .land_on_t_end = false, .snapshot_every = 1};
  o.observers = {&probe};
  RunResult r = run(stepper, o);
  if (!r.completed()) std::fprintf(stderr, "run stopped: %s\n", r.message.c_str());
  return r;
}

/// Seconds of wall time since t0.
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// CPU seconds used so far by the calling thread (POSIX CLOCK_THREAD_CPUTIME_ID): the cost of a run on its own
/// thread, independent of how many other jobs share the cores (unlike its wall time).
inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// The machine's 1-minute load average (first field of /proc/loadavg), "-" where unavailable: the context of a wall
/// time measured on shared cores.
inline std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a;
  return f >> a ? a : "-";
}

/// Calls job(k) for k = 0 .. count - 1 on `threads` threads, each index once, started in increasing order; each job
/// writes its own result slot, so the results do not depend on the thread count. The first exception a job throws is
/// rethrown here once every thread has stopped (the other threads take no new index after it).
template <class Job>
void parallel_for(std::size_t count, int threads, Job job) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex m;
  auto worker = [&] {
    for (std::size_t k; (k = next++) < count;) try {
        job(k);
      } catch (...) {
        std::lock_guard<std::mutex> lock(m);
        if (!error) error = std::current_exception();
        next = count;
      }
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < std::max(1, threads); ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

/// Least-squares slope of log|y| against log x over the points with x > 0 and finite non-zero y (the observed order
/// or exponent of a power law); NaN with fewer than two such points.
inline double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    if (!(x[k] > 0) || !std::isfinite(y[k]) || y[k] == 0) continue;
    const double a = std::log(x[k]), b = std::log(std::abs(y[k]));
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
    ++m;
  }
  if (m < 2) return std::nan("");
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

using sphstab::random_vector;

/// v with `digits` significant digits for prose and tables: "-" for NaN, "inf"/"-inf".
inline std::string sig(double v, int digits = 3) { return std::isnan(v) ? "-" : format_number(v, digits); }

/// v with `decimals` digits after the point (%.*f, or %+.*f with `sign`): "-" for NaN, "inf"/"-inf". A value that
/// rounds to zero prints without a minus ("0.00", not printf's "-0.00" for -1e-9): a sign the digits do not carry.
inline std::string fixed(double v, int decimals, bool sign = false) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof(buf), sign ? "%+.*f" : "%.*f", decimals, v);
  if (buf[0] == '-' && std::string(buf).find_first_of("123456789") == std::string::npos)
    return fixed(0.0, decimals, sign);
  return buf;
}

/// Appends the Markdown row "| c1 | c2 | ... |" to `table` (rows separated by newlines; the template holds the
/// header). Cells are text: format numbers with sig() or fixed() first.
inline void md_row(std::string& table, const std::vector<std::string>& cells) {
  table += table.empty() ? "|" : "\n|";
  for (const std::string& c : cells) table += " " + c + " |";
}

/// The smallest and largest of some values, for a range a summary's prose names ("5.6–6.8"): render it from the data,
/// not by hand. NaN values are skipped; an empty range renders as "-".
struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (std::isnan(v)) return;
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  bool empty() const { return lo > hi; }
  /// "lo–hi" with `decimals` digits after the point (one value when they print the same).
  std::string text(int decimals) const {
    if (empty()) return "-";
    const std::string a = fixed(lo, decimals), b = fixed(hi, decimals);
    return a == b ? a : a + "–" + b;
  }
};

/// Key numbers of a study for its summary template: summary.json, one flat object of strings.
class Summary {
 public:
  /// A number with `digits` significant digits (sig()), or text.
  void set(const std::string& key, double value, int digits = 3) { m_values[key] = sig(value, digits); }
  void set(const std::string& key, const std::string& text) { m_values[key] = text; }
  void set(const std::string& key, const char* text) { m_values[key] = text; }
  void set(const std::string& key, long value) { m_values[key] = std::to_string(value); }
  void set(const std::string& key, int value) { m_values[key] = std::to_string(value); }
  /// Writes <dir>/summary.json. Throws std::runtime_error if the file cannot be written.
  void write(const std::string& dir) const {
    std::ofstream f(dir + "/summary.json");
    if (!f) throw std::runtime_error("cannot write " + dir + "/summary.json");
    f << "{\n";
    std::size_t k = 0;
    for (const auto& [key, value] : m_values)
      f << "  " << quote(key) << ": " << quote(value) << (++k < m_values.size() ? ",\n" : "\n");
    f << "}\n";
  }

 private:
  static std::string quote(const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\')
        q += '\\', q += c;
      else if (c == '\n')
        q += "\\n";
      else if (static_cast<unsigned char>(c) < 0x20) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", c);
        q += buf;
      } else
        q += c;
    }
    return q + "\"";
  }
  std::map<std::string, std::string> m_values;
};

}  // namespace sphstab::study
