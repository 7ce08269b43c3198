#pragma once
/// \file critical_load_problem.hpp
/// The front door of the critical-load engines: `critical_load(problem, direction, options)` takes a problem
/// described by its parameters (an elastic lattice with a pre-strain; nothing built yet), chooses the route, checks
/// the memory the route needs before anything is allocated, builds the linearisation that route takes, solves, and
/// returns ONE result type, `CriticalLoadResult`, with the route's own result kept as its diagnostics.
///
/// Routes (CriticalLoadRoute); every one solves the same question, the smallest |e| at which A(e) = A0 + e A1
/// leaves the stable set in `direction` (critical_load.hpp):
///   - Assembled: analytic_jacobian_2d (2D) or assemble_by_products of the matrix-free linearisation (3D, small
///     problems only) and critical_load(lin, ...): CHOLMOD bisection and the generalised eigenproblem, or the spectrum
///     criterion for a non-symmetric A (options.assembled). Diagnostics: CriticalLoadResult::assembled.
///   - MatrixFree: MatrixFreeLinearisation<Dim> and matrix_free_critical_load's block LOBPCG with the lattice sine
///     preconditioner (options.matrix_free), O(N) memory; square (2D) or cubic (3D) lattices with fixed layers,
///     symmetric A. A lattice smaller than the stencil probe (n < probe_lattice_size) takes the stencil of a probe-size
///     lattice of the same problem; where the lattice symbol has no positive L/K ratio (no interior instability in
///     this direction) no shift exists and the iteration runs unpreconditioned (a fallback, said in `reason`).
///     Diagnostics: CriticalLoadResult::matrix_free.
///   - Symbol: a periodic 2D lattice, exactly, by its Fourier symbols on the lattice's wavevectors
///     (critical_strain_periodic_symbol_2d, criterion: spectrum). Diagnostics: CriticalLoadResult::symbol.
///   - Distributed: the assembled linearisation handed to options.distributed, a solver the core library does not
///     provide: the PETSc/SLEPc backend (library sphstab_petsc, distributed/petsc_critical_load.hpp) supplies one,
///     `petsc_critical_load_solver()`. Without it this route is bad input. Diagnostics:
///     CriticalLoadResult::distributed.
///   - Auto: periodic -> Symbol; 3D -> MatrixFree; 2D -> Assembled when its estimated memory fits the limit
///     (core/memory_budget.hpp), else MatrixFree when that route applies (a FALLBACK, reported in route_reason and
///     at the head of reason), else Assembled (which then refuses with the memory error).
///
/// Memory: critical_load_memory_bytes() is the estimate of each route (lattice, neighbours, operators, Jacobian, the
/// dense copies of a dense eigen route; the block LOBPCG's blocks), checked with require_memory() before anything
/// is built; the library checks each allocation again (and CHOLMOD's fill from its symbolic analysis).
///
/// \code{.cpp}
/// sphstab::ElasticLatticeProblem<2> p{.lattice = sphstab::LatticeType::Square, .n = 64, .h = 1.3};
/// sphstab::CriticalLoadResult r = sphstab::critical_load(p, sphstab::LoadDirection::Tension);
/// if (r.info() == sphstab::Status::Successful)
///   std::cout << r.load << " by " << sphstab::critical_load_route_name(r.route) << ": " << r.route_reason;
/// \endcode
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/jacobian/linearisation.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/matrix_free_critical_load.hpp"

