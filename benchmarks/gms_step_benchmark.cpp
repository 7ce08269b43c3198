// One-core speed of the full GMS scheme (forms/rate_form.hpp with the options of [GMS2001]: continuity -rho tr L,
// XSPH 1/2, viscosity alpha = 1, beta = 2 with the compression switch, artificial stress 0.3, n = 4; GMS
// predictor-corrector, integrate/rate_form_run.hpp) on the scenes of issue 10, neighbour updates included:
//   - RingsSI: the colliding rings in SI units (E = 1e7 Pa, nu = 0.3975, rho0 = 1, radii 0.03 / 0.04 m, dx = 5e-4 m,
//     h = 1.5 dx, +-0.059 c0; 17 608 particles), at first contact speed;
//   - Lattice: periodic 2D square lattices of 99 856 and 1e6 particles (GMS units, mu = 0.22, h = 1.5 dx) with random
//     velocities of 0.01 c0 (so the viscosity switch acts on about half the pairs) and densities 1 +- 0.5 %.
// Each scene with the row loop and with the pair loop (PairLoop, forms/rate_form.hpp; scene names "<scene>/pairs").
// Per scene, in the same run:
//   - Run (RingsSI only): the SI run of studies/gms-rings, 300 steps from y0 with the Verlet list (skin 0.5 dx), its
//     builds included: the whole-run cost per particle-step of issue 10's target; RunOneRate: the same with one rate
//     evaluation per step (RateFormRunOptions::reuse_corrector_rate);
//   - Step: run_rate_form for `steps` predictor-corrector steps with a Verlet list (skin 0.5 dx, rebuilt when a
//     particle has moved skin / 2; the build at the start is part of every run_rate_form call and is counted);
//   - StepFixedList: steady-state steps on the scene's list (neighbour_skin 0, never rebuilt): two rate evaluations,
//     the integration and the run loop's state check per step, without the per-run set-up. Per iteration a
//     RateFormStepper is constructed and takes one warm-up step with the timing paused (so the copies of the state the
//     stepper holds and its predictor-corrector buffers exist and their pages are touched: at 1e6 particles each is
//     64 MB; timing whole run_rate_form calls of 2 steps instead, on a host with slow page faults, put 30-50 % of the
//     1e6 lattice's step into the "integration"), then `steps` steps are timed; the stepper is destroyed with the
//     timing paused too. The timed steps therefore go from the state after one step to the state after steps + 1,
//     one step later than the states Rate evaluates at (y0 to the state after `steps`): the same list, only the pairs
//     the viscosity switch acts on can differ a little;
//   - Rate: RateFormScheme::rate at y0 and at the state after each of the scene's steps (the states a run from y0
//     passes through): kernel sums, velocity gradient, stress rates, artificial stress and viscosity in one fused pass
//     per particle row, so kernel and stress work are not separable by timing; one untimed evaluation first, so that
//     the output vector's pages are touched (as in a run's steps);
//   - Rebuild: RateFormScheme::rebuilt (cell-list search at radius support + skin and the scheme's set-up on it);
//   - Triad: a STREAM triad, the memory bandwidth reference (before and after the scenes);
//   - Step/<scene>/threads:2, Rate/<scene>/threads:2 (both loops: the row loop's rows and the pair loop's chunks are
//     split between the threads): Step and Rate with two OpenMP threads, the same bits as one thread (checked here
//     before timing, for every scene key: the state after the scene's steps); every other benchmark runs on one thread
//     whatever OMP_NUM_THREADS says.
// Counters per benchmark: particles, pairs (ordered, list of the timed scheme), steps (timed; StepFixedList's warm-up
// step is not counted), builds, model_bytes (the least data a step must move: see model_bytes()).
//
//   build/bin/gms_step_benchmark [--max-particles=N] [google-benchmark flags]
//   (studies/gms-speed/run.sh writes results/gms-speed/benchmark.json and, with benchmarks/gms_step_report.py,
//    benchmark.md; about 3 min)
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "max_particles.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/colliding_rings.hpp"
#include "stream_triad.hpp"

