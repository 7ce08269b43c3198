#pragma once
// The memory-bandwidth reference of the benchmarks: a STREAM triad a = b + s c over three 256 MB arrays, timed in the
// same run as the kernels it is compared with. Reports bytes_per_second (SetBytesProcessed, STREAM convention: 2 reads
// + 1 write per element, write-allocate traffic not counted) and array_bytes. The bandwidth of the last run (wall time
// of its timed loop) stays in last_triad_bandwidth, for benchmarks that report a ratio to it in their own counters.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sphstab::bench {

/// Bytes per second of the last stream_triad run in this process (STREAM convention as above; 0 before the first).
inline double last_triad_bandwidth = 0;

inline void stream_triad(benchmark::State& state) {
  const std::size_t n = std::size_t(1) << 25;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double scalar = 3.0;
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + scalar * pc[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  last_triad_bandwidth = static_cast<double>(state.iterations() * 3 * n * sizeof(double)) / seconds;
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * 3 * n * sizeof(double)));
  state.counters["array_bytes"] = 3.0 * n * sizeof(double);
}

}  // namespace sphstab::bench
