// The large-lattice critical strain (issue 13: n = 1000 in under 60 s and 4 GB) by the matrix-free route with the
// preconditioned block LOBPCG: square lattice of n x n free particles plus fixed layers, cubic spline, h = 1.3 dx,
// conservative form, isotropic tension, plane strain (benchmarks/strain_lattice.hpp). One case per process, so that
// the peak RSS is the case's; prints one CSV row (header with --header).
//   build/bin/lattice_lobpcg_benchmark 1000 [--block 4] [--tol 1e-8] [--margin 0.02] [--measure] [--threads 1]
// --storage auto|per-pair|by-offset: where MatrixFreeLinearisation keeps G and H (default auto = by-offset on these
// perfect lattices: values per lattice offset, lattice loops; per-pair: values per neighbour pair, the route of
// perturbed or finite blocks); the reports run both in the same run for their ratio.
// Wall-time split: lattice (particles + neighbour list), linearisation (MatrixFreeLinearisation: the G, H values and,
// by offset, the lattice check of every free row), probe (stencil from 4 operator products), preconditioner setup
// (symbols, FFTW plan), solve. The probe check (12 products: the free-free operator against the restricted stencil at
// an interior, an edge and a corner particle) and the per-product profile (A0, A1, T on one vector, median of 5) are
// timed apart and not part of the total. benchmarks/lattice_lobpcg_report.py runs the cases and writes
// results/critical-strain-large/.
// --dim 3: the n x n x n cubic lattice (same kernel, h, material, form; 3D isotropic pre-strain); --direct-reference
// adds the direct route in the same process (the linearisation assembled by products with unit vectors, then
// critical_load's eigen route: CHOLMOD and shifted Spectra; small n only) as the reference of rel_diff_reference.
#include <sys/resource.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "sphstab/core/threads.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/lattice_sine_preconditioner.hpp"
#include "sphstab/stability/lattice_stencil.hpp"
#include "sphstab/stability/matrix_free_critical_load.hpp"
#include "strain_lattice.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// User + system CPU seconds of the process so far (all threads).
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Direct references (PETSc shift-invert, residual 3e-12; results/critical-strain-petsc).
const std::map<int, double> kReference = {
    {32, 5.75187135005997e-04}, {64, 1.50721497909831e-04}, {128, 3.8532198124872e-05}, {256, 9.73848094883822e-06}};

template <class F>
double median_seconds(F&& f, int reps = 5) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = Clock::now();
    f();
    t.push_back(since(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// The direct route in the same process: the linearisation assembled by products with unit vectors and handed to
/// the engine's eigen route (critical_load: CHOLMOD + shifted Spectra); small lattices only.
template <int Dim>
double direct_critical_strain(const sphstab::MatrixFreeLinearisation<Dim>& lin) {
  using namespace sphstab;
  CriticalLoadOptions o = CriticalLoadOptions::strain_2d();
  o.method = CriticalLoadMethod::Eigen;
  const CriticalLoad r = critical_load(assemble_by_products(lin), LoadDirection::Tension, o);
  return r.info() == Status::Successful ? r.load : NAN;
}

template <int Dim>
std::shared_ptr<const sphstab::Discretisation<Dim>> lattice(int n) {
  using namespace sphstab;
  const Kernel<Dim> k(KernelType::CubicSpline);
  if constexpr (Dim == 2) {
    return make_discretisation(strain_lattice_2d(LatticeType::Square, k, bench::kH, n), k, bench::kH);
  } else {
    return make_discretisation(
        make_lattice<3>(LatticeType::Cubic, n, {.spacing = 1.0, .support_radius = k.support_radius(bench::kH)}), k,
        bench::kH);
  }
}

}  // namespace

template <int Dim>
int run(int n, sphstab::MatrixFreeCriticalLoadOptions o, bool direct_reference, sphstab::MatrixFreeStorage storage);

int main(int argc, char** argv) {
  using namespace sphstab;
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s n [--dim 2|3] [--block b] [--tol t] [--margin m] [--measure] [--threads k] "
                 "[--direct-reference] [--storage auto|per-pair|by-offset] [--header]\n",
                 argv[0]);
    return 2;
  }
  const std::string header =
      "n,dofs,threads,block,tol,margin,fftw_measure,status,e_crit,rel_diff_reference,iterations,a0_products,"
      "a1_products,preconditioner_applications,residual,sigma_p_over_lambda,lattice_s,linearisation_s,probe_s,"
      "prec_setup_s,solve_s,solve_products_s,solve_preconditioner_s,solve_dense_s,total_s,cpu_s,probe_check_s,probe_"
      "deviation,a0_product_s,a1_product_s,preconditioner_s,"
      "linearisation_MB,peak_rss_MB,reason,dim,direct_reference_e_crit,direct_reference_s,storage";
  MatrixFreeCriticalLoadOptions o;
  o.method = MatrixFreeEigenMethod::BlockLobpcg;
  int n = 0, dim = 2;
  bool direct_reference = false;
  MatrixFreeStorage storage = MatrixFreeStorage::Auto;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    if (s == "--header") {
      std::printf("%s\n", header.c_str());
      return 0;
    } else if (s == "--block" && a + 1 < argc) {
      o.block_size = std::atoi(argv[++a]);
    } else if (s == "--tol" && a + 1 < argc) {
      o.residual_tol = std::atof(argv[++a]);
    } else if (s == "--margin" && a + 1 < argc) {
      o.margin = std::atof(argv[++a]);
    } else if (s == "--noise" && a + 1 < argc) {
      o.start_noise = std::atof(argv[++a]);
    } else if (s == "--random") {
      o.start = MatrixFreeStart::Random;
    } else if (s == "--measure") {
      o.fftw_measure = true;
    } else if (s == "--threads" && a + 1 < argc) {
      set_threads(std::atoi(argv[++a]));
    } else if (s == "--dim" && a + 1 < argc) {
      dim = std::atoi(argv[++a]);
    } else if (s == "--direct-reference") {
      direct_reference = true;
    } else if (s == "--storage" && a + 1 < argc) {
      try {
        storage = parse_matrix_free_storage(argv[++a]);
      } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
      }
    } else {
      n = std::atoi(argv[a]);
    }
  }
  if (n < 4) {
    std::fprintf(stderr, "n must be >= 4 (below 11 the stencil is probed on an 11-lattice)\n");
    return 2;
  }
  if (dim != 2 && dim != 3) {
    std::fprintf(stderr, "--dim must be 2 or 3\n");
    return 2;
  }
  o.max_iterations = 2000;
  return dim == 2 ? run<2>(n, o, direct_reference, storage) : run<3>(n, o, direct_reference, storage);
}