namespace sphstab {

enum class CriticalLoadRoute { Auto, Assembled, MatrixFree, Symbol, Distributed };
/// Parses "auto", "assembled", "matrix-free", "symbol", "petsc" (or "distributed"); throws std::invalid_argument.
CriticalLoadRoute parse_critical_load_route(const std::string& name);
/// "auto", "assembled", "matrix-free", "symbol", "distributed".
std::string critical_load_route_name(CriticalLoadRoute route);
/// "eig", "bisect", "both" (the names parse_critical_load_method accepts).
std::string critical_load_method_name(CriticalLoadMethod method);

/// An elastic lattice under a uniform pre-strain e (forms/elasticity_2d.hpp; 3D: the same terms,
/// jacobian/matrix_free_linearisation.hpp): n free particles per side (n x n or n x n x n), fixed layers completing
/// every neighbourhood (support 2h) or periodic (2D), spacing dx = 1.
template <int Dim>
struct ElasticLatticeProblem {
  static_assert(Dim == 2 || Dim == 3, "ElasticLatticeProblem: 2D or 3D");
  LatticeType lattice = Dim == 2 ? LatticeType::Square : LatticeType::Cubic;  ///< 2D: square, hex, face-centred
  int n = 16;                                                                 ///< free particles per side, >= 1
  bool periodic = false;                                                      ///< 2D only
  KernelType kernel = KernelType::CubicSpline;
  double h = 1.3;  ///< h / dx
  /// Plane strain with nu = 0.3 (E = 2.1, Powell's Swegle test); rho cancels in e_crit.
  ElasticMaterial material = ElasticMaterial::from_lame(1.2115384615384615, 0.80769230769230769, 1.0);
  MomentumForm form = MomentumForm::Conservative;
  PreStrainKind prestrain = PreStrainKind::Isotropic;

  /// Unknowns, Dim n^Dim (a double: the count is only estimated before anything is built).
  double dofs() const { return Dim * (Dim == 2 ? double(n) * n : double(n) * n * n); }
};

/// What a distributed route reports (filled by the solver that options.distributed holds; PETSc:
/// distributed/petsc_critical_load.hpp's PetscCriticalLoad, field by field).
struct DistributedCriticalLoad {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double load = nan;          ///< signed critical load; +-inf when lambda_max <= 0; NaN unless Successful
  double lambda_max = nan;    ///< largest eigenvalue of L x = lambda K x
  double residual = nan;      ///< relative residual of the returned pair
  int iterations = 0;         ///< outer eigen-solver iterations
  long inner_iterations = 0;  ///< inner (K solve) iterations in all
  int ranks = 0;              ///< processes the rows were distributed over
  double assembly_seconds = 0, solve_seconds = 0;
  std::string solver;  ///< e.g. "krylovschur+cholesky(mumps)"
  Status status = Status::NotComputed;
  std::string reason;  ///< why status is not Successful (empty otherwise); one line
};
/// A distributed eigen route: collective where the backend needs it; the same `lin` on every process.
using DistributedCriticalLoadSolver = std::function<DistributedCriticalLoad(const Linearisation&, LoadDirection)>;

struct CriticalLoadRouteOptions {
  CriticalLoadRoute route = CriticalLoadRoute::Auto;
  /// Assembled route (and the Auto choice's dense estimate): the 2D studies' settings with the mode kept.
  CriticalLoadOptions assembled = [] {
    CriticalLoadOptions o = CriticalLoadOptions::strain_2d();
    o.want_mode = true;
    return o;
  }();
  /// MatrixFree route: block LOBPCG with the lattice sine preconditioner.
  MatrixFreeCriticalLoadOptions matrix_free{.method = MatrixFreeEigenMethod::BlockLobpcg};
  /// Distributed route: the solver (empty: the route is not available in this program).
  DistributedCriticalLoadSolver distributed;
  /// The text before " needs ~X GB ..." in a memory refusal, per route; empty: "critical_load: <Dim>D <lattice> n = N,
  /// h/dx = H, <route> route". (The command line puts its own options there.)
  std::function<std::string(CriticalLoadRoute)> memory_label;
};

/// The one result of the front door. The common fields are filled by every route (NaN / empty where a route does not
/// compute them); the route's own result is kept in exactly one of the diagnostics below.
struct CriticalLoadResult {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double load = nan;                 ///< signed critical load; +-inf when stable up to the route's limit; 0; NaN
  double load_eigen = nan;           ///< the eigen route's value (assembled eigen, matrix-free, distributed)
  double load_bisection = nan;       ///< assembled: the bisection's value
  double relative_difference = nan;  ///< assembled: |eigen - bisection| / max
  LoadDirection direction = LoadDirection::Tension;
  CriticalLoadRoute route = CriticalLoadRoute::Auto;  ///< the route taken (never Auto)
  Criterion criterion = Criterion::Definiteness;      ///< the criterion actually used
  std::string method;   ///< assembled: "eig", "bisect", "both"; "lobpcg"; "symbol"; distributed: its solver
  std::string backend;  ///< assembled: "dense", "spectra", "dgeev" or "none"; "matrix-free"; "none"; "distributed"
  InstabilityMechanism mechanism = InstabilityMechanism::None;
  WavevectorEstimate mode_wavevector;  ///< dominant wavevector of the critical mode (assembled, symbol)
  /// How the route was chosen: "asked", "auto: ..." or "fallback: ..." (with the estimate that decided it).
  std::string route_reason;
  bool fallback = false;         ///< Auto left the assembled route for memory, or the preconditioner was dropped
  double memory_estimate = nan;  ///< bytes estimated for the route taken (critical_load_memory_bytes)
  Status status = Status::NotComputed;
  std::string reason;  ///< how the value arose; semicolon-separated, no commas (CSV-safe)
  Status info() const { return status; }

