// Assembly speed of W + G (2D square lattice) against this machine's memory-copy bandwidth, same run.
// Counters: nnz_per_s (nonzeros of W assembled per second, one value each in W, G^x, G^y) and
// bytes_per_s (values + indices written). Run with --benchmark_format=csv for results/assembly-speed/.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <map>
#include <vector>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"

namespace {

using namespace sphstab;

void BM_MemoryCopy(benchmark::State& state) {
  const size_t bytes = size_t(1) << 28;  // 256 MiB, far beyond cache
  std::vector<char> a(bytes, 1), b(bytes, 0);
  for (auto _ : state) {
    std::memcpy(b.data(), a.data(), bytes);
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
  // Read + write traffic of a copy.
  state.counters["bytes_per_s"] = benchmark::Counter(2.0 * bytes, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_MemoryCopy)->Unit(benchmark::kMillisecond)->UseRealTime();

struct Setup {
  ParticleSet<2> particles;
  NeighbourList neighbours;
};

const Setup& setup(long n_total, double h_over_dx) {
  static std::map<std::pair<long, double>, Setup> cache;
  auto key = std::make_pair(n_total, h_over_dx);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  cache.clear();  // keep one large set in memory at a time
  int side = static_cast<int>(std::lround(std::sqrt(double(n_total))));
  Setup s;
  s.particles = make_lattice<2>(LatticeType::Square, side, {.spacing = 1.0, .periodic = true});
  s.neighbours = find_neighbours(s.particles, 2.0 * h_over_dx);
  return cache.emplace(key, std::move(s)).first->second;
}

/// The counters of an assembly benchmark: particles, nonzeros, nonzeros per second and bytes per second at
/// `bytes_per_nonzero` over the matrices written.
void assembly_counters(benchmark::State& state, const Setup& s, double bytes_per_nonzero) {
  const double nnz = double(s.neighbours.nonzeros());
  state.counters["particles"] = double(s.particles.size());
  state.counters["nnz"] = nnz;
  state.counters["nnz_per_s"] = benchmark::Counter(nnz, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_s"] =
      benchmark::Counter(bytes_per_nonzero * nnz, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_AssembleWG(benchmark::State& state) {
  const double h = state.range(1) / 10.0;
  const Setup& s = setup(state.range(0), h);
  Kernel<2> kernel(KernelType::CubicSpline);
  for (auto _ : state) {
    auto ops = assemble_operators(s.particles, s.neighbours, kernel, h, {.kernel = true, .gradient = true});
    benchmark::DoNotOptimize(ops.W.valuePtr());
  }
  // Three matrices, each with values (8 B) and inner indices (4 B) per nonzero.
  assembly_counters(state, s, 3.0 * 12.0);
}

// Re-assembly into existing storage (updated-Lagrangian steady state: no allocation, pattern reused).
void BM_ReassembleWG(benchmark::State& state) {
  const double h = state.range(1) / 10.0;
  const Setup& s = setup(state.range(0), h);
  Kernel<2> kernel(KernelType::CubicSpline);
  Operators<2> ops;
  assemble_operators_into(ops, s.particles, s.neighbours, kernel, h, {.kernel = true, .gradient = true});
  for (auto _ : state) {
    assemble_operators_into(ops, s.particles, s.neighbours, kernel, h, {.kernel = true, .gradient = true});
    benchmark::DoNotOptimize(ops.W.valuePtr());
  }
  assembly_counters(state, s, 3.0 * 8.0);
}

void BM_NeighbourSearch(benchmark::State& state) {
  const double h = state.range(1) / 10.0;
  const Setup& s = setup(state.range(0), h);
  for (auto _ : state) {
    auto nl = find_neighbours(s.particles, 2.0 * h);
    benchmark::DoNotOptimize(nl.indices.data());
  }
  state.counters["particles"] = double(s.particles.size());
  state.counters["nnz_per_s"] =
      benchmark::Counter(double(s.neighbours.nonzeros()), benchmark::Counter::kIsIterationInvariantRate);
}

void sizes(benchmark::internal::Benchmark* b) {
  for (long n : {10000L, 40000L, 160000L, 640000L, 1000000L, 4000000L})
    for (long h10 : {13L, 20L}) b->Args({n, h10});
}
BENCHMARK(BM_AssembleWG)->Apply(sizes)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
BENCHMARK(BM_ReassembleWG)->Apply(sizes)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
BENCHMARK(BM_NeighbourSearch)->Apply(sizes)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);

}  // namespace

BENCHMARK_MAIN();
