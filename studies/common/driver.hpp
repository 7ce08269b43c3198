#pragma once
/// \file driver.hpp
/// What a study driver's main() does around its phases, the same in every driver that uses it: the cases run costliest
/// first on the threads, summary.json written with the study's wall time, and the exit on an exception.
#include <algorithm>
#include <cstddef>
#include <exception>
#include <iostream>
#include <string>
#include <type_traits>
#include <vector>

#include "common/study.hpp"

namespace sphstab::study {

/// run(case) for every case on `threads` threads (parallel_for), the costliest first (by cost(case); ties in case
/// order) so that no large run starts last on an otherwise idle pool. The results stay in case order, each in its own
/// slot: they do not depend on the order or the thread count.
template <class Case, class Cost, class Run>
auto run_costliest_first(const std::vector<Case>& cases, int threads, Cost cost, Run run) {
  std::vector<std::size_t> order(cases.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cost(cases[a]) > cost(cases[b]); });
  std::vector<std::decay_t<std::invoke_result_t<Run&, const Case&>>> results(cases.size());
  parallel_for(cases.size(), threads, [&](std::size_t k) { results[order[k]] = run(cases[order[k]]); });
  return results;
}

/// What write_summary records beside the study's own keys. A wall time is measured on shared cores, so a study whose
/// summary reads its timings says under what load (the 1-minute load average at the end) and, with its runs side by
/// side, on how many threads.
struct SummaryTiming {
  std::string wall_key = "wall_seconds";  ///< the wall time's key (the older drivers' summaries say "wall_total")
  bool load = false;                      ///< "load": load_average()
  int threads = 0;                        ///< "threads", when > 0
};

/// Sets the wall time since t0 (3 digits) and what `timing` asks for, and writes <out>/summary.json: a driver's last
/// step.
inline void write_summary(Summary& summary, const std::string& out, Clock::time_point t0,
                          const SummaryTiming& timing = {}) {
  summary.set(timing.wall_key, seconds_since(t0), 3);
  if (timing.load) summary.set("load", load_average());
  if (timing.threads > 0) summary.set("threads", timing.threads);
  summary.write(out);
}

/// The exit of a driver's main() on an exception: "<study>: <message>" on stderr, exit status 1.
inline int exit_on_error(const char* study, const std::exception& e) {
  std::cerr << study << ": " << e.what() << "\n";
  return 1;
}

}  // namespace sphstab::study
