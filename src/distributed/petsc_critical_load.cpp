#include "sphstab/distributed/petsc_critical_load.hpp"

#include <slepceps.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <stdexcept>

#include "sphstab/core/format.hpp"
#include "sphstab/core/named_values.hpp"

namespace sphstab {

namespace {

bool g_session = false;

/// Throws std::runtime_error with PETSc's one-line message for a failed call outside the solve.
void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw std::runtime_error(std::string("petsc_critical_load: ") + what + " failed (PETSc error " +
                           std::to_string(static_cast<int>(code)) + (text ? std::string(": ") + text : "") + ")");
}
#define SPH_CHECK(call) check((call), #call)

int world_rank() {
  PetscMPIInt r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}
int world_size() {
  PetscMPIInt s = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

/// Owns a PETSc object and destroys it (the Destroy functions take a pointer to the handle).
template <class T, PetscErrorCode (*Destroy)(T*)>
struct Owned {
  T h = nullptr;
  ~Owned() {
    if (h) Destroy(&h);
  }
};

/// (A + A^T) / 2, row-major.
SparseMatrix<> symmetric_part(const SparseMatrix<>& a) {
  SparseMatrix<> t = a.transpose();
  return SparseMatrix<>(0.5 * (a + t));
}

/// A MATAIJ matrix of the rows this rank owns: new DOF k (row order) <- old DOF, values of `a`.
void assemble(const SparseMatrix<>& a, const std::vector<int>& new_to_old, const std::vector<int>& old_to_new,
              PetscInt first, PetscInt local, int bs, Mat* out) {
  std::vector<PetscInt> ia(local + 1, 0), ja;
  std::vector<PetscScalar> va;
  std::vector<std::pair<PetscInt, double>> row;
  for (PetscInt k = 0; k < local; ++k) {
    const int old_row = new_to_old[first + k];
    row.clear();
    for (SparseMatrix<>::InnerIterator it(a, old_row); it; ++it) row.emplace_back(old_to_new[it.col()], it.value());
    std::sort(row.begin(), row.end());
    for (const auto& [c, v] : row) {
      ja.push_back(c);
      va.push_back(v);
    }
    ia[k + 1] = static_cast<PetscInt>(ja.size());
  }
  SPH_CHECK(MatCreate(PETSC_COMM_WORLD, out));
  SPH_CHECK(MatSetSizes(*out, local, local, PETSC_DETERMINE, PETSC_DETERMINE));
  SPH_CHECK(MatSetBlockSize(*out, bs));
  SPH_CHECK(MatSetType(*out, MATAIJ));
  SPH_CHECK(MatSeqAIJSetPreallocationCSR(*out, ia.data(), ja.data(), va.data()));
  SPH_CHECK(MatMPIAIJSetPreallocationCSR(*out, ia.data(), ja.data(), va.data()));
  SPH_CHECK(MatSetOption(*out, MAT_SYMMETRIC, PETSC_TRUE));
  SPH_CHECK(MatSetOption(*out, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
}

/// The last Krylov-Schur / LOBPCG estimate, for a report of non-convergence.
struct MonitorState {
  PetscInt its = 0;
  double eig = std::numeric_limits<double>::quiet_NaN();
  double errest = std::numeric_limits<double>::quiet_NaN();
};

PetscErrorCode record_monitor(EPS, PetscInt its, PetscInt nconv, PetscScalar* eigr, PetscScalar*, PetscReal* errest,
                              PetscInt nest, void* ctx) {
  auto* m = static_cast<MonitorState*>(ctx);
  m->its = its;
  const PetscInt k = nconv < nest ? nconv : 0;  // the first pair not yet converged (else the first)
  if (nest > 0) {
    m->eig = PetscRealPart(eigr[k]);
    m->errest = errest[k];
  }
  return 0;
}

/// Sets up the inner solver on `pc` (and `ksp`) for K.
void configure_solver(const PetscCriticalLoadOptions& o, bool as_preconditioner, KSP ksp, PC pc, Mat k,
                      const Eigen::MatrixXd& x_local, int bs, std::string& label) {
  const bool parallel = world_size() > 1;
  switch (o.solver) {
    case PetscSolver::Cholesky:
      SPH_CHECK(KSPSetType(ksp, KSPPREONLY));
      SPH_CHECK(PCSetType(pc, PCCHOLESKY));
      SPH_CHECK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
      label += "cholesky(mumps)";
      return;
    case PetscSolver::CgGamg: {
      SPH_CHECK(PCSetType(pc, PCGAMG));
      // Rigid-body modes from the coordinates of the owned particles (interleaved, block size bs).
      if (x_local.cols() == bs && bs >= 2) {
        Owned<Vec, VecDestroy> coords;
        SPH_CHECK(VecCreateMPI(PETSC_COMM_WORLD, static_cast<PetscInt>(x_local.size()), PETSC_DETERMINE, &coords.h));
        SPH_CHECK(VecSetBlockSize(coords.h, bs));
        PetscScalar* c = nullptr;
        SPH_CHECK(VecGetArray(coords.h, &c));
        for (Eigen::Index p = 0; p < x_local.rows(); ++p)
          for (int d = 0; d < bs; ++d) c[p * bs + d] = x_local(p, d);
        SPH_CHECK(VecRestoreArray(coords.h, &c));
        Owned<MatNullSpace, MatNullSpaceDestroy> rigid;
        SPH_CHECK(MatNullSpaceCreateRigidBody(coords.h, &rigid.h));
        SPH_CHECK(MatSetNearNullSpace(k, rigid.h));
      }
      label += "gamg";
      break;
    }
    case PetscSolver::CgHypre:
      SPH_CHECK(PCSetType(pc, PCHYPRE));
      SPH_CHECK(PCHYPRESetType(pc, "boomeramg"));
      label += "hypre(boomeramg)";
      break;
    case PetscSolver::CgIcc:
      if (parallel) {
        SPH_CHECK(PCSetType(pc, PCBJACOBI));
        const char* prefix = nullptr;
        SPH_CHECK(KSPGetOptionsPrefix(ksp, &prefix));
        const std::string key = std::string("-") + (prefix ? prefix : "") + "sub_pc_type";
        SPH_CHECK(PetscOptionsSetValue(nullptr, key.c_str(), "icc"));
        label += "bjacobi+icc(0)";
      } else {
        SPH_CHECK(PCSetType(pc, PCICC));
        label += "icc(0)";
      }
      break;
  }
  if (as_preconditioner) {
    SPH_CHECK(KSPSetType(ksp, KSPPREONLY));
  } else {
    SPH_CHECK(KSPSetType(ksp, KSPCG));
    SPH_CHECK(KSPSetTolerances(ksp, o.ksp_rtol, PETSC_DEFAULT, PETSC_DEFAULT, o.ksp_max_iterations));
    label.insert(label.find('+') + 1, "cg+");
  }
}

/// One SLEPc solve of L x = lambda K x, and what came of it.
struct EpsRun {
  PetscErrorCode error = 0;
  std::string error_text, ksp_state;
  std::string label;
  int iterations = 0;
  long ksp_iterations = 0;
  int converged = 0;
  std::string eps_reason;
  MonitorState monitor;
  double lambda = std::numeric_limits<double>::quiet_NaN();
  double residual = std::numeric_limits<double>::quiet_NaN();  ///< ||L x - lambda K x|| / (|lambda| ||K x||)
  PetscInt eigen_above_shift = 0;                              ///< shift-invert: positive inertia of L - sigma K
};

/// Method: KrylovSchur (STSHIFT, shift 0: K^{-1} L), Lobpcg (STPRECOND with K), ShiftInvert (STSINVERT about `sigma`,
/// nearest eigenvalue; L - sigma K factored by MUMPS LDL^T, whose inertia is returned).
EpsRun run_eps(Mat L, Mat K, const PetscCriticalLoadOptions& o, PetscEigenMethod method, double tol, double sigma,
               const Eigen::MatrixXd& x_local, int bs) {
  EpsRun run;
  Owned<EPS, EPSDestroy> eps;
  SPH_CHECK(EPSCreate(PETSC_COMM_WORLD, &eps.h));
  SPH_CHECK(EPSSetOperators(eps.h, L, K));
  SPH_CHECK(EPSSetProblemType(eps.h, EPS_GHEP));
  ST st;
  KSP ksp;
  PC pc;
  SPH_CHECK(EPSGetST(eps.h, &st));
  const bool lobpcg = method == PetscEigenMethod::Lobpcg;
  run.label = petsc_eigen_method_name(method) + "+";
  if (lobpcg) {
    SPH_CHECK(EPSSetType(eps.h, EPSLOBPCG));
    SPH_CHECK(STSetType(st, STPRECOND));
    SPH_CHECK(STSetPreconditionerMat(st, K));
  } else {
    SPH_CHECK(EPSSetType(eps.h, EPSKRYLOVSCHUR));
  }
  SPH_CHECK(STGetKSP(st, &ksp));
  SPH_CHECK(KSPGetPC(ksp, &pc));
  if (method == PetscEigenMethod::ShiftInvert) {
    SPH_CHECK(STSetType(st, STSINVERT));
    SPH_CHECK(EPSSetTarget(eps.h, sigma));
    SPH_CHECK(EPSSetWhichEigenpairs(eps.h, EPS_TARGET_MAGNITUDE));
    SPH_CHECK(KSPSetType(ksp, KSPPREONLY));
    SPH_CHECK(PCSetType(pc, PCCHOLESKY));  // MUMPS symmetric indefinite (LDL^T): L - sigma K is not definite
    SPH_CHECK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    // MUMPS reports the inertia with null-pivot detection on (ICNTL 24) and, in parallel, no ScaLAPACK root (ICNTL 13).
    SPH_CHECK(PetscOptionsSetValue(nullptr, "-st_mat_mumps_icntl_13", "1"));
    SPH_CHECK(PetscOptionsSetValue(nullptr, "-st_mat_mumps_icntl_24", "1"));
    run.label += "ldlt(mumps)";
  } else {
    SPH_CHECK(STSetType(st, lobpcg ? STPRECOND : STSHIFT));
    if (!lobpcg) SPH_CHECK(STSetShift(st, 0.0));
    SPH_CHECK(EPSSetWhichEigenpairs(eps.h, EPS_LARGEST_REAL));
    configure_solver(o, lobpcg, ksp, pc, K, x_local, bs, run.label);
  }
  SPH_CHECK(KSPSetErrorIfNotConverged(ksp, lobpcg ? PETSC_FALSE : PETSC_TRUE));
  SPH_CHECK(EPSSetDimensions(eps.h, 1, o.ncv > 0 ? o.ncv : PETSC_DEFAULT, PETSC_DEFAULT));
  SPH_CHECK(EPSSetTolerances(eps.h, tol, o.max_iterations > 0 ? o.max_iterations : PETSC_DEFAULT));
  SPH_CHECK(EPSMonitorSet(eps.h, record_monitor, &run.monitor, nullptr));
  if (o.from_options) SPH_CHECK(EPSSetFromOptions(eps.h));

  // Failures inside the solve (an inner KSP that does not converge, a factorisation that breaks down) become a status.
  // (Environment SPHSTAB_PETSC_TRACE set: keep PETSc's traceback handler, which prints the full message.)
  const bool quiet = std::getenv("SPHSTAB_PETSC_TRACE") == nullptr;
  if (quiet) SPH_CHECK(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  run.error = EPSSetUp(eps.h);
  if (!run.error && method == PetscEigenMethod::ShiftInvert) {
    Mat F = nullptr;
    PetscInt nneg = 0, nzero = 0, npos = 0;
    run.error = PCFactorGetMatrix(pc, &F);
    if (!run.error) run.error = MatGetInertia(F, &nneg, &nzero, &npos);
    run.eigen_above_shift = npos + nzero;
  }
  if (!run.error && run.eigen_above_shift == 0) run.error = EPSSolve(eps.h);
  if (quiet) SPH_CHECK(PetscPopErrorHandler());
  PetscInt its = 0, lits = 0;
  EPSGetIterationNumber(eps.h, &its);
  run.iterations = static_cast<int>(std::max<PetscInt>(its, run.monitor.its));
  KSPGetTotalIterations(ksp, &lits);
  run.ksp_iterations = lits;
  if (run.error) {
    const char* text = nullptr;
    PetscErrorMessage(run.error, &text, nullptr);
    run.error_text = text ? text : "";
    PetscInt kits = 0;
    PetscReal knorm = 0;
    KSPConvergedReason kreason = KSP_CONVERGED_ITERATING;
    KSPGetIterationNumber(ksp, &kits);
    KSPGetResidualNorm(ksp, &knorm);
    KSPGetConvergedReason(ksp, &kreason);
    run.ksp_state = std::string("inner KSP ") + KSPConvergedReasons[kreason] + " after " + std::to_string(kits) +
                    " iterations at residual norm " + format_number(knorm, 3);
    return run;
  }
  if (run.eigen_above_shift > 0) return run;
  PetscInt nconv = 0;
  SPH_CHECK(EPSGetConverged(eps.h, &nconv));
  run.converged = static_cast<int>(nconv);
  EPSConvergedReason ereason;
  SPH_CHECK(EPSGetConvergedReason(eps.h, &ereason));
  run.eps_reason = EPSConvergedReasons[ereason];
  if (nconv < 1) return run;
  Owned<Vec, VecDestroy> xr, kx, lx;
  SPH_CHECK(MatCreateVecs(K, &xr.h, &kx.h));
  SPH_CHECK(VecDuplicate(kx.h, &lx.h));
  PetscScalar lambda = 0;
  SPH_CHECK(EPSGetEigenpair(eps.h, 0, &lambda, nullptr, xr.h, nullptr));
  SPH_CHECK(MatMult(K, xr.h, kx.h));
  SPH_CHECK(MatMult(L, xr.h, lx.h));
  PetscReal kx_norm = 0, r_norm = 0;
  SPH_CHECK(VecNorm(kx.h, NORM_2, &kx_norm));
  SPH_CHECK(VecAXPY(lx.h, -lambda, kx.h));
  SPH_CHECK(VecNorm(lx.h, NORM_2, &r_norm));
  run.lambda = PetscRealPart(lambda);
  run.residual = r_norm / (std::abs(run.lambda) * kx_norm);
  return run;
}

/// Status and one-line reason of a failed or unconverged run.
void fill_failure(PetscCriticalLoad& out, const EpsRun& run, double tol) {
  out.solver = run.label;
  out.converged = run.converged;
  out.residual = run.monitor.errest;
  if (run.error) {
    out.status = run.error == PETSC_ERR_NOT_CONVERGED ? Status::NotConverging : Status::NumericalIssue;
    out.reason = "SLEPc " + run.label + " failed after " + std::to_string(run.iterations) +
                 " iterations (PETSc error " + std::to_string(static_cast<int>(run.error)) +
                 (run.error_text.empty() ? "" : ": " + run.error_text) + "); " + run.ksp_state +
                 "; last eigen residual estimate " + format_number(run.monitor.errest, 3);
    return;
  }
  out.status = Status::NotConverging;
  out.reason = "SLEPc " + run.label + " converged 0 of 1 eigenpairs in " + std::to_string(run.iterations) +
               " iterations (" + run.eps_reason + "); last residual estimate " + format_number(run.monitor.errest, 3) +
               " for lambda " + format_number(run.monitor.eig, 6) + " (tol " + format_number(tol, 3) + ")";
}
}  // namespace

PetscSession::PetscSession(int* argc, char*** argv) {
  if (g_session) throw std::runtime_error("PetscSession: a session already exists in this process");
  const PetscErrorCode e = SlepcInitialize(argc, argv, nullptr, nullptr);
  if (e) throw std::runtime_error("PetscSession: SlepcInitialize failed (PETSc error " + std::to_string(e) + ")");
  g_session = true;
}

PetscSession::~PetscSession() {
  SlepcFinalize();
  g_session = false;
}

int PetscSession::rank() const { return world_rank(); }
int PetscSession::size() const { return world_size(); }

double max_over_ranks(double value) {
  double out = value;
  MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return out;
}

double wall_seconds() { return MPI_Wtime(); }

LatticeRowPartition lattice_row_partition(const Eigen::MatrixXd& x, int ranks) {
  if (ranks < 1) throw std::invalid_argument("lattice_row_partition: ranks must be >= 1, got " + std::to_string(ranks));
  if (x.rows() == 0 || x.cols() == 0)
    throw std::invalid_argument("lattice_row_partition: no particle positions (Linearisation::x is empty)");
  const int n = static_cast<int>(x.rows());
  const int ycol = static_cast<int>(x.cols()) - 1;
  const double extent = std::max(x.maxCoeff() - x.minCoeff(), 1.0 * std::abs(x.maxCoeff()));
  const double tol = 1e-9 * (extent > 0 ? extent : 1.0);
  LatticeRowPartition p;
  p.order.resize(n);
  std::iota(p.order.begin(), p.order.end(), 0);
  std::stable_sort(p.order.begin(), p.order.end(), [&](int a, int b) {
    if (x.cols() == 1) return x(a, 0) < x(b, 0);
    if (std::abs(x(a, ycol) - x(b, ycol)) > tol) return x(a, ycol) < x(b, ycol);
    return x(a, 0) < x(b, 0);
  });
  // Row starts in the sorted order.
  std::vector<int> row_start;
  for (int k = 0; k < n; ++k) {
    const bool new_row = k == 0 || x.cols() == 1 || std::abs(x(p.order[k], ycol) - x(p.order[k - 1], ycol)) > tol;
    if (new_row) row_start.push_back(k);
  }
  p.rows = static_cast<int>(row_start.size());
  if (ranks > p.rows)
    throw std::invalid_argument("lattice_row_partition: " + std::to_string(ranks) + " MPI ranks for a lattice of " +
                                std::to_string(p.rows) + " rows; run with at most " + std::to_string(p.rows) +
                                " ranks (each rank owns whole rows)");
  row_start.push_back(n);
  p.particle_offset.resize(ranks + 1);
  for (int r = 0; r <= ranks; ++r) {
    const long row = static_cast<long>(r) * p.rows / ranks;
    p.particle_offset[r] = row_start[row];
  }
  return p;
}

constexpr NamedValue<PetscEigenMethod> kPetscEigenMethodNames[] = {{PetscEigenMethod::ShiftInvert, "shift-invert"},
                                                                   {PetscEigenMethod::KrylovSchur, "krylov-schur"},
                                                                   {PetscEigenMethod::Lobpcg, "lobpcg"},
                                                                   {PetscEigenMethod::ShiftInvert, "sinvert"},
                                                                   {PetscEigenMethod::KrylovSchur, "krylovschur"}};
constexpr NamedValue<PetscSolver> kPetscSolverNames[] = {{PetscSolver::Cholesky, "cholesky"},
                                                         {PetscSolver::CgGamg, "gamg"},
                                                         {PetscSolver::CgHypre, "hypre"},
                                                         {PetscSolver::CgIcc, "icc"},
                                                         {PetscSolver::Cholesky, "mumps"}};

PetscEigenMethod parse_petsc_eigen_method(const std::string& name) {
  return parse_named(name, kPetscEigenMethodNames, "eigen method");
}
PetscSolver parse_petsc_solver(const std::string& name) { return parse_named(name, kPetscSolverNames, "K solver"); }
std::string petsc_eigen_method_name(PetscEigenMethod m) { return name_of(m, kPetscEigenMethodNames); }
std::string petsc_solver_name(PetscSolver s) { return name_of(s, kPetscSolverNames); }

PetscCriticalLoad petsc_critical_load(const Linearisation& lin, LoadDirection direction,
                                      const PetscCriticalLoadOptions& o) {
  if (!g_session) throw std::runtime_error("petsc_critical_load: no PetscSession (construct one in main)");
  if (!lin.symmetric)
    throw std::invalid_argument(
        "petsc_critical_load: the linearisation is not symmetric (the definiteness criterion needs a symmetric A)");
  if (lin.A0.rows() == 0 || lin.A0.rows() != lin.A0.cols() || lin.A1.rows() != lin.A0.rows() ||
      lin.A1.cols() != lin.A0.cols())
    throw std::invalid_argument("petsc_critical_load: A0 and A1 must be square and of the same size");
  if (lin.A1.nonZeros() == 0 || lin.A1.norm() == 0)
    throw std::invalid_argument("petsc_critical_load: A1 = 0 (no load dependence, e.g. the minus form)");
  if (lin.x.rows() != lin.free_count())
    throw std::invalid_argument("petsc_critical_load: the linearisation has no free-particle positions (x)");
  if (!(o.tol > 0 && o.tol < 1) || !(o.ksp_rtol > 0 && o.ksp_rtol < 1) || o.max_iterations < 0 || o.ncv < 0 ||
      o.ksp_max_iterations < 1 || !(o.residual_check > 0) || !(o.estimate_tol > 0 && o.estimate_tol < 1) ||
      !(o.shift_margin > 0))
    throw std::invalid_argument(
        "petsc_critical_load: options need 0 < tol < 1, 0 < ksp_rtol < 1, max_iterations >= 0, ncv >= 0, "
        "ksp_max_iterations >= 1, residual_check > 0, 0 < estimate_tol < 1 and shift_margin > 0");

  const double t0 = MPI_Wtime();
  PetscCriticalLoad out;
  out.ranks = world_size();
  const int rank = world_rank();
  const LatticeRowPartition part = lattice_row_partition(lin.x, out.ranks);
  out.lattice_rows = part.rows;
  const int bs = lin.dofs_per_particle, dofs = lin.dofs();
  out.global_dofs = dofs;
  std::vector<int> new_to_old(dofs), old_to_new(dofs);
  for (int k = 0; k < lin.free_count(); ++k)
    for (int a = 0; a < bs; ++a) {
      new_to_old[k * bs + a] = part.order[k] * bs + a;
      old_to_new[part.order[k] * bs + a] = k * bs + a;
    }
  const int p0 = part.particle_offset[rank], p1 = part.particle_offset[rank + 1];
  const PetscInt first = static_cast<PetscInt>(p0) * bs, local = static_cast<PetscInt>(p1 - p0) * bs;
  out.local_dofs = static_cast<int>(local);
  Eigen::MatrixXd x_local(p1 - p0, lin.x.cols());
  for (int k = p0; k < p1; ++k) x_local.row(k - p0) = lin.x.row(part.order[k]);

  const double sgn = load_sign(direction);
  Owned<Mat, MatDestroy> K, L;
  {
    const SparseMatrix<> k_sym = symmetric_part(lin.A0);
    assemble(k_sym, new_to_old, old_to_new, first, local, bs, &K.h);
  }
  {
    const SparseMatrix<> l_sym = symmetric_part(SparseMatrix<>(-sgn * lin.A1));
    assemble(l_sym, new_to_old, old_to_new, first, local, bs, &L.h);
  }
  SPH_CHECK(MatSetOption(K.h, MAT_SPD, PETSC_TRUE));
  SPH_CHECK(MatSetOption(K.h, MAT_SPD_ETERNAL, PETSC_TRUE));
  for (Mat m : {K.h, L.h}) {
    MatInfo info;
    SPH_CHECK(MatGetInfo(m, MAT_LOCAL, &info));
    out.petsc_matrix_bytes += info.memory;
  }
  out.assembly_seconds = MPI_Wtime() - t0;
  const double t1 = MPI_Wtime();

  const bool sinvert = o.method == PetscEigenMethod::ShiftInvert;
  if (sinvert && o.solver != PetscSolver::Cholesky)
    throw std::invalid_argument("petsc_critical_load: the shift-invert method needs the direct solver (cholesky)");
  EpsRun run;
  if (!sinvert) {
    run = run_eps(L.h, K.h, o, o.method, o.tol, 0, x_local, bs);
  } else {
    // 1. Estimate: Krylov-Schur on K^{-1} L to estimate_tol (a Ritz value, theta <= lambda_max to round-off).
    EpsRun est = run_eps(L.h, K.h, o, PetscEigenMethod::KrylovSchur, o.estimate_tol, 0, x_local, bs);
    out.iterations += est.iterations;
    out.ksp_iterations += est.ksp_iterations;
    if (est.error || est.converged < 1) {
      fill_failure(out, est, o.estimate_tol);
      out.reason = "estimate: " + out.reason;
      return out;
    }
    if (!(est.lambda > 0)) {
      run = std::move(est);  // lambda_max <= 0: no critical load of this sign; the estimate is the answer's sign
    } else {
      // 2. Shift-invert about sigma > lambda_max, checked by the inertia of L - sigma K (Sylvester: its positive
      //    eigenvalues count the lambda > sigma); raised until none is left.
      double margin = o.shift_margin;
      for (int attempt = 0;; ++attempt) {
        const double sigma = est.lambda * (1 + margin);
        run = run_eps(L.h, K.h, o, PetscEigenMethod::ShiftInvert, o.tol, sigma, x_local, bs);
        out.shift = sigma;
        out.iterations += run.iterations;
        out.ksp_iterations += run.ksp_iterations;
        ++out.factorisations;
        if (run.error || run.eigen_above_shift == 0) break;
        if (attempt == 30) {
          out.status = Status::NumericalIssue;
          out.reason = "shift-invert: " + std::to_string(run.eigen_above_shift) +
                       " eigenvalues still above the shift " + format_number(sigma, 6) + " after 30 increases";
          return out;
        }
        margin *= 4;
      }
    }
  }
  out.solver = run.label;
  out.solve_seconds = MPI_Wtime() - t1;
  out.iterations += run.iterations;
  out.ksp_iterations += run.ksp_iterations;
  out.converged = run.converged;
  if (run.error || run.converged < 1) {
    fill_failure(out, run, o.tol);
    return out;
  }
  out.lambda_max = run.lambda;
  out.residual = run.residual;
  if (!(out.residual <= o.residual_check)) {
    out.status = Status::NumericalIssue;
    out.reason = "SLEPc " + run.label + " returned lambda " + format_number(out.lambda_max, 6) + " after " +
                 std::to_string(out.iterations) + " iterations with relative residual " +
                 format_number(out.residual, 3) + " > " + format_number(o.residual_check, 3);
    return out;
  }
  out.load = out.lambda_max > 0 ? sgn / out.lambda_max : sgn * std::numeric_limits<double>::infinity();
  out.status = Status::Successful;
  return out;
}

}  // namespace sphstab
