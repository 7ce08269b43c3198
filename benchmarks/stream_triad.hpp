#pragma once
// The memory-bandwidth reference of the benchmarks: a STREAM triad a = b + s c over three 256 MB arrays, timed in the
// same run as the kernels it is compared with. Reports bytes_per_second (SetBytesProcessed, STREAM convention: 2 reads
// + 1 write per element, write-allocate traffic not counted) and array_bytes.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sphstab::bench {

inline void stream_triad(benchmark::State& state) {
  const std::size_t n = std::size_t(1) << 25;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double scalar = 3.0;
  for (auto _ : state) {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + scalar * pc[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * 3 * n * sizeof(double)));
  state.counters["array_bytes"] = 3.0 * n * sizeof(double);
}

}  // namespace sphstab::bench
