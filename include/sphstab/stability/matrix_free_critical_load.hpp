#pragma once
/// \file matrix_free_critical_load.hpp
/// The eigen route of the critical-load engine (critical_load.hpp, Criterion::Definiteness) in O(N) memory: the
/// largest eigenvalue lambda of L x = lambda K x with K = A0, L = -sgn A1, applied matrix-free
/// (matrix_free_linearisation.hpp); tau_crit = 1/lambda_max (inf when lambda_max <= 0), load = sgn tau_crit.
/// Spectra's SymGEigsSolver in regular-inverse mode: Lanczos on K^{-1} L in the K inner product, each K^{-1} v by
/// conjugate gradients on the matrix-free A0 (K must be symmetric positive definite: fixed layers, not periodic).
/// No factorisation and no assembled matrix: memory is the linearisation plus ncv + 5 vectors.
///
/// \note The inner solves are iterative, so the eigenvalue is as accurate as the solves allow; with the default
///       cg_rtol 1e-12 it agrees with the direct route to ~1e-13 relative (n = 16, 32 square lattices). Cost: CG is
///       unpreconditioned and A0 is nearly singular on the zone-boundary modes: measured ~3 n^2 steps per solve on
///       an n x n lattice (790 at n = 16, 3200 at n = 32, i.e. condition ~n^4) and 60-280 solves per eigenvalue, so
///       the route saves memory, not time, until A0 gets a preconditioner.
///
/// \code{.cpp}
/// sphstab::MatrixFreeLinearisation lin(*disc, material, sphstab::MomentumForm::Conservative,
///                                      sphstab::PreStrainKind::Isotropic);
/// auto r = sphstab::matrix_free_critical_load(lin, sphstab::LoadDirection::Tension);
/// if (r.info() == sphstab::Status::Successful) std::cout << r.load << " after " << r.cg_iterations << " CG steps";
/// \endcode
#include <Eigen/Core>
#include <limits>
#include <string>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"

namespace sphstab {

struct MatrixFreeCriticalLoadOptions {
  double cg_rtol = 1e-12;  ///< each K solve: ||r|| <= cg_rtol ||b||
  int cg_maxit = 0;        ///< CG steps per solve; 0: 10 x dofs
  double tol = 1e-12;      ///< Spectra's relative tolerance on the Ritz value
  int maxit = 1000;        ///< Spectra restarts
  int ncv = 0;             ///< Lanczos basis size; 0: min(30, dofs)
};

struct MatrixFreeCriticalLoad {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double load = nan;        ///< signed critical load, +-inf when lambda_max <= 0
  double lambda_max = nan;  ///< largest eigenvalue of L x = lambda K x
  int solves = 0;           ///< K^{-1} v solves (one per Lanczos step)
  long cg_iterations = 0;   ///< total CG steps (A0 products)
  int max_cg_iterations = 0;
  Eigen::VectorXd mode;  ///< the eigenvector of lambda_max (K-normalised)
  Status status = Status::NotComputed;
  std::string reason;  ///< why status is not Successful (empty otherwise)
  Status info() const { return status; }
};

/// Throws std::invalid_argument for a non-symmetric linearisation (lin.symmetric() false), a form without load
/// dependence (minus: A1 = 0) or invalid options. NumericalIssue when CG meets a non-positive curvature (K not positive
/// definite), NotConverging when CG or Spectra stop at their limits.
MatrixFreeCriticalLoad matrix_free_critical_load(const MatrixFreeLinearisation& lin, LoadDirection direction,
                                                 const MatrixFreeCriticalLoadOptions& options = {});

}  // namespace sphstab
