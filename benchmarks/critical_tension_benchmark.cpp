// Critical tension of a 1D lattice (cubic B-spline, h = 1.2 dx, conservative form): eigen route (Spectra
// Cholesky mode over CHOLMOD), bisection (CHOLMOD LL^T, simplicial and supernodal), dense LAPACK dsygv (N <= 3000),
// and one numeric factorisation of A(T) per CHOLMOD variant. Jacobian assembly is set-up, not timed.
//   build/bin/critical_tension_benchmark --benchmark_out=bench.json --benchmark_out_format=json
//   python3 benchmarks/critical_tension_report.py bench.json results/critical-tension
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/linalg/symmetric_pencil.hpp"
#include "sphstab/stability/critical_tension.hpp"

namespace {

using namespace sphstab;

const TensionJacobian1d& jacobian(int n) {
  static std::map<int, std::unique_ptr<TensionJacobian1d>> cache;
  auto& j = cache[n];
  if (!j) {
    Kernel<1> kernel(KernelType::CubicSpline);
    j = std::make_unique<TensionJacobian1d>(analytic_jacobian_1d(tension_lattice_1d(kernel, 1.2, n), kernel, 1.2));
  }
  return *j;
}

void run(benchmark::State& state, CriticalTensionOptions opt) {
  const TensionJacobian1d& jac = jacobian(static_cast<int>(state.range(0)));
  CriticalTension r;
  // Note: benchmark::DoNotOptimize on a double (constraint "+m,r") corrupts the value with GCC 12 and
  // libbenchmark 1.7.1 here; a volatile sink keeps the result observable instead.
  volatile double sink = 0;
  for (auto _ : state) {
    r = critical_tension(jac, 4, opt);
    sink = r.tcrit;
  }
  (void)sink;
  // Reference: bisection, to report the agreement of each route.
  const CriticalTension ref = critical_tension(jac, 4, {.method = TcritMethod::Bisection});
  state.counters["tcrit"] = r.tcrit;
  state.counters["rel_diff_vs_bisection"] = std::abs(r.tcrit - ref.tcrit) / ref.tcrit;
  state.counters["factorizations"] = r.factorizations;
  state.counters["ok"] = r.status == Status::Successful;
}

void BM_EigenSpectra(benchmark::State& s) { run(s, {.method = TcritMethod::Eigen, .backend = EigenBackend::Spectra}); }
void BM_EigenDense(benchmark::State& s) { run(s, {.method = TcritMethod::Eigen, .backend = EigenBackend::Dense}); }
void BM_BisectionSimplicial(benchmark::State& s) {
  run(s, {.method = TcritMethod::Bisection, .variant = CholmodVariant::Simplicial});
}
void BM_BisectionSupernodal(benchmark::State& s) {
  run(s, {.method = TcritMethod::Bisection, .variant = CholmodVariant::Supernodal});
}

void factorize(benchmark::State& state, CholmodVariant variant) {
  const TensionJacobian1d& jac = jacobian(static_cast<int>(state.range(0)));
  SymmetricPencil pencil(jac.K, jac.L);
  CholmodDefiniteness check(variant);
  check.analyze_pattern(pencil.pattern());
  const ColSparseMatrix& a = pencil.evaluate(0.0);
  volatile bool sink = false;
  for (auto _ : state) sink = check.is_positive_definite(a);
  (void)sink;
  state.counters["nnz_lower"] = static_cast<double>(a.nonZeros());
}
void BM_FactorizeSimplicial(benchmark::State& s) { factorize(s, CholmodVariant::Simplicial); }
void BM_FactorizeSupernodal(benchmark::State& s) { factorize(s, CholmodVariant::Supernodal); }

}  // namespace

BENCHMARK(BM_EigenSpectra)->Arg(30)->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BisectionSimplicial)->Arg(30)->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BisectionSupernodal)->Arg(30)->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EigenDense)->Arg(30)->Arg(300)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EigenDense)->Arg(3000)->Iterations(1)->Unit(benchmark::kMillisecond);  // minutes with reference BLAS
BENCHMARK(BM_FactorizeSimplicial)->Arg(30)->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FactorizeSupernodal)->Arg(30)->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