namespace {

using namespace sphstab;

constexpr double kSkin = 0.5;  // Verlet skin in dx, as in the gms-* studies

RateFormOptions gms(PairLoop loop) {
  return {.continuity = ContinuityForm::Divergence,
          .xsph = 0.5,
          .viscosity = ViscositySwitch::Compression,
          .viscosity_alpha = 1,
          .viscosity_beta = 2,
          .artificial_stress = 0.3,
          .pair_loop = loop};
}

struct Scene {
  std::string name;
  std::unique_ptr<RateFormScheme<2>> scheme;
  Eigen::VectorXd y0;
  std::vector<Eigen::VectorXd> states;  // y0 and the state after each of the timed steps (Rate runs over them)
  double dt = 0, dx = 0;
  long steps = 0;  // per timed run
  long pairs() const { return scheme->discretisation().neighbours.nonzeros(); }
  int particles() const { return scheme->discretisation().size(); }
};

Scene rings_si(PairLoop loop) {
  const ElasticMaterial m = ElasticMaterial::from_young_poisson(1e7, 0.3975, 1.0);
  const double dx = 5e-4;
  const CollidingRings r = make_colliding_rings(
      {.inner_radius = 0.03, .outer_radius = 0.04, .spacing = dx, .gap = 2e-3, .speed = 0.059 * m.sound_speed()});
  Scene s{.name = "RingsSI", .dx = dx, .steps = 40};
  s.scheme = std::make_unique<RateFormScheme<2>>(
      make_discretisation(r.particles, Kernel<2>(KernelType::CubicSpline), 1.5 * dx), m, gms(loop));
  s.y0 = s.scheme->uniform_state();
  for (int i = 0; i < r.size(); ++i) s.scheme->set_velocity(s.y0, i, r.velocity.col(i));
  s.dt = 0.5 * 1.5 * dx / m.p_wave_speed();
  return s;
}

Scene lattice(int side, PairLoop loop) {
  const ElasticMaterial m = ElasticMaterial::from_bulk_shear(1, 0.22, 1);
  Scene s{.name = "Lattice", .dx = 1.0, .steps = side >= 1000 ? 2 : 6};
  s.scheme = std::make_unique<RateFormScheme<2>>(
      make_discretisation(make_lattice<2>(LatticeType::Square, side, {.spacing = 1.0, .periodic = true}),
                          Kernel<2>(KernelType::CubicSpline), 1.5),
      m, gms(loop));
  s.y0 = s.scheme->uniform_state();
  std::mt19937_64 rng(side);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < s.particles(); ++i) {
    s.scheme->set_velocity(s.y0, i, 0.01 * m.sound_speed() * Eigen::Vector2d(u(rng), u(rng)));
    s.y0[s.scheme->density_offset(i)] += 0.005 * u(rng);
  }
  s.dt = 0.5 * 1.5 / m.p_wave_speed();
  return s;
}

Scene& scene(const std::string& key) {
  static std::map<std::string, Scene> cache;
  auto it = cache.find(key);
  if (it == cache.end()) {
    // "<scene>" (the row loop) or "<scene>/pairs" (the pair loop).
    const std::size_t slash = key.find('/');
    const std::string base = key.substr(0, slash);
    const PairLoop loop = slash == std::string::npos ? PairLoop::Rows : parse_pair_loop(key.substr(slash + 1));
    Scene s = base == "RingsSI" ? rings_si(loop)
                                : lattice(static_cast<int>(std::lround(std::sqrt(std::atof(base.c_str() + 7)))), loop);
    // At y0 the rings move rigidly (no pair approaches: the viscosity is off everywhere); a few steps in, it acts.
    const ThreadCountGuard one(1);
    const RateFormRunResult r =
        run_rate_form(*s.scheme, s.y0,
                      {.dt = s.dt,
                       .t_end = static_cast<double>(s.steps) * s.dt,
                       .observer = [&s](long, double, const Eigen::VectorXd& y) { s.states.push_back(y); }});
    if (!r.completed()) throw std::runtime_error("gms_step_benchmark: " + s.name + " set-up run: " + r.message);
    if (threads_available()) {  // the two-thread benchmarks time the same computation
      const ThreadCountGuard two(2);
      const RateFormRunResult r2 =
          run_rate_form(*s.scheme, s.y0, {.dt = s.dt, .t_end = static_cast<double>(s.steps) * s.dt});
      if (!r2.completed() || r2.y.size() != r.y.size() ||
          std::memcmp(r2.y.data(), r.y.data(), sizeof(double) * r.y.size()) != 0)
        throw std::runtime_error("gms_step_benchmark: " + s.name + ": two threads end in a different state");
    }
    it = cache.emplace(key, std::move(s)).first;
  }
  return it->second;
}

/// The least data one predictor-corrector step must move, in bytes: per rate evaluation, the state read and the
/// rates written (8 doubles each per particle in 2D: x, v, rho, S) plus the neighbour list's indices (4 B per pair) and
/// offsets (8 B per particle); per step two evaluations and the integration's passes over the state (the predictor
/// reads y, f and writes y*; the corrector reads y, f, f* and writes y; 7 state vectors).
double model_bytes(long particles, long pairs) {
  const double state = 8.0 * 8 * static_cast<double>(particles);
  const double eval = 2 * state + 4.0 * static_cast<double>(pairs) + 8.0 * static_cast<double>(particles);
  return 2 * eval + 7 * state;
}