  std::optional<CriticalLoad> assembled;               ///< route Assembled
  std::optional<MatrixFreeCriticalLoad> matrix_free;   ///< route MatrixFree
  std::optional<SymbolCriticalStrain> symbol;          ///< route Symbol
  std::optional<DistributedCriticalLoad> distributed;  ///< route Distributed
};

/// Estimated peak bytes of `route` (not Auto) on `problem`, before anything is built. Assembled: lattice,
/// neighbours, G and H, the Jacobian, and 5 dense copies when the assembled options pick a dense route; Symbol: 0;
/// MatrixFree: the stored operator values and the block LOBPCG's 10 b + 8 vectors; Distributed: as Assembled
/// without dense copies. Throws std::invalid_argument for Auto.
template <int Dim>
double critical_load_memory_bytes(const ElasticLatticeProblem<Dim>& problem, CriticalLoadRoute route,
                                  const CriticalLoadRouteOptions& options = {});

/// The route `critical_load(problem, ...)` takes, and why: resolves Auto, validates the problem against the route
/// (std::invalid_argument: n, h, lattice or periodic the route cannot take) and checks its memory estimate
/// (MemoryLimitError). Call it on every case of a sweep first to refuse before any output.
struct CriticalLoadRouteChoice {
  CriticalLoadRoute route = CriticalLoadRoute::Auto;
  std::string reason;  ///< "asked", "auto: ...", "fallback: ..."
  bool fallback = false;
  double memory_estimate = 0;
};
template <int Dim>
CriticalLoadRouteChoice choose_critical_load_route(const ElasticLatticeProblem<Dim>& problem,
                                                   const CriticalLoadRouteOptions& options = {});

/// Critical pre-strain of `problem` in `direction` by the route choose_critical_load_route() gives. Throws as it
/// does, as the route's engine does for invalid input (e.g. a non-symmetric A on the matrix-free route), and
/// std::invalid_argument for the Distributed route without options.distributed; numerical outcomes are a status.
template <int Dim>
CriticalLoadResult critical_load(const ElasticLatticeProblem<Dim>& problem, LoadDirection direction,
                                 const CriticalLoadRouteOptions& options = {});

/// Free particles per side of the smallest lattice whose stencil can be probed (lattice_stencil.hpp): the central
/// particle's A0 column reaches two hops of the support, 2 ceil(2 s) lattice spacings (s = support / dx), and must
/// stay off the edge.
int probe_lattice_size(double support_over_dx);

}  // namespace sphstab
