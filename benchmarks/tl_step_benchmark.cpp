// One-core speed of the finite-strain total-Lagrangian step (forms/finite_strain_total_lagrangian.hpp: strain SpMV,
// constitutive update P(F) per particle, divergence SpMV; integrate/leapfrog.hpp: kick-drift-kick, one force
// evaluation per step), issue 11, on periodic 2D square lattices of 10 000, 99 856 and 10^6 particles.
//
// Problem (as stepping_benchmark.cpp): spacing dx = 1/side, cubic B-spline, h = 1.3 dx (20 neighbours + the particle
// itself per row), steel in plane strain (rho0 = 7.8, lambda = 1.21154, mu = 0.80769; g, cm, us), all particles free,
// random displacements of 1e-3 dx and velocities of 1e-3 c_p (fixed seed), dt = 0.3 h / c_p. Variants: St Venant-
// Kirchhoff or compressible Neo-Hookean, plain reference gradient (K = G, one operator set) or the NCSPH corrected one
// (K != G: a second operator set); difference strain sum and Plus divergence (the form's defaults), no hourglass term.
// On a periodic lattice NCSPH is G times a constant, so the two differ in the data read, not in the flops per pair.
//
// Per variant and size, in the same run:
//   - Eval: FiniteStrainTotalLagrangian::acceleration at the set-up state (strain pass into the form's F array,
//     P(F) per active particle into its P array, divergence pass);
//   - Step: LeapfrogStepper::step(dt) (the evaluation plus three vector updates), continuing from step to step;
//   - Stress (plain variants only): the constitutive update alone, P_i = P(F_i) for every particle through the
//     material's virtual stress(), on the set-up state's F;
//   - Triad: a STREAM triad (stream_triad.hpp), the memory-bandwidth reference, before the scenes and again after.
// Counters: particles; pairs (stored entries per operator matrix = neighbour-list entries, the particle itself
// included); particle_steps_per_s (particles per timed iteration / wall second: particle-evaluations for Eval and
// Stress); model_bytes (below); bound_ratio = measured wall time per iteration / (model_bytes / triad bandwidth),
// the triad bandwidth being the last Triad measured before the benchmark in this process (so >= 1 means slower
// than the bandwidth bound); peak_rss_mb (process peak resident memory so far).
//
//   build/bin/tl_step_benchmark [--max-particles=N] [google-benchmark flags]
//   (studies/tl-step-speed/run.sh writes results/tl-step-speed/benchmark.json and, with benchmarks/tl_step_report.py,
//    benchmark.md; about 1 min)
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "max_particles.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"
#include "sphstab/particles/lattice.hpp"
#include "stream_triad.hpp"

