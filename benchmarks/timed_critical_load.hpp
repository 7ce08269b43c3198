#pragma once
// The timed loop of the critical-load benchmarks (critical_strain_benchmark, critical_tension_benchmark).
#include <benchmark/benchmark.h>

#include "sphstab/stability/critical_load.hpp"

namespace bench {

/// critical_load(j, LoadDirection::Tension, opt) once per benchmark iteration; the last iteration's result.
/// Note: benchmark::DoNotOptimize on a double (constraint "+m,r") corrupts the value with GCC 12 and libbenchmark 1.7.1
/// here; a volatile sink keeps the result observable instead.
inline sphstab::CriticalLoad timed_critical_tension(benchmark::State& state, const sphstab::Linearisation& j,
                                                    const sphstab::CriticalLoadOptions& opt) {
  sphstab::CriticalLoad r;
  volatile double sink = 0;
  for (auto _ : state) {
    r = sphstab::critical_load(j, sphstab::LoadDirection::Tension, opt);
    sink = r.load;
  }
  (void)sink;
  return r;
}

}  // namespace bench
