#pragma once
/// \file stable_time_step.hpp
/// The leap-frog / central-difference stability limit of a force function linearised at a state u:
///
///   dt_max = 2 / sqrt(lambda_max(M^{-1} K)),   K = M A,  A = -da/du (coloured complex-step Jacobian at u),
///
/// M = diag(dof_mass). lambda_max is computed on the symmetric mass-scaled matrix S = M^{1/2} A M^{-1/2} (similar to
/// A; symmetric when K is, i.e. for a conservative form), with Spectra's SymEigsSolver (largest algebraic
/// eigenvalue) above `dense_max` unknowns and LAPACK dsyev below (the independent cross-check). For the central
/// difference u_{n+1} = dt^2 a_n + 2 u_n - u_{n-1} of [Ismail2009, (4.46)] (equivalent to leap-frog) a mode of
/// u'' = -A u with eigenvalue mu > 0 is bounded iff dt <= 2 / sqrt(mu).
///
/// \note Ismail's rule [Ismail2009, (4.47)] is dt = h / c with his h the SUPPORT radius of the modified mollifier,
///       i.e. 2h in sphstab's support-2h convention. On a periodic lattice of the modified mollifier at support >= 3 dx
///       the linear limit is 0.7226 (support) / c (our von Neumann check, studies/tl-time-step); h/c is unstable.
/// \note A non-symmetric K (Ismail's plain pair at a boundary, unequal volumes) is reduced to its symmetric part;
///       `asymmetry` reports ||S - S^T||_F / ||S||_F so a caller can tell when the result is only indicative.
///
/// \code{.cpp}
/// sphstab::FiniteStrainTotalLagrangian<1> tl(disc, material, 8000.0);
/// sphstab::StableTimeStep r = sphstab::stable_time_step(tl, u);
/// if (r.status == sphstab::Status::Successful) dt = 0.9 * r.dt;
/// \endcode
#include <Eigen/Core>
#include <string>

#include "sphstab/core/status.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

enum class EigenRoute { Auto, Dense, Spectra };

struct StableTimeStepOptions {
  EigenRoute route = EigenRoute::Auto;
  int dense_max = 400;        ///< Auto: LAPACK dsyev up to this many unknowns, Spectra above
  double tolerance = 1e-12;   ///< Spectra relative tolerance
  int max_iterations = 5000;  ///< Spectra restarts
  int ncv = 0;                ///< Spectra Krylov size; 0: min(n, 40)
};

struct StableTimeStep {
  double dt = 0;          ///< 2 / sqrt(lambda_max); inf when lambda_max <= 0
  double lambda_max = 0;  ///< largest eigenvalue of S (1/s^2)
  double asymmetry = 0;   ///< ||S - S^T||_F / ||S||_F before symmetrisation
  int dofs = 0;
  std::string route;  ///< "dense" or "spectra"
  Status status = Status::NotComputed;
};

/// The limit for A = -da/du (dofs x dofs) and the DOF masses m (dofs entries, > 0). Throws std::invalid_argument
/// (one line) for a non-square A, a mass of the wrong size or not > 0 and finite.
StableTimeStep stable_time_step(const SparseMatrix<>& a, const Eigen::VectorXd& mass,
                                const StableTimeStepOptions& options = {});
/// The limit of `force` linearised at u (dofs entries): A from ComplexStepJacobian, M from force.dof_mass().
/// Throws std::invalid_argument for u of the wrong size.
StableTimeStep stable_time_step(const ForceFunction& force, const Eigen::VectorXd& u,
                                const StableTimeStepOptions& options = {});

}  // namespace sphstab
