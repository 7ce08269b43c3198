#pragma once
/// \file equilibrium.hpp
/// Static equilibrium a(u*) = 0 of a force function near a starting displacement, by Newton's method with the exact
/// sparse Jacobian A = -da/du (coloured complex step) and a sparse LU solve: u <- u + A^{-1} a(u).
/// Used where a formulation does not vanish at the pre-stressed lattice (e.g. the symmetrised S-SPH of Powell's
/// algorithm 4.2 near fixed layers), so that a stability test can start from its own equilibrium.
/// For piecewise force functions (switches) each Newton step uses the Jacobian of the branch at the current iterate.
#include <Eigen/Core>
#include <string>

#include "sphstab/core/status.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

struct EquilibriumOptions {
  int max_iterations = 40;   ///< Newton steps (full or chord) per load step (>= 1)
  double tolerance = 1e-14;  ///< stop when ||a(u)||_inf <= tolerance * max(||a(u0)||_inf, accel_scale)
  /// Accept a stagnating iteration (no further decrease, round-off reached) when ||a|| <= stagnation * reference.
  double stagnation = 1e-10;
  double accel_scale = 0;  ///< floor of the reference acceleration (0: ||a(u0)||_inf alone)
  /// Load continuation: solve at load * k / load_steps, k = 1..load_steps (ForceFunction::with_load), each from
  /// the linear extrapolation of the previous solutions (u0 standing for the solution at zero load).
  int load_steps = 1;
};

struct Equilibrium {
  Eigen::VectorXd u;                    ///< the last iterate (u* when converged)
  double initial_residual = 0;          ///< ||a(u0)||_inf
  double residual = 0;                  ///< ||a(u)||_inf at the returned u
  int iterations = 0;                   ///< Newton steps taken (full and chord)
  int jacobians = 0;                    ///< Jacobians computed and factorised
  Status status = Status::NotComputed;  ///< Successful, NotConverging, or NumericalIssue (singular/non-finite)
  std::string message;
};

/// Damped Newton iteration (backtracking on ||a||_inf) from u0 (size dofs()), with optional load continuation. The
/// factorised Jacobian is reused (chord steps) while each step still reduces ||a|| fourfold, and refreshed otherwise.
/// Returns at once (0 iterations) if a(u0) already meets the tolerance.
/// Throws std::invalid_argument for a size mismatch or invalid options.
Equilibrium find_equilibrium(const ForceFunction& force, const Eigen::VectorXd& u0,
                             const EquilibriumOptions& options = {});

}  // namespace sphstab