template <int Dim>
int run(int n, sphstab::MatrixFreeCriticalLoadOptions o, bool direct_reference, sphstab::MatrixFreeStorage storage) {
  using namespace sphstab;

  const auto t_total = Clock::now();
  auto t = Clock::now();
  std::shared_ptr<const Discretisation<Dim>> d = lattice<Dim>(n);
  const double lattice_s = since(t);
  t = Clock::now();
  const MatrixFreeLinearisation<Dim> lin(*d, bench::kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic,
                                         storage);
  const double linearisation_s = since(t);
  d.reset();  // the linearisation keeps what it needs
  t = Clock::now();
  // The probe needs n >= 11: a smaller lattice takes the stencil of an 11-lattice (same kernel, h, material, form).
  const LatticeStencil<Dim> st =
      n >= 11
          ? probe_lattice_stencil(lin, LoadDirection::Tension)
          : probe_lattice_stencil(MatrixFreeLinearisation<Dim>(*lattice<Dim>(11), bench::kMaterial,
                                                               MomentumForm::Conservative, PreStrainKind::Isotropic),
                                  LoadDirection::Tension);
  const double probe_s = since(t);
  t = Clock::now();
  const LatticeSinePreconditioner<Dim> prec(st, n, o.margin, o.fftw_measure);
  const double prec_setup_s = since(t);
  t = Clock::now();
  const MatrixFreeCriticalLoad r = matrix_free_critical_load(lin, LoadDirection::Tension, o, prec);
  const double solve_s = since(t);
  const double total_s = since(t_total);
  const double cpu_s = cpu_seconds();
  const double peak_solve_mb = bench::peak_rss_mb();

  // Not part of the total: probe check and per-product profile.
  t = Clock::now();
  const int c = n / 2;
  const int plane = Dim == 3 ? n * n * c : 0;  // 3D: the middle z plane for the interior and edge particles
  const double dev =
      n < 11 ? NAN
             : lattice_stencil_deviation(lin, LoadDirection::Tension, st,
                                         {plane + c + 1 + n * (c - 2), plane + n / 2, 0});  // interior, edge, corner
  const double probe_check_s = since(t);
  Eigen::VectorXd x = Eigen::VectorXd::Random(lin.dofs()), y(lin.dofs());
  const double a0_s = median_seconds([&] { lin.apply_A0(x, y); });
  const double a1_s = median_seconds([&] { lin.apply_combination(0.0, -1.0, x, y); });
  Eigen::MatrixXd xb = Eigen::MatrixXd::Random(lin.dofs(), 1), yb(lin.dofs(), 1);
  const double t_s = median_seconds([&] { prec.apply(xb, yb); });

  double direct = NAN, direct_s = NAN, reference = NAN;
  if (direct_reference) {
    t = Clock::now();
    direct = direct_critical_strain(lin);
    direct_s = since(t);
    reference = direct;
  } else if (const auto ref = kReference.find(n); Dim == 2 && ref != kReference.end()) {
    reference = ref->second;
  }
  const double rel = std::abs(r.load - reference) / reference;
  std::printf(
      "%d,%d,%d,%d,%g,%g,%d,%s,%.15g,%.3g,%ld,%ld,%ld,%ld,%.3g,%.6f,"
      "%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3g,%.5f,%.5f,%.5f,%.1f,%.1f,\"%s\",%d,%.15g,%.3f,%s\n",
      n, lin.dofs(), max_threads(), o.block_size, o.residual_tol, o.margin, o.fftw_measure ? 1 : 0,
      status_name(r.info()).c_str(), r.load, rel, r.iterations, r.a0_products, r.a1_products,
      r.preconditioner_applications, r.residual, r.sigma_p * r.load, lattice_s, linearisation_s, probe_s, prec_setup_s,
      solve_s, r.product_seconds, r.preconditioner_seconds,
      r.solve_seconds - r.product_seconds - r.preconditioner_seconds, total_s, cpu_s, probe_check_s, dev, a0_s, a1_s,
      t_s, lin.memory_bytes() / 1e6, peak_solve_mb, r.reason.c_str(), Dim, direct, direct_s,
      matrix_free_storage_name(lin.storage()).c_str());
  return r.info() == Status::Successful ? 0 : 1;
}
