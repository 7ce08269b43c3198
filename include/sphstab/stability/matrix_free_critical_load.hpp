#pragma once
/// \file matrix_free_critical_load.hpp
/// The eigen route of the critical-load engine (critical_load.hpp, Criterion::Definiteness) in O(N) memory: the
/// largest eigenvalue lambda of L x = lambda K x with K = A0, L = -sgn A1, applied matrix-free
/// (matrix_free_linearisation.hpp); tau_crit = 1/lambda_max (inf when lambda_max <= 0), load = sgn tau_crit.
/// K must be symmetric positive definite (fixed layers, not periodic). No factorisation and no assembled matrix:
/// memory is the linearisation plus a few vectors. Three methods:
///   - Lobpcg (default; written here because Spectra's contrib LOBPCGSolver takes assembled sparse matrices, which is
///     what this route avoids): block-size-1 LOBPCG [Knyazev2001] maximising the Rayleigh quotient x^T L x / x^T K x,
///     with Rayleigh-Ritz on span{x, r, p} (r = L x - lambda K x, no preconditioner); one A0 and one A1 product per
///     step. Stops at ||r|| <= residual_tol |lambda| ||K x||; the eigenvalue error is quadratic in it (1e-8 gives
///     ~1e-13 relative). Measured on square lattices (cubic, h = 1.3 dx, conservative, isotropic): 3300 steps /
///     0.7 s at n = 32, 10900 steps / 7 s at n = 64 (unpreconditioned: the step count grows with n).
///   - BlockLobpcg: block LOBPCG in the orthogonal-basis form of [HetmaniukLehoucq2006] with a preconditioner T:
///     blocks X (Ritz vectors), W = T R (preconditioned residuals, K-orthogonalised against X and P) and P (the W/P
///     part of the last step, K-orthogonalised against X); Rayleigh-Ritz on span{X, W, P} by Eigen's
///     GeneralizedSelfAdjointEigenSolver; every block K-orthonormalised by an eigen-decomposition of its
///     diagonally scaled Gram matrix, dropping directions below 1e-12 of the largest (near-dependent). K X and L X
///     are recomputed (and P dropped) every refresh_every steps against drift. Stops when the top Ritz pair has
///     ||L x - theta K x|| <= residual_tol |theta| ||K x||. Per step: b products with A0, b with A1 and b
///     preconditioner applications (b = block_size); memory: about 10 b + 8 vectors of dofs (O(N)).
///     preconditioner LatticeSine (lattice_sine_preconditioner.hpp, stencil probed from `lin` itself, square or
///     cubic lattices only): T = (sigma_p K - L)^{-1} approximated by 2D (3D) sine transforms; start ZoneBoundary:
///     the zone-boundary modes (-1)^i, (-1)^j[, (-1)^k] times the lowest sine envelopes, polarised along each axis
///     (the shape of the critical modes). When the lattice symbol has no positive L/K ratio (no interior instability
///     in this direction, e.g. compression) no shift exists: the iteration runs without a preconditioner and says so
///     in MatrixFreeCriticalLoad::preconditioner. Measured (cubic, h = 1.3 dx, conservative, isotropic; block size 4,
///     residual_tol 1e-8, margin 0.02): 37-40 steps at n = 12 - 128, 36-37 at n = 256 - 1000 (independent of n), n =
///     1000 (2 x 10^6 DOFs) in ~40 s and 2.6 GB on 2 threads (results/critical-strain-large). In the Python prototype
///     block sizes 1 and 2 from this start converged to the second eigenvalue (relative error 1e-3): keep 4. 3D (cubic
///     lattice, same case): 39-44 steps at n = 8 - 100; 100^3 free particles (3 x 10^6 DOFs) on 2 threads in
///     results/critical-strain-3d; agreement with a dense reference 1e-13 at n = 8 and 11.
///     Threads (core/threads.hpp): operator rows, the preconditioner's transforms and the dense block algebra over
///     fixed row chunks: the same bits for any thread count. The dense block algebra (src/linalg/tall_block_algebra)
///     runs AVX2 or baseline SIMD kernels chosen at run time, with the same bits (no FMA); the step count of the small
///     3D cases moves by a few steps with any change of summation order (n = 8: 39 -> 44, n = 11: 72 -> 78 when the
///     Gram sums went from Eigen's kernels to these), e_crit by <= 3e-15 relative.
///   - LanczosCg: Spectra's SymGEigsSolver in regular-inverse mode (Lanczos on K^{-1} L in the K inner product),
///     each K^{-1} v by unpreconditioned conjugate gradients to cg_rtol. A0 is nearly singular on the zone-boundary
///     modes: ~3 n^2 CG steps per solve (790 at n = 16, 3200 at n = 32) times 60-280 solves: 8x the A0 products of
///     LOBPCG at n = 16, 190x at n = 32; kept as an independent check.
/// All agree with the direct route (critical_load, Criterion::Definiteness) to <= 1e-13 relative: n = 16 in
/// tests/stability/matrix_free_critical_load_test.cpp (BlockLobpcg: n = 16 and 32), n = 32 and 64 (LOBPCG) and
/// n = 32 (LanczosCg) by hand.
///
/// \code{.cpp}
/// sphstab::MatrixFreeLinearisation lin(*disc, material, sphstab::MomentumForm::Conservative,
///                                      sphstab::PreStrainKind::Isotropic);
/// auto r = sphstab::matrix_free_critical_load(lin, sphstab::LoadDirection::Tension,
///                                             {.method = sphstab::MatrixFreeEigenMethod::BlockLobpcg});
/// if (r.info() == sphstab::Status::Successful) std::cout << r.load << " after " << r.iterations << " steps";
/// else std::cout << r.reason;   // e.g. NotConverging: steps and residual
/// \endcode
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"

