#pragma once
/// \file critical_tension.hpp
/// Critical tension of a 1D lattice: the smallest T > 0 at which A(T) = K - n T L (Powell (3.40),
/// analytic_jacobian_1d.hpp) stops being positive definite (Theorem 3.1: then the equilibrium is unstable; for the
/// conservative form positive definiteness also proves stability). Two independent routes, in tau = n T:
///
/// 1. Bisection with sparse Cholesky (Powell footnote g): A(tau) is positive definite iff CHOLMOD's LL^T succeeds.
///    Bracket from tau_start by doubling (up to tau_max: inf) or halving, then geometric bisection to
///    hi/lo - 1 <= rtol. Pattern analysed once, one numeric factorisation per tau.
/// 2. The generalised symmetric eigenproblem L x = lambda K x (K positive definite): A(tau) x = 0 iff
///    lambda = 1/tau, so tau_crit = 1/lambda_max (inf when lambda_max <= 0). Dense LAPACK dsygv for small systems,
///    Spectra's SymGEigsSolver in Cholesky mode (CHOLMOD factor of K, SortRule::LargestAlge) for large ones.
///
/// T_crit = tau_crit / n, so the forms scale exactly 1 : 2 : 4 (uncorrected : plus : conservative have T_crit in the
/// ratio 4 : 2 : 1). The minus form (n = 0) has no T dependence: T_crit = inf.
///
/// Singular K: K = G_f G_f^T is singular on a periodic lattice (translation u = 1 for every N; the sawtooth
/// (-1)^i too when N is even, since the SPH gradient of the sawtooth vanishes). These modes are eigenvectors of both
/// K and L and are projected out (deflation; the sawtooth is decided analytically: T_crit = 0 if its L-value is
/// positive). Any other failure of the Cholesky factorisation of K is reported (status NumericalIssue, tcrit NaN,
/// reason), never turned into a number. A near-singular K (CHOLMOD rcond estimate < 1e-14) is flagged in `reason`.
/// When both routes run and differ by more than 1e-8 (relative) the difference is stated in `reason`; above 1e-6 the
/// status becomes NumericalIssue. Both routes see K = G_f G_f^T only through its rounded entries, so T_crit is
/// resolved to about eps / rcond(K): for T_crit far below that (e.g. cubic, h = 2 dx, N >~ 100, where the sawtooth is
/// nearly in the null space of G_f^T) neither value can be trusted and the status says so.
#include <limits>
#include <string>

#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/linalg/cholmod_factor.hpp"
#include "sphstab/linalg/status.hpp"
#include "sphstab/stability/dominant_wavenumber.hpp"

namespace sphstab {

enum class TcritMethod { Eigen, Bisection, Both };
enum class EigenBackend { Auto, Dense, Spectra };

/// Parses "eig", "bisect", "both"; throws std::invalid_argument otherwise.
TcritMethod parse_tcrit_method(const std::string& name);
/// Parses "auto", "dense", "spectra"; throws std::invalid_argument otherwise.
EigenBackend parse_eigen_backend(const std::string& name);

struct CriticalTensionOptions {
  TcritMethod method = TcritMethod::Both;
  EigenBackend backend = EigenBackend::Auto;
  int dense_max = 200;  ///< Auto backend: dense LAPACK up to this many degrees of freedom, Spectra above
  CholmodVariant variant = CholmodVariant::Simplicial;
  double tau_start = 1e-3;  ///< first n T tried by the bisection bracket search
  double tau_max = 1e8;     ///< bisection reports inf if A is positive definite up to n T = tau_max
  double tau_min = 1e-200;  ///< bisection gives up below (status NumericalIssue)
  double rtol = 1e-13;      ///< bisection stops when hi/lo - 1 <= rtol
  double spectra_tol = 1e-13;
  int spectra_maxit = 3000;
  int spectra_ncv = 0;           ///< 0: min(size, 40)
  bool want_mode = false;        ///< keep the critical mode (eigen route) and its wavenumber
  bool deflate_periodic = true;  ///< project out translation (+ sawtooth for even N) on periodic lattices
};

struct CriticalTension {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double tcrit = nan;                ///< the result: eigen route when computed, else bisection; inf if never
  double tcrit_eigen = nan;          ///< 1 / (n lambda_max)
  double tcrit_bisection = nan;      ///< geometric mean of the final bracket
  double bisection_lo = nan;         ///< largest T found positive definite
  double bisection_hi = nan;         ///< smallest T found not positive definite
  double lambda_max = nan;           ///< largest eigenvalue of L x = lambda K x (deflated space)
  double relative_difference = nan;  ///< |eigen - bisection| / max, when both ran (0 if both inf)
  double k_rcond = nan;              ///< CHOLMOD rcond estimate of K (deflated)
  int factorizations = 0;            ///< numeric Cholesky factorisations in the bisection
  int size = 0;                      ///< degrees of freedom after deflation
  std::string eigen_backend;         ///< "dense" or "spectra" (empty if not run)
  Status status = Status::NotComputed;
  std::string reason;    ///< how the value arose; semicolon-separated, no commas (CSV-safe)
  Eigen::VectorXd mode;  ///< critical mode on the free particles (want_mode, eigen route)
  WavenumberEstimate mode_wavenumber;
};

/// T_crit of A(T) = K - n T L for a Jacobian from analytic_jacobian_1d (n = initial_stress_multiplier(form), n >= 0).
/// Throws std::invalid_argument for n < 0, non-positive or non-finite options, or mismatched K and L.
CriticalTension critical_tension(const TensionJacobian1d& jacobian, int n, const CriticalTensionOptions& options = {});

/// The line lattice used for critical-tension studies: `free` free particles at spacing dx = 1 (T is dimensionless
/// and independent of dx), either periodic or with fixed layers at every m dx < 2h, strictly, so that the layers
/// match find_neighbours (a kernel truncated with W' != 0 at its support, like the Gaussian, then keeps complete
/// neighbourhoods even when 2h is a multiple of dx up to rounding). With layer_supports = m > 1 the fixed layers
/// reach m supports (m 2h) instead: then every particle within m - 1 supports of the free block also has a complete
/// neighbourhood, which the corrected kernels need (their rows read neighbours of neighbours; m = 3 makes u = 0 an
/// equilibrium of every corrected 1D form, Powell's regular grid, ch. 3 footnote h). Throws std::invalid_argument for
/// free < 1, h <= 0 or layer_supports < 1.
ParticleSet<1> tension_lattice_1d(const Kernel<1>& kernel, double h, int free, bool periodic = false,
                                  int layer_supports = 1);

/// Convenience: jacobian of the lattice and the form, then critical_tension().
CriticalTension critical_tension_1d(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h,
                                    MomentumForm form, const CriticalTensionOptions& options = {});

}  // namespace sphstab
