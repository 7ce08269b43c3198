#pragma once
/// \file petsc_critical_load.hpp
/// The eigen route of the critical-load engine (stability/critical_load.hpp, Criterion::Definiteness) on PETSc and
/// SLEPc, with the rows of the operators distributed across MPI ranks. Built only with SPHSTAB_WITH_PETSC (library
/// target sphstab_petsc; the core library sphstab does not depend on MPI). This header includes no PETSc or MPI
/// header.
///
/// Problem solved (the same pencil and sign convention as critical_load.hpp and matrix_free_critical_load.hpp): with
/// A(load) = A0 + load A1 (jacobian/linearisation.hpp), tau = |load| and sgn = +1 (tension) or -1 (compression),
/// K = A0 (symmetric positive definite: fixed layers, not periodic) and L = -sgn A1, the generalised symmetric-definite
/// eigenproblem (SLEPc EPS_GHEP)
///   \f$ L x = \lambda K x \f$,  wanted: the largest real eigenvalue lambda_max;
/// tau_crit = 1/lambda_max (inf when lambda_max <= 0), load = sgn tau_crit. Both matrices are symmetrised,
/// (A + A^T)/2, before they are handed to PETSc (as CriticalLoadOptions::symmetrize; the analytic 2D A0 is symmetric to
/// round-off, so this moves e_crit by ~1e-11 relative against the unsymmetrised direct route).
///
/// Distribution: the free particles are grouped into lattice rows (equal y to 1e-9 of the extent; in 1D every particle
/// is a row), numbered row by row (y, then x), and each rank owns a contiguous block of whole rows (rank r of P:
/// rows [r R / P, (r + 1) R / P)), i.e. the DOFs 2 f + a of its particles; K and L are PETSc MATAIJ (MATMPIAIJ on
/// more than one rank, block size dofs_per_particle). First version: every rank receives the same assembled
/// Linearisation (each builds the same Eigen operators) and inserts only its own rows, so the memory per rank is that
/// of the whole Linearisation plus its share of the PETSc copy; measured in results/critical-strain-petsc/.
/// More ranks than lattice rows is bad input (std::invalid_argument, one line).
///
/// Solvers (PetscCriticalLoadOptions): the default is Krylov-Schur shift-invert (below, PetscEigenMethod::ShiftInvert),
/// the analogue of the direct route's shifted Spectra: the top of the spectrum of K^{-1} L is clustered (the
/// near-singular short-wave modes of A0), so unshifted methods need hundreds of K solves or LOBPCG steps. Also
/// available: Krylov-Schur on K^{-1} L (SLEPc spectral transformation STSHIFT with shift 0,
/// B-inner product), each K^{-1} v by the chosen KSP: a parallel sparse Cholesky (MUMPS, the default), or conjugate
/// gradients preconditioned by algebraic multigrid (PETSc GAMG with the rigid-body near-null space, or hypre
/// BoomerAMG) or by incomplete Cholesky (ICC(0); block Jacobi with ICC per rank on more than one rank), to ksp_rtol;
/// or LOBPCG (SLEPc EPSLOBPCG, STPRECOND) preconditioned by the same choice of approximate K^{-1}.
/// Convergence is checked, never assumed: fewer than one converged eigenpair, a failed inner solve (the KSP is set to
/// error when it does not converge), or a relative residual ||L x - lambda K x|| / (|lambda| ||K x||) above
/// residual_check gives status NotConverging / NumericalIssue with the SLEPc iteration count, the last residual
/// estimate and, for an inner solve, the KSP's iterations and residual in `reason`; load stays NaN.
///
/// Measured (tests/distributed/petsc_critical_load_mpi_test.cpp under mpirun -np 1 and -np 2; square lattices, cubic,
/// h = 1.3 dx): agreement with the direct route <= 4e-14 relative (shift-invert, n = 16, 32; unshifted Krylov-Schur
/// with MUMPS or CG+GAMG <= 5e-14; LOBPCG at tol 1e-8, 5e-12). At n = 128 (results/critical-strain-petsc): shift-invert
/// 8-9 SLEPc iterations, ~95 solves, 1.7e-13 from the direct route; unshifted Krylov-Schur needs ~400 K solves, and
/// LOBPCG + GAMG ~3000 steps without reaching a residual of 1e-6 (the top of the spectrum of K^{-1} L is clustered).
///
/// \code{.cpp}
/// sphstab::PetscSession session(&argc, &argv);   // SlepcInitialize / SlepcFinalize (MPI_Init / MPI_Finalize)
/// auto lin = sphstab::analytic_jacobian_2d(*disc, material, sphstab::MomentumForm::Conservative,
///                                          sphstab::PreStrainKind::Isotropic);   // the same on every rank
/// sphstab::PetscCriticalLoad r = sphstab::petsc_critical_load(lin, sphstab::LoadDirection::Tension);
/// if (r.info() == sphstab::Status::Successful && session.rank() == 0) std::cout << r.load << "\n";
/// \endcode
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/jacobian/linearisation.hpp"