namespace sphstab {

enum class MatrixFreeEigenMethod { Lobpcg, LanczosCg, BlockLobpcg };
/// BlockLobpcg's preconditioner: none (T = I) or the lattice sine transform (square and cubic lattices).
enum class MatrixFreePreconditioner { None, LatticeSine };
/// BlockLobpcg's start block: Auto = ZoneBoundary on a square (cubic) lattice in DOF order, Random otherwise.
enum class MatrixFreeStart { Auto, ZoneBoundary, Random };

struct MatrixFreeCriticalLoadOptions {
  MatrixFreeEigenMethod method = MatrixFreeEigenMethod::Lobpcg;
  double residual_tol = 1e-8;    ///< Lobpcg: ||L x - lambda K x|| <= residual_tol |lambda| ||K x||
  int max_iterations = 1000000;  ///< Lobpcg steps
  std::uint64_t seed = 1;        ///< Lobpcg start vector (uniform random)
  double cg_rtol = 1e-12;        ///< each K solve: ||r|| <= cg_rtol ||b||
  int cg_maxit = 0;              ///< CG steps per solve; 0: 10 x dofs
  double tol = 1e-12;            ///< Spectra's relative tolerance on the Ritz value
  int maxit = 1000;              ///< Spectra restarts
  int ncv = 0;                   ///< Lanczos basis size; 0: min(30, dofs)
  // BlockLobpcg (residual_tol, max_iterations and seed as Lobpcg; max_iterations counts block steps)
  int block_size = 4;  ///< b, in [1, dofs / 3]
  MatrixFreePreconditioner preconditioner = MatrixFreePreconditioner::LatticeSine;
  double margin = 0.02;  ///< LatticeSine: sigma_p = (1 + margin) x the symbol maximum
  MatrixFreeStart start = MatrixFreeStart::Auto;
  /// ZoneBoundary start plus this much uniform random noise (relative 2-norm per column): breaks the start's
  /// reflection symmetry, which K, L and the preconditioner preserve (0: none).
  double start_noise = 0.1;
  int refresh_every = 100;    ///< recompute K X, L X and drop P every this many steps (0: never)
  bool fftw_measure = false;  ///< LatticeSine: plan with FFTW_MEASURE instead of FFTW_ESTIMATE
};

struct MatrixFreeCriticalLoad {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double load = nan;                     ///< signed critical load, +-inf when lambda_max <= 0
  double lambda_max = nan;               ///< largest eigenvalue of L x = lambda K x
  long iterations = 0;                   ///< Lobpcg / BlockLobpcg steps, or LanczosCg solves
  long a0_products = 0;                  ///< matrix-free A0 products in all (one per vector)
  long a1_products = 0;                  ///< BlockLobpcg: A1 products (one per vector)
  long preconditioner_applications = 0;  ///< BlockLobpcg: T applications (one per vector)
  double residual = nan;  ///< BlockLobpcg: ||L x - theta K x|| / (|theta| ||K x||) of the top pair at the end
  double sigma_p = nan;   ///< BlockLobpcg with LatticeSine: the preconditioner shift
  /// BlockLobpcg: "lattice-sine", "none", or "none (...)" when LatticeSine was asked for but the lattice symbol has no
  /// positive L/K ratio in this direction (compression on the square lattice): then no shift exists and the block
  /// LOBPCG runs unpreconditioned (more steps; the result is still checked by the same residual).
  std::string preconditioner;
  double setup_seconds = 0;           ///< BlockLobpcg: stencil probe and preconditioner setup (wall)
  double solve_seconds = 0;           ///< BlockLobpcg: the iteration (wall), of which:
  double product_seconds = 0;         ///<   A0 and A1 products
  double preconditioner_seconds = 0;  ///<   preconditioner applications (the rest: dense block algebra)
  int solves = 0;                     ///< LanczosCg: K^{-1} v solves (one per Lanczos step)
  long cg_iterations = 0;             ///< LanczosCg: total CG steps
  int max_cg_iterations = 0;
  Eigen::VectorXd mode;  ///< the eigenvector of lambda_max (K-normalised)
  Status status = Status::NotComputed;
  std::string reason;  ///< why status is not Successful (empty otherwise)
  Status info() const { return status; }
};

/// Throws std::invalid_argument for a non-symmetric linearisation (lin.symmetric() false), a form without load
/// dependence (minus: A1 = 0) or invalid options; BlockLobpcg with LatticeSine or ZoneBoundary also for free particles
/// that are not an n x n square (n x n x n cubic) lattice in DOF order, or a lattice too small to probe the stencil (n
/// < 11 at h = 1.3 dx: use the overload with a preconditioner set up from a larger lattice). NumericalIssue when K
/// meets a non-positive curvature (not positive definite), NotConverging when LOBPCG, CG or Spectra stop at their
/// limits.
template <int Dim>
MatrixFreeCriticalLoad matrix_free_critical_load(const MatrixFreeLinearisation<Dim>& lin, LoadDirection direction,
                                                 const MatrixFreeCriticalLoadOptions& options = {});

template <int Dim>
class LatticeSinePreconditioner;
/// BlockLobpcg with a given lattice preconditioner (options.method and options.preconditioner are ignored); its n must
/// match the lattice of `lin`.
template <int Dim>
MatrixFreeCriticalLoad matrix_free_critical_load(const MatrixFreeLinearisation<Dim>& lin, LoadDirection direction,
                                                 const MatrixFreeCriticalLoadOptions& options,
                                                 const LatticeSinePreconditioner<Dim>& preconditioner);

}  // namespace sphstab