void set_counters(benchmark::State& st, const Scene& s, long steps, long builds) {
  st.counters["particles"] = s.particles();
  st.counters["pairs"] = static_cast<double>(s.pairs());
  st.counters["steps"] = static_cast<double>(steps);
  st.counters["builds"] = static_cast<double>(builds);
  st.counters["model_bytes"] = model_bytes(s.particles(), s.pairs());
}

/// Times run_rate_form(scheme, y0, o) per iteration and sets the counters; false (the benchmark skipped) when a run
/// stops early.
bool time_runs(benchmark::State& st, const Scene& s, const RateFormRunOptions& o) {
  long steps = 0, builds = 0;
  for (auto _ : st) {
    const RateFormRunResult r = run_rate_form(*s.scheme, s.y0, o);
    if (!r.completed()) {
      st.SkipWithError(("run stopped: " + r.message).c_str());
      return false;
    }
    steps = r.steps, builds = r.neighbour_builds;
    benchmark::DoNotOptimize(r.y.data());
  }
  set_counters(st, s, steps, builds);
  return true;
}

void bm_step(benchmark::State& st, const std::string& key, int threads = 1) {
  const ThreadCountGuard guard(threads);
  Scene& s = scene(key);
  const RateFormRunOptions o{.dt = s.dt,
                             .t_end = static_cast<double>(s.steps) * s.dt,
                             .record_every = static_cast<int>(s.steps),
                             .neighbour_skin = kSkin * s.dx};
  time_runs(st, s, o);
}

/// Steady-state steps on the scene's own list (see the file comment): the per-run set-up (the stepper's state copies,
/// the first touch of its buffers) is outside the timing, so the fixed-list step minus two rate evaluations is the
/// integration of a step, not the set-up of a short run spread over its steps.
void bm_step_fixed_list(benchmark::State& st, const std::string& key) {
  const ThreadCountGuard guard(1);
  Scene& s = scene(key);
  // The stepper takes dt from each step(dt) call, but its constructor checks the options as run_rate_form does
  // (t_end > 0 among them): t_end spans the warm-up and the timed steps, though nothing reads it.
  const RateFormRunOptions o{.dt = s.dt, .t_end = static_cast<double>(s.steps + 1) * s.dt, .neighbour_skin = 0.0};
  const BlowUpLimits limits{};  // run_rate_form's per-step check (check_every 1, no displacement limit)
  long steps = 0, builds = 0;
  for (auto _ : st) {
    st.PauseTiming();
    auto stepper = std::make_unique<RateFormStepper<2>>(*s.scheme, s.y0, o);
    stepper->step(s.dt);  // warm-up: allocates and touches the predictor-corrector's buffers
    StateFault fault = stepper->check(limits);
    st.ResumeTiming();
    for (long k = 0; k < s.steps && !fault; ++k) {
      stepper->step(s.dt);
      fault = stepper->check(limits);
    }
    benchmark::DoNotOptimize(stepper->state().data());
    st.PauseTiming();
    if (fault) {
      st.SkipWithError(("step " + std::to_string(stepper->steps()) + ": " + fault.why).c_str());
      return;
    }
    steps = stepper->steps() - 1, builds = stepper->neighbour_builds();
    stepper.reset();  // its buffers are freed outside the timing, as they were allocated
    st.ResumeTiming();
  }
  set_counters(st, s, steps, builds);
}

/// The SI rings as studies/gms-rings runs them by default: kRunSteps steps from y0 with the Verlet list (skin 0.5 dx),
/// its builds included: the whole-run cost per particle-step of issue 10's target.
constexpr long kRunSteps = 300;
void bm_run(benchmark::State& st, const std::string& key, bool one_rate, double skin = kSkin) {
  const ThreadCountGuard guard(1);
  Scene& s = scene(key);
  const RateFormRunOptions o{.dt = s.dt,
                             .t_end = static_cast<double>(kRunSteps) * s.dt,
                             .record_every = static_cast<int>(kRunSteps),
                             .reuse_corrector_rate = one_rate,
                             .neighbour_skin = skin * s.dx};
  if (skin != kSkin) {  // the skin sets the cost only: the same end state bit for bit as the default skin
    RateFormRunOptions ref = o;
    ref.neighbour_skin = kSkin * s.dx;
    const RateFormRunResult a = run_rate_form(*s.scheme, s.y0, ref), b = run_rate_form(*s.scheme, s.y0, o);
    if (!a.completed() || !b.completed() || a.y.size() != b.y.size() ||
        std::memcmp(a.y.data(), b.y.data(), sizeof(double) * a.y.size()) != 0) {
      st.SkipWithError("the skin changes the end state");
      return;
    }
  }
  if (time_runs(st, s, o)) st.counters["skin"] = skin;
}

