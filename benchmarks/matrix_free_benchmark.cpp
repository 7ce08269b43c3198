// Matrix-free against assembled linearisation (issue 13): square lattices of n x n free particles plus fixed layers,
// cubic spline, h = 1.3 dx, conservative form, isotropic pre-strain, y = A(e) x at e = 1e-4.
//   MatrixFreeBuild   MatrixFreeLinearisation from the discretisation (assembles G, H, keeps the needed values)
//   MatrixFreeApply   one y = (A0 + e A1) x, matrix-free
//   Assembly          analytic_jacobian_2d from the discretisation (A0, A1 assembled)
//   AssembledSpMV     one y = A x with A = A0 + e A1 assembled beforehand (the best case for the assembled route)
// Counters: bytes held (matrix-free: memory_bytes(); assembled: A0 + A1 as stored, 12 bytes per nonzero plus row
// pointers), peak RSS of the process (run one case per process for per-case memory), ns per DOF of one product.
//   build/bin/matrix_free_benchmark --benchmark_filter='BM_MatrixFreeApply/1000'
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <map>
#include <memory>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "strain_lattice.hpp"

namespace {

using namespace sphstab;

constexpr double kLoad = 1e-4;
using bench::discretisation;
using bench::kH;
using bench::kMaterial;
using bench::peak_rss_mb;

double sparse_bytes(const SparseMatrix<>& a) { return 12.0 * a.nonZeros() + 4.0 * (a.outerSize() + 1); }

void common_counters(benchmark::State& state, int n, int dofs) {
  state.counters["n"] = n;
  state.counters["dofs"] = dofs;
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

void BM_MatrixFreeBuild(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto d = discretisation(n);
  double bytes = 0;
  for (auto _ : state) {
    const MatrixFreeLinearisation lin(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
    bytes = lin.memory_bytes();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["bytes_MB"] = bytes / 1e6;
  common_counters(state, n, d->dofs());
}

void BM_MatrixFreeApply(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto d = discretisation(n);
  const MatrixFreeLinearisation lin(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(lin.dofs());
  Eigen::VectorXd y(lin.dofs());
  for (auto _ : state) {
    lin.apply(kLoad, x, y);
    benchmark::DoNotOptimize(y.data());
    benchmark::ClobberMemory();
  }
  state.counters["bytes_MB"] = lin.memory_bytes() / 1e6;
  state.counters["ns_per_dof"] = benchmark::Counter(
      double(lin.dofs()) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  common_counters(state, n, lin.dofs());
}

void BM_Assembly(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto d = discretisation(n);
  double bytes = 0, nnz0 = 0;
  for (auto _ : state) {
    const Linearisation j = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
    bytes = sparse_bytes(j.A0) + sparse_bytes(j.A1);
    nnz0 = double(j.A0.nonZeros());
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["bytes_MB"] = bytes / 1e6;
  state.counters["nnz_A0_per_row"] = nnz0 / d->dofs();
  common_counters(state, n, d->dofs());
}

void BM_AssembledSpMV(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto d = discretisation(n);
  SparseMatrix<> a;
  double bytes = 0;
  {
    const Linearisation j = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
    bytes = sparse_bytes(j.A0) + sparse_bytes(j.A1);
    a = j.at(kLoad);
  }
  const Eigen::VectorXd x = Eigen::VectorXd::Random(a.rows());
  Eigen::VectorXd y(a.rows());
  for (auto _ : state) {
    y.noalias() = a * x;
    benchmark::DoNotOptimize(y.data());
    benchmark::ClobberMemory();
  }
  state.counters["bytes_MB"] = bytes / 1e6;  // A0 and A1, the Linearisation the product comes from
  state.counters["ns_per_dof"] = benchmark::Counter(
      double(a.rows()) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  common_counters(state, n, static_cast<int>(a.rows()));
}

}  // namespace

BENCHMARK(BM_MatrixFreeBuild)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MatrixFreeBuild)->Arg(512)->Arg(1000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MatrixFreeApply)->Arg(64)->Arg(128)->Arg(256)->Arg(512)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Assembly)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Assembly)->Arg(256)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AssembledSpMV)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
