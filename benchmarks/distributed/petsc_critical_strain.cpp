// Critical pre-strain of the 2D benchmark lattice (strain_lattice.hpp: n x n free particles plus fixed layers, cubic
// spline, h = 1.3 dx, conservative form, isotropic tension) by one route per process, one CSV row on stdout (rank 0):
//   --route petsc        petsc_critical_load (distributed/petsc_critical_load.hpp) on all ranks of mpirun
//   --route direct       critical_load, Criterion::Definiteness, eigen route only: shifted Spectra over CHOLMOD
//                        (the 2D presets of CriticalLoadOptions::strain_2d(), single process)
//   --route matrix-free  matrix_free_critical_load, LOBPCG (single process)
// Columns: route,method,ranks,n,dofs,e_crit,status,iterations,inner_iterations,residual,build_s,assembly_s,solve_s,
// total_s,cpu_s,peak_rss_mb_max_rank,peak_rss_mb_sum,reason. cpu_s: user + system CPU seconds of the whole process,
// summed over ranks (getrusage), the fairer measure on a shared machine. build_s: lattice + Linearisation (or
// MatrixFreeLinearisation); peak RSS from getrusage per rank (max and sum over ranks).
//   mpirun -np 2 build/bin/petsc_critical_strain --route petsc --n 128 --method krylov-schur --solver cholesky
#include <sys/resource.h>

#include <cstdio>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>

#include "../strain_lattice.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/distributed/petsc_critical_load.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/matrix_free_critical_load.hpp"

namespace {

using namespace sphstab;

struct Row {
  std::string route, method;
  int ranks = 1, n = 0, dofs = 0;
  double e_crit = 0;
  std::string status;
  long iterations = 0, inner = 0;
  double residual = 0, build_s = 0, assembly_s = 0, solve_s = 0, total_s = 0;
  std::string reason;
};

std::string arg(int argc, char** argv, const std::string& key, const std::string& fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (key == argv[i]) return argv[i + 1];
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  PetscSession session(&argc, &argv);
  try {
    const std::string route = arg(argc, argv, "--route", "petsc");
    const int n = std::stoi(arg(argc, argv, "--n", "32"));
    Row row;
    row.route = route;
    row.n = n;
    row.ranks = session.size();
    const double t0 = wall_seconds();
    auto d = bench::discretisation(n);
    if (route == "matrix-free") {
      if (session.size() != 1) throw std::invalid_argument("--route matrix-free runs on one rank");
      const MatrixFreeLinearisation lin(*d, bench::kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
      row.build_s = wall_seconds() - t0;
      const double t1 = wall_seconds();
      const MatrixFreeCriticalLoad r = matrix_free_critical_load(lin, LoadDirection::Tension);
      row.solve_s = wall_seconds() - t1;
      row.method = "lobpcg(hand-written;unpreconditioned)";
      row.dofs = lin.dofs();
      row.e_crit = r.load;
      row.status = status_name(r.info());
      row.iterations = r.iterations;
      row.inner = r.a0_products;
      row.reason = r.reason;
    } else {
      const Linearisation lin =
          analytic_jacobian_2d(*d, bench::kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
      row.build_s = wall_seconds() - t0;
      row.dofs = lin.dofs();
      const double t1 = wall_seconds();
      if (route == "direct") {
        if (session.size() != 1) throw std::invalid_argument("--route direct runs on one rank");
        CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
        opt.criterion = Criterion::Definiteness;
        opt.method = CriticalLoadMethod::Eigen;
        opt.want_mode = false;
        const CriticalLoad r = critical_load(lin, LoadDirection::Tension, opt);
        row.solve_s = wall_seconds() - t1;
        row.method = "shifted-spectra+cholmod(" + r.eigen_backend + ")";
        row.e_crit = r.load;
        row.status = status_name(r.info());
        row.iterations = r.evaluations;
        row.reason = r.reason;
      } else if (route == "petsc") {
        PetscCriticalLoadOptions o;
        o.method = parse_petsc_eigen_method(arg(argc, argv, "--method", "krylov-schur"));
        o.solver = parse_petsc_solver(arg(argc, argv, "--solver", "cholesky"));
        const PetscCriticalLoad r = petsc_critical_load(lin, LoadDirection::Tension, o);
        row.method = r.solver;
        row.e_crit = r.load;
        row.status = status_name(r.info());
        row.iterations = r.iterations;
        row.inner = r.ksp_iterations;
        row.residual = r.residual;
        row.assembly_s = max_over_ranks(r.assembly_seconds);
        row.solve_s = max_over_ranks(r.solve_seconds);
        row.reason = r.reason;
      } else {
        throw std::invalid_argument("--route must be petsc, direct or matrix-free, got '" + route + "'");
      }
    }
    row.total_s = max_over_ranks(wall_seconds() - t0);
    const double rss = bench::peak_rss_mb();
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    const double cpu = u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec + 1e-6 * u.ru_stime.tv_usec;
    double cpu_sum = 0;
    const double rss_max = max_over_ranks(rss);
    // Sum over ranks from the max of (rank-tagged) values is not available; sum by gathering via max of each rank.
    double rss_sum = 0;
    for (int r = 0; r < session.size(); ++r) {
      rss_sum += max_over_ranks(session.rank() == r ? rss : 0.0);
      cpu_sum += max_over_ranks(session.rank() == r ? cpu : 0.0);
    }
    if (session.rank() == 0) {
      if (arg(argc, argv, "--header", "no") == "yes")
        std::cout << "route,method,ranks,n,dofs,e_crit,status,iterations,inner_iterations,residual,build_s,"
                     "assembly_s,solve_s,total_s,cpu_s,peak_rss_mb_max_rank,peak_rss_mb_sum,reason\n";
      std::cout << row.route << "," << row.method << "," << row.ranks << "," << row.n << "," << row.dofs << ","
                << format_number(row.e_crit, 15) << "," << row.status << "," << row.iterations << "," << row.inner
                << "," << format_number(row.residual, 3) << "," << format_number(row.build_s, 4) << ","
                << format_number(row.assembly_s, 4) << "," << format_number(row.solve_s, 4) << ","
                << format_number(row.total_s, 4) << "," << format_number(cpu_sum, 4) << "," << format_number(rss_max, 5)
                << "," << format_number(rss_sum, 5) << ",\"" << row.reason << "\"\n";
    }
  } catch (const std::exception& e) {
    if (session.rank() == 0) std::cerr << "petsc_critical_strain: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