namespace sphstab {

/// SLEPc (and so PETSc and MPI) initialised for the lifetime of the object; one per process, constructed before any
/// other PETSc call. Command-line options of PETSc/SLEPc (-eps_*, -st_*, -log_view, ...) are read from argc/argv.
/// Throws std::runtime_error when initialisation fails or a session already exists.
class PetscSession {
 public:
  PetscSession(int* argc, char*** argv);
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
  int rank() const;  ///< rank in PETSC_COMM_WORLD
  int size() const;  ///< ranks in PETSC_COMM_WORLD
};

/// Collective on PETSC_COMM_WORLD: the largest `value` over the ranks.
double max_over_ranks(double value);
/// MPI_Wtime(): wall-clock seconds.
double wall_seconds();

/// The free particles grouped into lattice rows and the rows split across ranks.
struct LatticeRowPartition {
  std::vector<int> order;            ///< free particles in row order: order[k] = free index (row of x) of the k-th
  std::vector<int> particle_offset;  ///< ranks + 1 entries: rank r owns order[particle_offset[r] .. [r + 1])
  int rows = 0;                      ///< lattice rows
};

/// Rows of equal last coordinate of `x` (free_count x dim; |dy| <= 1e-9 of the extent counts as equal; dim 1: every
/// particle is a row), ordered by (y, x), split into `ranks` contiguous blocks of whole rows as evenly as possible.
/// Throws std::invalid_argument (one line) for ranks < 1, an empty x, or more ranks than rows.
LatticeRowPartition lattice_row_partition(const Eigen::MatrixXd& x, int ranks);

enum class PetscEigenMethod {
  /// Krylov-Schur estimate on K^{-1} L to estimate_tol, then Krylov-Schur shift-invert (STSINVERT) about
  /// sigma = theta (1 + shift_margin) > lambda_max, L - sigma K factored by MUMPS LDL^T; sigma is raised (margin x 4)
  /// until the factor's inertia shows no eigenvalue above it, so the eigenvalue nearest sigma is lambda_max.
  ShiftInvert,
  KrylovSchur,  ///< SLEPc Krylov-Schur on K^{-1} L (STSHIFT, shift 0), K solved by `solver`
  Lobpcg,       ///< SLEPc LOBPCG (STPRECOND), preconditioned by `solver` applied to K
};
enum class PetscSolver {
  Cholesky,  ///< sparse Cholesky of K by MUMPS (parallel direct; KSPPREONLY)
  CgGamg,    ///< CG + PETSc GAMG (smoothed aggregation, rigid-body near-null space)
  CgHypre,   ///< CG + hypre BoomerAMG
  CgIcc,     ///< CG + ICC(0) (block Jacobi with ICC(0) per rank on more than one rank)
};
/// "shift-invert", "krylov-schur", "lobpcg"; throws std::invalid_argument otherwise.
PetscEigenMethod parse_petsc_eigen_method(const std::string& name);
/// "cholesky", "gamg", "hypre", "icc"; throws std::invalid_argument otherwise.
PetscSolver parse_petsc_solver(const std::string& name);
std::string petsc_eigen_method_name(PetscEigenMethod method);
std::string petsc_solver_name(PetscSolver solver);

struct PetscCriticalLoadOptions {
  PetscEigenMethod method = PetscEigenMethod::ShiftInvert;
  PetscSolver solver = PetscSolver::Cholesky;  ///< K solves / preconditioner (ShiftInvert: Cholesky only)
  double estimate_tol = 5e-2;  ///< ShiftInvert: tolerance of the Krylov-Schur estimate theta of lambda_max
  double shift_margin = 1e-2;  ///< ShiftInvert: first shift theta (1 + shift_margin)
  double tol = 1e-10;          ///< SLEPc: relative residual ||L x - lambda K x|| / |lambda| (eigenvalue error ~ tol^2)
  int max_iterations = 0;      ///< SLEPc restarts (Krylov-Schur) or steps (LOBPCG); 0: SLEPc's default
  int ncv = 0;                 ///< Krylov-Schur basis size; 0: SLEPc's default
  double ksp_rtol = 1e-12;     ///< iterative K solves (Krylov-Schur with CG): ||r|| <= ksp_rtol ||b||
  int ksp_max_iterations = 20000;  ///< iterative K solves: CG steps per solve
  double residual_check = 1e-6;    ///< accepted relative residual of the returned pair, recomputed here
  bool from_options = true;        ///< let -eps_* / -st_* command-line options override the above (EPSSetFromOptions)
};

struct PetscCriticalLoad {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double load = nan;            ///< signed critical load; +-inf when lambda_max <= 0; NaN unless Successful
  double lambda_max = nan;      ///< largest eigenvalue of L x = lambda K x
  double residual = nan;        ///< ||L x - lambda K x|| / (|lambda| ||K x||) of the returned pair (or last estimate)
  int iterations = 0;           ///< SLEPc iterations (EPSGetIterationNumber)
  long ksp_iterations = 0;      ///< inner KSP iterations in all (KSPGetTotalIterations of the spectral transformation)
  int converged = 0;            ///< converged eigenpairs (EPSGetConverged)
  int ranks = 0;                ///< MPI ranks
  int lattice_rows = 0;         ///< rows of the partition
  int global_dofs = 0;          ///< unknowns
  int local_dofs = 0;           ///< unknowns owned by this rank
  double assembly_seconds = 0;  ///< wall time: partition, symmetrisation and PETSc matrices (this rank)
  double solve_seconds = 0;     ///< wall time of EPSSetUp + EPSSolve (this rank)
  double petsc_matrix_bytes = 0;  ///< PETSc memory held by K and L on this rank (MatGetInfo, memory)
  double shift = nan;             ///< ShiftInvert: the final shift sigma (> lambda_max)
  int factorisations = 0;         ///< ShiftInvert: LDL^T factorisations of L - sigma K (inertia checks)
  std::string solver;             ///< e.g. "krylovschur+cholesky(mumps)"
  Status status = Status::NotComputed;
  std::string reason;  ///< why status is not Successful (empty otherwise); one line
  Status info() const { return status; }
};

/// Collective on PETSC_COMM_WORLD: every rank passes the same `lin` and options and gets the same result. Throws
/// std::invalid_argument (one line) for a non-symmetric linearisation, A1 = 0, positions missing (lin.x empty), more
/// ranks than lattice rows, or invalid options; std::runtime_error when PETSc fails outside the solve or no
/// PetscSession exists.
PetscCriticalLoad petsc_critical_load(const Linearisation& lin, LoadDirection direction,
                                      const PetscCriticalLoadOptions& options = {});

}  // namespace sphstab