namespace {

using namespace sphstab;

constexpr double kHOverDx = 1.3, kRho = 7.8;
const ElasticMaterial kLame = ElasticMaterial::from_lame(1.21154, 0.80769, kRho);

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

struct Variant {
  bool neo_hookean = false, ncsph = false;
  std::string name() const {
    return std::string(neo_hookean ? "NeoHookean" : "StVenantKirchhoff") + (ncsph ? "-Ncsph" : "-Plain");
  }
};

/// One size and variant at a time (a 10^6 form with its operators is about 1 GB).
struct Scene {
  int side = 0;
  std::string variant;
  std::shared_ptr<const Discretisation<2>> disc;
  std::unique_ptr<FiniteStrainTotalLagrangian<2>> tl;
  std::unique_ptr<LeapfrogStepper> stepper;
  Eigen::VectorXd u0;
  double dt = 0;
  int particles() const { return disc->size(); }
  long pairs() const { return disc->neighbours.nonzeros(); }
};

std::unique_ptr<Scene> g_scene;

Scene& scene(int side, const Variant& v) {
  if (g_scene && g_scene->side == side && g_scene->variant == v.name()) return *g_scene;
  std::shared_ptr<const Discretisation<2>> disc;
  if (g_scene && g_scene->side == side) disc = g_scene->disc;
  g_scene.reset();
  auto s = std::make_unique<Scene>();
  s->side = side;
  s->variant = v.name();
  const double dx = 1.0 / side, h = kHOverDx * dx;
  if (!disc)
    disc = make_discretisation(make_lattice<2>(LatticeType::Square, side, {.spacing = dx, .periodic = true}),
                               Kernel<2>(KernelType::CubicSpline), h);
  s->disc = disc;
  std::shared_ptr<const HyperelasticModel<2>> material;
  if (v.neo_hookean)
    material = std::make_shared<NeoHookean<2>>(kLame);
  else
    material = std::make_shared<StVenantKirchhoff<2>>(kLame);
  FiniteStrainOptions<2> options;
  if (v.ncsph) options.gradient = make_gradient_provider<2>(Correction::Ncsph);
  s->tl = std::make_unique<FiniteStrainTotalLagrangian<2>>(disc, material, kRho, options);
  const double cp = std::sqrt((kLame.lambda() + 2 * kLame.mu()) / kRho);
  s->dt = 0.3 * h / cp;
  std::mt19937_64 rng(static_cast<std::uint64_t>(side));
  std::uniform_real_distribution<double> un(-1, 1);
  s->u0.resize(s->tl->dofs());
  Eigen::VectorXd v0(s->tl->dofs());
  for (Eigen::Index k = 0; k < s->u0.size(); ++k) s->u0[k] = 1e-3 * dx * un(rng), v0[k] = 1e-3 * cp * un(rng);
  SecondOrderSystem sys;
  FiniteStrainTotalLagrangian<2>* tl = s->tl.get();
  sys.acceleration = [tl](const Eigen::VectorXd& u, Eigen::VectorXd& a) { tl->acceleration(u, a); };
  sys.dofs_per_particle = 2;
  sys.mass = Eigen::VectorXd::Constant(s->particles(), kRho * dx * dx);
  s->stepper = std::make_unique<LeapfrogStepper>(std::move(sys), s->u0, v0);
  g_scene = std::move(s);
  return *g_scene;
}

/// Bytes one force evaluation must move at least, for N particles and `pairs` stored entries per operator matrix
/// (Eigen row-major, 8 B value + 4 B column index per entry, 4 B row offset per row):
///   - the strain pass reads the Dim = 2 strain matrices K^b once and u (2 doubles per particle) and writes P
///     (4 doubles per particle), F being consumed in the same row by the constitutive update (the form stores F and
///     computes P in a second loop: 64 B per particle more than the model);
///   - the divergence pass reads the 2 divergence matrices G^b once and P, and writes a (2 doubles per particle).
/// The gathers u_j and P_j are counted once (lattice order: neighbours are near in memory). The count is the same for
/// the plain gradient, where K and G are the same matrices read in the two passes (the divergence needs P_j of
/// every neighbour, so the passes cannot be one), and for NCSPH (different matrices of the same pattern). Not
/// counted: the active-set list and the NaN / zero fills of the scratch F, P (16 doubles per particle).
double eval_bytes(long particles, long pairs) {
  const double n = static_cast<double>(particles), matrix = 12.0 * static_cast<double>(pairs) + 4.0 * (n + 1);
  return 4 * matrix + 8.0 * n * (2 + 4 + 4 + 2);
}
/// A leap-frog step: the evaluation plus three vector updates of 2 doubles per particle, each reading two vectors
/// and writing one (v += dt/2 a; u += dt v; v += dt/2 a): 9 vector passes.
double step_bytes(long particles, long pairs) {
  return eval_bytes(particles, pairs) + 9 * 16.0 * static_cast<double>(particles);
}
/// The constitutive update alone: read F, write P (4 doubles each per particle).
double stress_bytes(long particles) { return 64.0 * static_cast<double>(particles); }

void set_counters(benchmark::State& st, const Scene& s, double bytes) {
  st.counters["particles"] = s.particles();
  st.counters["pairs"] = static_cast<double>(s.pairs());
  st.counters["particle_steps_per_s"] =
      benchmark::Counter(s.particles(), benchmark::Counter::kIsIterationInvariantRate);
  st.counters["model_bytes"] = bytes;
  // value (the bound's seconds per iteration) x iterations / seconds, inverted: seconds per iteration / bound
  if (bench::last_triad_bandwidth > 0)
    st.counters["bound_ratio"] =
        benchmark::Counter(bytes / bench::last_triad_bandwidth,
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  st.counters["peak_rss_mb"] = peak_rss_mb();
}

void bm_eval(benchmark::State& st, int side, Variant v) {
  Scene& s = scene(side, v);
  Eigen::VectorXd a = Eigen::VectorXd::Zero(s.tl->dofs());  // written before timing: no first-touch page faults
  for (auto _ : st) {
    s.tl->acceleration(s.u0, a);
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  set_counters(st, s, eval_bytes(s.particles(), s.pairs()));
}

void bm_step(benchmark::State& st, int side, Variant v) {
  Scene& s = scene(side, v);
  try {
    for (auto _ : st) {
      s.stepper->step(s.dt);
      benchmark::DoNotOptimize(s.stepper->u().data());
      benchmark::ClobberMemory();
    }
  } catch (const std::exception& e) {  // det F <= 0: a blown-up run
    st.SkipWithError(e.what());
    return;
  }
  set_counters(st, s, step_bytes(s.particles(), s.pairs()));
  st.counters["steps_taken"] = static_cast<double>(s.stepper->steps());
}

void bm_stress(benchmark::State& st, int side, Variant v) {
  Scene& s = scene(side, v);
  const Eigen::MatrixXd Frows = s.tl->deformation_gradients(s.u0);
  // P written before timing (no first-touch page faults in the timed loop)
  std::vector<Deformation<double, 2>> F(s.particles()), P(s.particles(), Deformation<double, 2>::Zero());
  for (int i = 0; i < s.particles(); ++i) F[i] << Frows(i, 0), Frows(i, 1), Frows(i, 2), Frows(i, 3);
  const HyperelasticModel<2>& m = s.tl->material();
  for (auto _ : st) {
    for (int i = 0; i < s.particles(); ++i) P[i] = m.stress(F[i]);
    benchmark::DoNotOptimize(P.data());
    benchmark::ClobberMemory();
  }
  set_counters(st, s, stress_bytes(s.particles()));
}

}  // namespace

int main(int argc, char** argv) {
  const long max_particles = bench::initialize_with_max_particles(argc, argv, "tl_step_benchmark");
  if (max_particles < 0) return 2;
  benchmark::RegisterBenchmark("Triad", bench::stream_triad)
      ->Unit(benchmark::kMillisecond)
      ->MinTime(1.0)
      ->UseRealTime();
  const std::vector<Variant> variants = {{false, false}, {true, false}, {false, true}, {true, true}};
  for (int side : {100, 316, 1000}) {
    const long count = static_cast<long>(side) * side;
    if (count > max_particles) continue;
    // about 0.1-0.3 s per repetition; 10^6: one evaluation is about 0.1 s
    const int iterations = side >= 1000 ? 4 : side >= 316 ? 20 : 200;
    for (const Variant& v : variants) {
      auto reg = [&](const char* what, auto fn) {
        const std::string name = std::string(what) + "/" + v.name() + "/" + std::to_string(count);
        benchmark::RegisterBenchmark(name.c_str(), fn)
            ->Unit(benchmark::kMillisecond)
            ->Iterations(iterations)
            ->Repetitions(3)
            ->UseRealTime();
      };
      reg("Eval", [side, v](benchmark::State& st) { bm_eval(st, side, v); });
      reg("Step", [side, v](benchmark::State& st) { bm_step(st, side, v); });
      if (!v.ncsph) reg("Stress", [side, v](benchmark::State& st) { bm_stress(st, side, v); });
    }
  }
  benchmark::RegisterBenchmark("TriadAgain", bench::stream_triad)
      ->Unit(benchmark::kMillisecond)
      ->MinTime(1.0)
      ->UseRealTime();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
