// Stepping speed of linear-elastic SPH in 2D: total-Lagrangian sparse matrix-vector products vs updated-Lagrangian
// reassembly vs matrix-free pair loops of the same force, from 1e4 to 1e6 particles, with a memory-bandwidth
// estimate of the SpMV work against the copy bandwidth measured in the same run.
//
//   build/bin/stepping_benchmark [--out DIR] [--max-side N] [google-benchmark flags]
//
// One benchmark iteration = one leap-frog (kick-drift-kick) step = one force evaluation + 3 vector updates.
// Problem: periodic square lattice n x n (N = 1e4, 99 856, 1e6), spacing 1/n, cubic B-spline, h = 1.3 dx, steel
// in plane strain (rho = 7.8, λ = 1.21154, µ = 0.80769; g, cm, µs), minus gradient + plus divergence,
// dt = 0.3 h / c_p, small random initial velocities (no neighbour rebuild during the timed steps; the rebuild cost
// is measured separately).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sphstab/core/named_values.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/forms/linear_elastic.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/particles/lattice.hpp"

using namespace sphstab;

namespace {

constexpr double kHOverDx = 1.3, kRho = 7.8, kLambda = 1.21154, kMu = 0.80769;

struct Problem {
  int side = 0;
  ParticleSet<2> particles;
  std::unique_ptr<LinearElasticSph<2>> tl, ul;
  Eigen::VectorXd u0, v0;
  double dt = 0, h = 0, setup_tl_s = 0, setup_ul_s = 0, check_tl = 0, check_ul = 0;
};

std::unique_ptr<Problem> g_problem;  // one size at a time (memory)

Problem& problem(int side) {
  if (g_problem && g_problem->side == side) return *g_problem;
  g_problem.reset();
  auto P = std::make_unique<Problem>();
  P->side = side;
  const double dx = 1.0 / side;
  P->h = kHOverDx * dx;
  LatticeOptions lo;
  lo.spacing = dx;
  lo.periodic = true;
  P->particles = make_lattice<2>(LatticeType::Square, side, lo);
  Kernel<2> k(KernelType::CubicSpline);
  LinearElasticOptions o{.material = ElasticMaterial::from_lame(kLambda, kMu, kRho)};
  auto t0 = std::chrono::steady_clock::now();
  P->tl = std::make_unique<LinearElasticSph<2>>(P->particles, k, P->h, o);
  auto t1 = std::chrono::steady_clock::now();
  o.frame = LagrangianFrame::Updated;
  o.skin = 0.3 * dx;
  P->ul = std::make_unique<LinearElasticSph<2>>(P->particles, k, P->h, o);
  auto t2 = std::chrono::steady_clock::now();
  P->setup_tl_s = std::chrono::duration<double>(t1 - t0).count();
  P->setup_ul_s = std::chrono::duration<double>(t2 - t1).count();
  const long n = 2L * P->particles.size();
  P->dt = cfl_time_step(kDefaultCourant, P->h, P->tl->p_wave_speed());
  // Velocities such that no particle moves more than skin/2 = 0.15 dx in 1000 steps.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  P->v0.resize(n);
  for (long i = 0; i < n; ++i) P->v0[i] = d(rng) * 1e-4 * dx / P->dt;
  P->u0 = Eigen::VectorXd::Zero(n);
  // Same force from the matrices and from the pair loop (relative difference, reported in the summary).
  Eigen::VectorXd probe(n), a1, a2;
  for (long i = 0; i < n; ++i) probe[i] = d(rng) * 0.01 * dx;
  P->tl->acceleration(probe, a1);
  P->tl->acceleration_pair_loop(probe, a2);
  P->check_tl = (a1 - a2).norm() / a1.norm();
  P->ul->acceleration(probe, a1);
  P->ul->acceleration_pair_loop(probe, a2);
  P->check_ul = (a1 - a2).norm() / a1.norm();
  g_problem = std::move(P);
  return *g_problem;
}

enum class Variant { TlSpmv, TlPairLoop, UlReassembly, UlPairLoop };
constexpr NamedValue<Variant> kVariantNames[] = {{Variant::TlSpmv, "TL_SpMV"},
                                                 {Variant::TlPairLoop, "TL_PairLoop"},
                                                 {Variant::UlReassembly, "UL_Reassembly"},
                                                 {Variant::UlPairLoop, "UL_PairLoop"}};
std::string variant_name(Variant v) { return name_of(v, kVariantNames); }

struct Extra {  // per-benchmark facts for the summary
  long particles = 0;
  double model_bytes = 0, setup_s = 0, check = 0;
  long nnz = 0, rebuilds = 0;
};
std::map<std::string, Extra> g_extra;

void bm_step(benchmark::State& state, int side, Variant v, const std::string& key, int threads = 1) {
  const ThreadCountGuard guard(threads);  // one thread unless asked: OMP_NUM_THREADS must not change the 1-thread rows
  Problem& P = problem(side);
  const bool tl = v == Variant::TlSpmv || v == Variant::TlPairLoop;
  const LinearElasticSph<2>& op = tl ? *P.tl : *P.ul;
  const bool pair = v == Variant::TlPairLoop || v == Variant::UlPairLoop;
  SecondOrderSystem sys = op.system(pair);
  sys.strain_energy = nullptr;
  const long builds0 = op.neighbour_builds();
  LeapfrogStepper stepper(sys, P.u0, P.v0);
  for (auto _ : state) stepper.step(P.dt);
  const long N = P.particles.size();
  state.SetItemsProcessed(state.iterations() * N);
  Extra e;
  e.particles = N;
  e.setup_s = tl ? P.setup_tl_s : P.setup_ul_s;
  e.check = tl ? P.check_tl : P.check_ul;
  e.rebuilds = op.neighbour_builds() - builds0;
  if (v == Variant::TlSpmv) {
    // Force traffic + 3 leap-frog vector updates (each reads 2 and writes 1 vector of 2N doubles).
    e.model_bytes = op.tl_bytes_per_acceleration() + 3.0 * 3.0 * 8.0 * 2.0 * N;
    e.nnz = op.stored_nonzeros();
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * e.model_bytes));
  }
  g_extra[key] = e;
}

