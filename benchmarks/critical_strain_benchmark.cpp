// Critical pre-strain of 2D square lattices (cubic spline, h = 1.3 dx, conservative form, isotropic tension), n free
// particles per side plus fixed layers: the pieces of one e_crit computation and their growth with N = n^2.
//   Jacobian        operators G, H and the analytic A0, A1 (analytic_jacobian_2d), from the particle set
//   JacobianCS      the same by coloured complex step (affine_jacobian: two coloured Jacobians), small n only
//   Factorize       one numeric CHOLMOD supernodal LL^T of A(e) (pattern analysed once; METIS ordering chosen by
//                   CHOLMOD), with CHOLMOD's fill (lnz) and flop count as counters
//   Bisection       critical_strain, bisection route only (bracket in factors of 8, then rtol 1e-12)
//   Eigen           critical_strain, eigen route only (bracket + Spectra Cholesky mode with the shifted B = A(lo))
//   SymbolPeriodic  the exact periodic-lattice e_crit from the 2 x 2 Fourier symbols (n^2 wavevectors)
// Every benchmark reports peak RSS (MB) of the process: run one case per process for per-case memory
// (benchmarks/critical_strain_report.py does that).
//   build/bin/critical_strain_benchmark --benchmark_filter='BM_Factorize/128'
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <Eigen/CholmodSupport>
#include <map>
#include <memory>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "strain_lattice.hpp"
#include "timed_critical_load.hpp"

namespace {

using namespace sphstab;

using bench::discretisation;
using bench::kH;
using bench::kMaterial;
using bench::peak_rss_mb;

const Linearisation& jacobian(int n) {
  static std::map<int, std::unique_ptr<Linearisation>> cache;
  auto& j = cache[n];
  if (!j)
    j = std::make_unique<Linearisation>(
        analytic_jacobian_2d(*discretisation(n), kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic));
  return *j;
}

void common_counters(benchmark::State& state, int n) {
  state.counters["n"] = n;
  state.counters["particles"] = double(n) * n;
  state.counters["dofs"] = 2.0 * n * n;
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

void BM_Jacobian(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto d = discretisation(n);
  volatile double sink = 0;
  long nnz0 = 0, nnz1 = 0;
  for (auto _ : state) {
    const Linearisation j = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
    nnz0 = j.A0.nonZeros();
    nnz1 = j.A1.nonZeros();
    sink = j.A0.valuePtr()[0];
  }
  (void)sink;
  state.counters["nnz_A0"] = double(nnz0);
  state.counters["nnz_A1"] = double(nnz1);
  common_counters(state, n);
}

void BM_JacobianCS(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto d = discretisation(n);
  ElasticForm2D force(d, kMaterial, MomentumForm::Conservative, PreStrain{PreStrainKind::Isotropic, 0.0});
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(force.dofs());
  volatile double sink = 0;
  for (auto _ : state) {
    const Linearisation j = affine_jacobian(force, u);
    sink = j.A0.valuePtr()[0];
  }
  (void)sink;
  state.counters["colours"] = ComplexStepJacobian(force).colours();
  common_counters(state, n);
}

void BM_Factorize(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Linearisation& j = jacobian(n);
  ColSparseMatrix a = ColSparseMatrix(j.at(1e-5)).triangularView<Eigen::Lower>();
  a.makeCompressed();
  Eigen::CholmodSupernodalLLT<ColSparseMatrix, Eigen::Lower> chol;
  chol.cholmod().print = 0;
  chol.analyzePattern(a);
  bool ok = true;
  for (auto _ : state) {
    chol.factorize(a);
    ok = ok && chol.info() == Eigen::Success;
  }
  const cholmod_common& c = chol.cholmod();
  state.counters["nnz_lower"] = double(a.nonZeros());
  state.counters["lnz"] = c.lnz;
  state.counters["flops"] = c.fl;
  state.counters["GFLOPs_per_s"] = benchmark::Counter(c.fl * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["ok"] = ok;
  common_counters(state, n);
}

void critical(benchmark::State& state, CriticalLoadMethod method) {
  const int n = static_cast<int>(state.range(0));
  const Linearisation& j = jacobian(n);
  CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
  opt.method = method;
  opt.want_mode = false;
  opt.backend = EigenBackend::Spectra;
  const CriticalLoad r = bench::timed_critical_tension(state, j, opt);
  state.counters["ecrit"] = r.load;
  state.counters["factorizations"] = r.evaluations;
  state.counters["ok"] = r.status == Status::Successful;
  common_counters(state, n);
}
void BM_Bisection(benchmark::State& s) { critical(s, CriticalLoadMethod::Bisection); }
void BM_Eigen(benchmark::State& s) { critical(s, CriticalLoadMethod::Eigen); }

void BM_SymbolPeriodic(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const ElasticSymbol2D sym(LatticeType::Square, Kernel<2>(KernelType::CubicSpline), kH, 1.0, kMaterial,
                            MomentumForm::Conservative, PreStrainKind::Isotropic);
  volatile double sink = 0;
  SymbolCriticalStrain r;
  for (auto _ : state) {
    r = critical_strain_periodic_symbol_2d(sym, n + 1, LoadDirection::Tension);  // odd n: no zone-boundary zero
    sink = r.e;
  }
  (void)sink;
  state.counters["ecrit"] = r.e;
  common_counters(state, n + 1);
}

}  // namespace

BENCHMARK(BM_Jacobian)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Jacobian)->Arg(256)->Arg(512)->Arg(1000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JacobianCS)->Arg(32)->Arg(64)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Factorize)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Factorize)->Arg(128)->Arg(181)->Arg(256)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Bisection)->Arg(32)->Iterations(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Bisection)->Arg(64)->Arg(128)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Eigen)->Arg(32)->Arg(64)->Iterations(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Eigen)->Arg(128)->Arg(181)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SymbolPeriodic)->Arg(32)->Arg(128)->Arg(1000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
