// Critical tension of a 1D lattice (cubic B-spline, h = 1.2 dx, conservative form): eigen route (Spectra
// Cholesky mode over CHOLMOD), bisection (CHOLMOD LL^T, simplicial and supernodal), dense LAPACK dsygv (N <= 3000),
// and one numeric factorisation of A(T) per CHOLMOD variant. Jacobian assembly is set-up, not timed.
//   build/bin/critical_tension_benchmark --benchmark_out=bench.json --benchmark_out_format=json
//   python3 benchmarks/critical_tension_report.py bench.json results/critical-tension
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/linalg/symmetric_pencil.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "timed_critical_load.hpp"

namespace {

using namespace sphstab;

/// The conservative form's linearisation, A(T) = K - 4 T L.
const Linearisation& jacobian(int n) {
  static std::map<int, std::unique_ptr<Linearisation>> cache;
  auto& j = cache[n];
  if (!j) {
    Kernel<1> kernel(KernelType::CubicSpline);
    j = std::make_unique<Linearisation>(
        analytic_jacobian_1d(tension_lattice_1d(kernel, 1.2, n), kernel, 1.2, MomentumForm::Conservative));
  }
  return *j;
}

CriticalLoadOptions options(CriticalLoadMethod method, EigenBackend backend = EigenBackend::Auto,
                            CholmodVariant variant = CholmodVariant::Simplicial) {
  CriticalLoadOptions o = CriticalLoadOptions::tension_1d();
  o.criterion = Criterion::Definiteness;
  o.method = method;
  o.backend = backend;
  o.variant = variant;
  return o;
}

void run(benchmark::State& state, CriticalLoadOptions opt) {
  const Linearisation& jac = jacobian(static_cast<int>(state.range(0)));
  const CriticalLoad r = bench::timed_critical_tension(state, jac, opt);
  // Reference: bisection, to report the agreement of each route.
  const CriticalLoad ref = critical_load(jac, LoadDirection::Tension, options(CriticalLoadMethod::Bisection));
  state.counters["tcrit"] = r.load;
  state.counters["rel_diff_vs_bisection"] = std::abs(r.load - ref.load) / ref.load;
  state.counters["factorizations"] = r.evaluations;
  state.counters["ok"] = r.status == Status::Successful;
}

void BM_EigenSpectra(benchmark::State& s) { run(s, options(CriticalLoadMethod::Eigen, EigenBackend::Spectra)); }
void BM_EigenDense(benchmark::State& s) { run(s, options(CriticalLoadMethod::Eigen, EigenBackend::Dense)); }
void BM_BisectionSimplicial(benchmark::State& s) {
  run(s, options(CriticalLoadMethod::Bisection, EigenBackend::Auto, CholmodVariant::Simplicial));
}
void BM_BisectionSupernodal(benchmark::State& s) {
  run(s, options(CriticalLoadMethod::Bisection, EigenBackend::Auto, CholmodVariant::Supernodal));
}

void factorize(benchmark::State& state, CholmodVariant variant) {
  const Linearisation& jac = jacobian(static_cast<int>(state.range(0)));
  SymmetricPencil pencil(ColSparseMatrix(jac.A0), ColSparseMatrix(-0.25 * jac.A1));  // K, L
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