void bm_rebuild(benchmark::State& state, int side, const std::string& key) {
  Problem& P = problem(side);
  const double radius = 2 * P.h + 0.3 / side;
  for (auto _ : state) benchmark::DoNotOptimize(find_neighbours(P.particles, radius));
  state.SetItemsProcessed(state.iterations() * P.particles.size());
  g_extra[key] = Extra{.particles = P.particles.size()};
}

void bm_copy(benchmark::State& state, const std::string& key) {
  const std::size_t n = 1ul << 25;  // 32 Mi doubles = 256 MiB per array (far beyond cache)
  std::vector<double> a(n, 1.0), b(n, 0.0);
  for (auto _ : state) {
    std::memcpy(b.data(), a.data(), n * sizeof(double));
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
  // Bytes moved: read a + write b (write-allocate traffic not counted, as in STREAM).
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * 2 * n * sizeof(double)));
  g_extra[key] = Extra{.model_bytes = 2.0 * n * sizeof(double)};
}

struct Result {
  std::string name;
  double seconds_per_iteration;
  long iterations;
  int repetitions;
};

class CollectingReporter : public benchmark::ConsoleReporter {
 public:
  std::vector<Result> results;
  /// Best (minimum) time per iteration over repetitions: the least disturbed measurement on a shared machine.
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& r : runs) {
      if (r.error_occurred || r.run_type != Run::RT_Iteration) continue;
      std::string name = r.benchmark_name();
      if (auto p = name.find("/repeats:"); p != std::string::npos) name.erase(p, name.find('/', p + 1) - p);
      const double t = r.real_accumulated_time / static_cast<double>(r.iterations);
      auto it = std::find_if(results.begin(), results.end(), [&](const Result& x) { return x.name == name; });
      if (it == results.end())
        results.push_back({name, t, static_cast<long>(r.iterations), 1});
      else {
        it->seconds_per_iteration = std::min(it->seconds_per_iteration, t);
        ++it->repetitions;
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

std::string fmt(double x, const char* f = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof(buf), f, x);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out;
  int max_side = 1000;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else if (a.rfind("--out=", 0) == 0) {
      out = a.substr(6);
    } else if (a == "--max-side" && i + 1 < argc) {
      max_side = std::stoi(argv[++i]);
    } else {
      args.push_back(argv[i]);
    }
  }
  bool has_reps = false;
  for (char* a : args) has_reps = has_reps || std::string(a).rfind("--benchmark_repetitions", 0) == 0;
  static char reps[] = "--benchmark_repetitions=3";
  if (!has_reps) args.push_back(reps);
  int bargc = static_cast<int>(args.size());
  benchmark::Initialize(&bargc, args.data());

  std::vector<int> sides;
  for (int s : {100, 316, 1000})
    if (s <= max_side) sides.push_back(s);
  benchmark::RegisterBenchmark("Copy", [](benchmark::State& st) { bm_copy(st, "Copy/real_time"); })
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  for (int s : sides) {
    for (Variant v : {Variant::TlSpmv, Variant::TlPairLoop, Variant::UlReassembly, Variant::UlPairLoop}) {
      const std::string name = std::string(variant_name(v)) + "/" + std::to_string(s * s);
      benchmark::RegisterBenchmark(name.c_str(),
                                   [s, v, name](benchmark::State& st) { bm_step(st, s, v, name + "/real_time"); })
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond);
    }
    if (threads_available())  // the same steps on two threads (core/threads.hpp: the same bits)
      for (Variant v : {Variant::TlSpmv, Variant::TlPairLoop, Variant::UlReassembly, Variant::UlPairLoop}) {
        const std::string name = std::string(variant_name(v)) + "/" + std::to_string(s * s) + "/threads:2";
        benchmark::RegisterBenchmark(name.c_str(),
                                     [s, v, name](benchmark::State& st) { bm_step(st, s, v, name + "/real_time", 2); })
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
      }
    const std::string rname = "NeighbourRebuild/" + std::to_string(s * s);
    benchmark::RegisterBenchmark(rname.c_str(),
                                 [s, rname](benchmark::State& st) { bm_rebuild(st, s, rname + "/real_time"); })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("CopyAgain", [](benchmark::State& st) { bm_copy(st, "CopyAgain/real_time"); })
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  CollectingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  if (out.empty()) return 0;

  // ---- results ----
  std::filesystem::create_directories(out);
  std::map<std::string, double> sec;
  for (const auto& r : reporter.results) sec[r.name] = r.seconds_per_iteration;
  double copy_gbs = 0;  // best of the two copy measurements (before and after the stepping benchmarks)
  for (const char* c : {"Copy/real_time", "CopyAgain/real_time"})
    if (sec.count(c)) copy_gbs = std::max(copy_gbs, g_extra[c].model_bytes / sec[c] / 1e9);
  CsvWriter csv(out + "/stepping_speed.csv",
                {"variant", "particles", "seconds_per_step", "particle_steps_per_s", "ratio_to_pair_loop",
                 "model_bytes_per_step", "achieved_GB_per_s", "fraction_of_copy_bandwidth", "stored_nonzeros",
                 "setup_s", "neighbour_rebuilds_in_timed_steps", "rel_diff_matrix_vs_pair_loop"});
  std::ostringstream table, threads_table;
  table << "| particles | TL SpMV | TL pair loop | TL pair/SpMV | UL reassembly | UL pair loop | UL pair/reassembly | "
           "UL reassembly/TL SpMV | TL SpMV GB/s | % of copy |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (int s : sides) {
    const long N = static_cast<long>(s) * s;
    auto key = [&](Variant v) { return std::string(variant_name(v)) + "/" + std::to_string(N) + "/real_time"; };
    std::map<Variant, double> t;
    for (Variant v : {Variant::TlSpmv, Variant::TlPairLoop, Variant::UlReassembly, Variant::UlPairLoop})
      t[v] = sec.count(key(v)) ? sec[key(v)] : NAN;
    for (Variant v : {Variant::TlSpmv, Variant::TlPairLoop, Variant::UlReassembly, Variant::UlPairLoop}) {
      const Extra& e = g_extra[key(v)];
      const bool tl = v == Variant::TlSpmv || v == Variant::TlPairLoop;
      const double pair = tl ? t[Variant::TlPairLoop] : t[Variant::UlPairLoop];
      const double gbs = e.model_bytes > 0 ? e.model_bytes / t[v] / 1e9 : NAN;
      csv.row({variant_name(v), N, t[v], N / t[v], pair / t[v], e.model_bytes, gbs, gbs / copy_gbs, e.nnz, e.setup_s,
               e.rebuilds, e.check});
    }
    for (Variant v : {Variant::TlSpmv, Variant::TlPairLoop, Variant::UlReassembly, Variant::UlPairLoop}) {
      const std::string k2 = std::string(variant_name(v)) + "/" + std::to_string(N) + "/threads:2/real_time";
      if (!sec.count(k2)) continue;
      const Extra& e = g_extra[k2];
      const double gbs = e.model_bytes > 0 ? e.model_bytes / sec[k2] / 1e9 : NAN;
      csv.row({std::string(variant_name(v)) + "/threads:2", N, sec[k2], N / sec[k2], NAN, e.model_bytes, gbs,
               gbs / copy_gbs, e.nnz, e.setup_s, e.rebuilds, e.check});
      threads_table << "| " << N << " | " << variant_name(v) << " | " << fmt(N / t[v] / 1e6, "%.2f") << " M/s | "
                    << fmt(N / sec[k2] / 1e6, "%.2f") << " M/s | " << fmt(t[v] / sec[k2], "%.2f") << " |\n";
    }
    const std::string rk = "NeighbourRebuild/" + std::to_string(N) + "/real_time";
    if (sec.count(rk)) csv.row({"NeighbourRebuild", N, sec[rk], N / sec[rk], NAN, NAN, NAN, NAN, 0L, 0.0, 0L, NAN});
    const double tl_gbs = g_extra[key(Variant::TlSpmv)].model_bytes / t[Variant::TlSpmv] / 1e9;
    table << "| " << N << " | " << fmt(N / t[Variant::TlSpmv] / 1e6, "%.1f") << " M/s | "
          << fmt(N / t[Variant::TlPairLoop] / 1e6, "%.2f") << " M/s | "
          << fmt(t[Variant::TlPairLoop] / t[Variant::TlSpmv], "%.1f") << " | "
          << fmt(N / t[Variant::UlReassembly] / 1e6, "%.2f") << " M/s | "
          << fmt(N / t[Variant::UlPairLoop] / 1e6, "%.2f") << " M/s | "
          << fmt(t[Variant::UlPairLoop] / t[Variant::UlReassembly], "%.2f") << " | "
          << fmt(t[Variant::UlReassembly] / t[Variant::TlSpmv], "%.1f") << " | " << fmt(tl_gbs, "%.2f") << " | "
          << fmt(100 * tl_gbs / copy_gbs, "%.0f") << " % |\n";
  }
  csv.row({"Copy", 0L, NAN, NAN, NAN, g_extra["Copy/real_time"].model_bytes, copy_gbs, 1.0, 0L, 0.0, 0L, NAN});

  // Summary.
  const long Nmax = static_cast<long>(sides.back()) * sides.back();
  const std::string kmax = "TL_SpMV/" + std::to_string(Nmax) + "/real_time";
  const Extra& em = g_extra[kmax];
  std::ostringstream md;
  md << "# stepping-speed: TL SpMV vs UL reassembly vs pair loops (2D linear-elastic SPH)\n\n"
     << "Generated by `build/bin/stepping_benchmark --out " << out
     << "` (Google Benchmark, one thread unless marked threads:2, real time, best of "
     << reporter.results.front().repetitions
     << " repetitions; the 2 cores are shared with other jobs and single runs varied by up to 40 %, so the numbers "
        "are indicative). Raw numbers: stepping_speed.csv.\n\n"
     << "## Setup\n"
     << "- Periodic square lattice n × n in the unit square (N = n², spacing 1/n), cubic B-spline with support 2h, "
        "h = 1.3Δx (21 neighbours incl. self), plane-strain steel ρ = 7.8, λ = 1.21154, µ = 0.80769 (g, cm, µs), "
        "minus gradient + plus divergence (`include/sphstab/scene/linear_elastic.hpp`).\n"
     << "- One step = leap-frog kick-drift-kick = one force evaluation + three vector updates "
        "(`LeapfrogStepper::step`).\n"
     << "- **TL SpMV**: B^a = G^a − diag(G^a 1), C^a = G^a + diag(G^a 1) assembled once; per step one fused CSR pass "
        "for ∇u (both B^a share the pattern), a pointwise stress pass and one fused CSR pass for the divergence. "
        "**TL pair loop**: the same force without stored operators, ∇W evaluated for every pair in both passes. "
        "**UL reassembly**: G^a recomputed at x = X + u every step, in place (the CSR pattern of the neighbour list "
        "of radius 2h + 0.3Δx is kept between rebuilds: allocating fresh matrices every step was 4× slower here, "
        "first-touch page faults), then the same passes with row sums. **UL pair loop**: the pair loop at the current "
        "positions. The matrix and pair-loop forces agree to "
     << fmt(em.check, "%.1e") << " (TL) relative difference at N = " << Nmax
     << "; neighbour rebuilds during the timed UL steps: "
     << g_extra["UL_Reassembly/" + std::to_string(Nmax) + "/real_time"].rebuilds
     << " (the rebuild cost is listed separately).\n\n"
     << "## Particle-steps per second\n\n"
     << table.str() << "\n"
     << (threads_table.str().empty()
             ? std::string()
             : "## Two threads (OpenMP, core/threads.hpp)\n\nThe same steps with two threads (the particle rows of "
               "every pass split in two contiguous blocks; the same bits as one thread, "
               "tests/forms/threads_determinism_test.cpp). UL reassembly recomputes G^a on one thread; only its passes "
               "are split. Speed-up = 1-thread time / 2-thread time in this run.\n\n"
               "| particles | variant | 1 thread | 2 threads | speed-up |\n|---|---|---|---|---|\n" +
                   threads_table.str() + "\n")
     << "## Memory-bandwidth estimate of the TL SpMV step\n"
     << "- Copy bandwidth measured in the same run (memcpy of 256 MiB, read + write bytes): " << fmt(copy_gbs, "%.2f")
     << " GB/s (best of a measurement before and after the stepping benchmarks).\n"
     << "- Minimal-traffic model of one TL step (every byte crosses the bus once, perfect reuse of gathered "
        "entries): per fused pass nnz·(4 + 16) B of column indices and two value arrays, 4 B per row pointer, "
        "8 B per vector entry read or written; ∇u (4 doubles) and σ (3 doubles) per particle written and re-read; "
        "three leap-frog updates of 2N-vectors (read 2, write 1). At N = "
     << Nmax << ": " << fmt(em.nnz / 2.0 / 2.0, "%.4g") << " nonzeros per pattern, "
     << fmt(em.model_bytes / Nmax, "%.0f") << " B per particle-step, " << fmt(em.model_bytes / 1e6, "%.1f")
     << " MB per step.\n"
     << "- The achieved rate (model bytes / measured time, table above) relative to copy bandwidth shows how close "
        "the SpMV step is to being memory bound: a fraction near 100 % means the step runs at streaming speed and "
        "only less traffic (e.g. float values, symmetric storage, fused gradient+divergence with recomputation) can "
        "make it faster; a small fraction at small N means the data fit in cache (the model then overstates "
        "DRAM traffic).\n\n"
     << "## Reading\n";
  {
    auto t_of = [&](const std::string& v, long N) {
      const std::string k = v + "/" + std::to_string(N) + "/real_time";
      return sec.count(k) ? sec[k] : NAN;
    };
    const double tl = t_of("TL_SpMV", Nmax), tlp = t_of("TL_PairLoop", Nmax), ul = t_of("UL_Reassembly", Nmax),
                 ulp = t_of("UL_PairLoop", Nmax), rb = t_of("NeighbourRebuild", Nmax);
    const double tl_gbs = em.model_bytes / tl / 1e9;
    md << "- At N = " << Nmax << ": TL SpMV " << fmt(Nmax / tl / 1e6, "%.1f") << " M particle-steps/s, "
       << fmt(tlp / tl, "%.0f")
       << "× faster than the matrix-free pair loop of the same force, which evaluates ∇W "
          "twice per pair per step. The SpMV step moves "
       << fmt(tl_gbs, "%.1f") << " GB/s by the traffic model, " << fmt(100 * tl_gbs / copy_gbs, "%.0f")
       << " % of the copy bandwidth, i.e. a factor " << fmt(copy_gbs / tl_gbs, "%.1f")
       << " below streaming speed; the gap is the indirect gather of neighbour displacements/stresses and the short "
          "rows (21 entries). Smaller N run closer to copy speed because part of the data stays in cache.\n"
       << "- UL reassembly costs " << fmt(ul / tl, "%.0f") << "× a TL SpMV step (" << fmt(Nmax / ul / 1e6, "%.2f")
       << " M particle-steps/s): the kernel gradients must be recomputed every step. Recomputing them once per pair "
          "into the kept pattern and then running the two passes is "
       << fmt(ulp / ul, "%.1f")
       << "× faster than the UL pair loop, which evaluates each pair's ∇W in both passes. A neighbour rebuild "
          "(radius 2h + 0.3Δx) costs "
       << fmt(rb / ul, "%.1f") << " UL steps; with a skin of 0.3Δx it is needed every 0.15Δx/(v_max dt) steps.\n"
       << "- Memory: TL stores 2 × 2 matrices with " << fmt(em.nnz / 4.0, "%.3g") << " nonzeros each ("
       << fmt(em.nnz * 12.0 / 1e9, "%.2f") << " GB at N = " << Nmax
       << "); the pair loop stores only the neighbour list. The 1D study results/speed-vs-error shows the same "
          "ordering (µs per particle-step of tl-plain vs ul-plain / ul-minus-plus).\n";
  }
  std::ofstream(out + "/summary.md") << md.str();
  std::fprintf(stderr, "stepping_benchmark: wrote %s/stepping_speed.csv and summary.md\n", out.c_str());
  return 0;
}