void bm_rate(benchmark::State& st, const std::string& key, int threads = 1) {
  const ThreadCountGuard guard(threads);
  Scene& s = scene(key);
  Eigen::VectorXd f(s.scheme->size());
  s.scheme->rate(s.states.front(), f);  // untimed: touches f's pages (64 MB at 1e6 particles), as a run's steps have
  for (auto _ : st) {
    for (const Eigen::VectorXd& y : s.states) {
      s.scheme->rate(y, f);
      benchmark::DoNotOptimize(f.data());
    }
  }
  set_counters(st, s, 0, 0);
  st.counters["evaluations"] = static_cast<double>(s.states.size());
}

void bm_rebuild(benchmark::State& st, const std::string& key) {
  const ThreadCountGuard guard(1);
  Scene& s = scene(key);
  const double radius = s.scheme->discretisation().kernel.support_radius(s.scheme->discretisation().h) + kSkin * s.dx;
  long pairs = 0;
  for (auto _ : st) {
    const RateFormScheme<2> r = s.scheme->rebuilt(s.states.back(), radius);
    pairs = r.discretisation().neighbours.nonzeros();
    benchmark::DoNotOptimize(&r);
  }
  set_counters(st, s, 0, 1);
  st.counters["pairs_rebuilt"] = static_cast<double>(pairs);
}

}  // namespace

int main(int argc, char** argv) {
  const long max_particles = bench::initialize_with_max_particles(argc, argv, "gms_step_benchmark");
  if (max_particles < 0) return 2;
  benchmark::RegisterBenchmark("Triad", bench::stream_triad)->Unit(benchmark::kMillisecond)->MinTime(1.0);
  std::vector<std::pair<std::string, long>> keys = {{"RingsSI", 17608},          {"RingsSI/pairs", 17608},
                                                    {"Lattice99856", 99856},     {"Lattice99856/pairs", 99856},
                                                    {"Lattice1000000", 1000000}, {"Lattice1000000/pairs", 1000000}};
  for (const auto& key_count : keys) {
    // not a structured binding: the lambdas below capture the key, which clang before 16 refuses for a binding
    const std::string& key = key_count.first;
    const long count = key_count.second;
    if (count > max_particles) continue;
    const int reps = count >= 1000000 ? 1 : 3;
    // The whole runs carry issue 35's target and its baseline: twice the repetitions, so that with random
    // interleaving (studies/gms-speed/run.sh) a slow spell of the shared host (minutes long) is less likely to fall
    // on every repetition of one of them. The same count for every run configuration, the baseline included.
    const int run_reps = 2 * reps;
    auto reg = [&](const char* what, auto fn, const char* suffix = "", int iterations = 0) {
      const std::string name = std::string(what) + "/" + key + suffix;
      benchmark::RegisterBenchmark(name.c_str(), fn)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(iterations > 0     ? iterations
                       : count >= 1000000 ? 1
                                          : 3)
          ->Repetitions(std::string(what).rfind("Run", 0) == 0 ? run_reps : reps)
          ->ReportAggregatesOnly(false);
    };
    if (key.rfind("RingsSI", 0) == 0) {
      reg(
          "Run", [key](benchmark::State& st) { bm_run(st, key, false); }, "", 1);
      reg(
          "RunOneRate", [key](benchmark::State& st) { bm_run(st, key, true); }, "", 1);
      // The list's skin is a cost parameter only (the rates read the pairs within the support; the pair loop's
      // bits do not depend on the list radius): larger skins, fewer builds, more listed pairs.
      if (key.find("/pairs") != std::string::npos)
        for (double skin : {0.75, 1.0}) {
          const std::string suffix = "/skin:" + format_number(skin);
          reg(
              "RunOneRate", [key, skin](benchmark::State& st) { bm_run(st, key, true, skin); }, suffix.c_str(), 1);
        }
    }
    reg("Step", [key](benchmark::State& st) { bm_step(st, key); });
    reg("StepFixedList", [key](benchmark::State& st) { bm_step_fixed_list(st, key); });
    reg("Rate", [key](benchmark::State& st) { bm_rate(st, key); });
    reg("Rebuild", [key](benchmark::State& st) { bm_rebuild(st, key); });
    if (threads_available()) {  // both loops split their work between the threads (scene() checks the bits)
      reg(
          "Step", [key](benchmark::State& st) { bm_step(st, key, 2); }, "/threads:2");
      reg(
          "Rate", [key](benchmark::State& st) { bm_rate(st, key, 2); }, "/threads:2");
    }
  }
  benchmark::RegisterBenchmark("TriadAgain", bench::stream_triad)->Unit(benchmark::kMillisecond)->MinTime(1.0);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
