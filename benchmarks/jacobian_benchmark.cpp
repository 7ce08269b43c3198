// Cost of the generic complex-step Jacobian against one force evaluation, 1D and 2D, as N grows.
// Counters: dofs, colours (= complex force evaluations per Jacobian), ratio_to_real_force (Jacobian time / one
// real force evaluation), complex_over_real (one complex force evaluation / one real one), setup_over_real (pattern +
// colouring, done once per ComplexStepJacobian, / one real force evaluation). Ratios use thread CPU time, so that
// preemption on a shared machine does not distort them.
// Allocation note: every force evaluation allocates fresh operator matrices (assemble_operators returns new Eigen
// matrices); with glibc's default heap trimming each call then re-faults its pages, which on this VM costs 4-7x the
// arithmetic for N >~ 1000 and makes timings erratic. main() therefore raises glibc's mmap/trim thresholds (as
// MALLOC_MMAP_THRESHOLD_ / MALLOC_TRIM_THRESHOLD_ would) unless SPHSTAB_DEFAULT_MALLOC is set in the environment.
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <time.h>

#include <cstdlib>

#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace {

using namespace sphstab;

/// Thread CPU time in seconds.
double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

std::unique_ptr<ForceFunction> make_force(int dim, int n, MomentumForm form) {
  const double h = 1.3;
  if (dim == 1) {
    Kernel<1> k(KernelType::CubicSpline);
    auto d =
        make_discretisation(make_lattice<1>(LatticeType::Line, n, {.spacing = 1.0, .support_radius = 2 * h}), k, h);
    return std::make_unique<WaveForm1D>(d, form, 1e-3);
  }
  Kernel<2> k(KernelType::CubicSpline);
  auto d =
      make_discretisation(make_lattice<2>(LatticeType::Square, n, {.spacing = 1.0, .support_radius = 2 * h}), k, h);
  return std::make_unique<ElasticForm2D>(d, ElasticMaterial::from_lame(1.0, 1.0, 1.0), form,
                                         PreStrain::from_area_ratio(1.001));
}

/// Mean CPU seconds of one call of f, repeated for at least 0.2 s.
template <class F>
double mean_time(F&& f) {
  int reps = 0;
  const double start = cpu_now();
  double elapsed = 0;
  do {
    f();
    ++reps;
    elapsed = cpu_now() - start;
  } while (elapsed < 0.2);
  return elapsed / reps;
}

void force(benchmark::State& state, int dim, MomentumForm form) {
  auto f = make_force(dim, static_cast<int>(state.range(0)), form);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(f->dofs()), a;
  for (auto _ : state) {
    f->acceleration(u, a);
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["dofs"] = f->dofs();
}

void jacobian_cost(benchmark::State& state, int dim, MomentumForm form) {
  auto f = make_force(dim, static_cast<int>(state.range(0)), form);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(f->dofs());
  Eigen::VectorXd a;
  Eigen::VectorXcd ac;
  const Eigen::VectorXcd uc = u.cast<std::complex<double>>();
  const double t_real = mean_time([&] { f->acceleration(u, a); });
  const double t_complex = mean_time([&] { f->acceleration(uc, ac); });
  ComplexStepJacobian jac(*f);  // pattern + colouring, outside the timed loop
  double total = 0;
  for (auto _ : state) {
    const double start = cpu_now();
    SparseMatrix<> A = jac.compute(u);
    total += cpu_now() - start;
    benchmark::DoNotOptimize(A.valuePtr());
  }
  state.counters["dofs"] = f->dofs();
  state.counters["colours"] = jac.colours();
  state.counters["ratio_to_real_force"] = total / state.iterations() / t_real;
  state.counters["complex_over_real"] = t_complex / t_real;
  const double t_setup = mean_time([&] { ComplexStepJacobian again(*f); });
  state.counters["setup_over_real"] = t_setup / t_real;
}

}  // namespace

BENCHMARK_CAPTURE(force, wave1d_plus, 1, MomentumForm::Plus)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(jacobian_cost, wave1d_plus, 1, MomentumForm::Plus)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(jacobian_cost, wave1d_conservative, 1, MomentumForm::Conservative)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(force, elastic2d_plus, 2, MomentumForm::Plus)
    ->Arg(16)
    ->Arg(32)
    ->Arg(64)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(jacobian_cost, elastic2d_plus, 2, MomentumForm::Plus)
    ->Arg(16)
    ->Arg(32)
    ->Arg(64)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(jacobian_cost, elastic2d_conservative, 2, MomentumForm::Conservative)
    ->Arg(16)
    ->Arg(32)
    ->Arg(64)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

int main(int argc, char** argv) {
  if (!std::getenv("SPHSTAB_DEFAULT_MALLOC")) {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
