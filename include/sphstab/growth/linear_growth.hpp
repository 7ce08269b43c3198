#pragma once
/// \file linear_growth.hpp
/// Linear-theory growth rates for comparison with time-stepped runs.
///  - matrix_growth: gamma = max Re sqrt(-mu), mu in eig(A) (dense LAPACK dgeev) for u'' = -A u (growth_rate.hpp;
///    KE ~ e^{2 gamma t}), with the fastest mode's shape on request.
///  - linear_growth: the same for A = -da/du of a ForceFunction at u, by the coloured complex-step Jacobian of the
///    SAME force function that is time-stepped.
///  - leapfrog_map_growth: the one-step map of the leap-frog algorithm itself, including a linear velocity hook
///    (XSPH), whose spectral radius rho gives log(rho)/dt; this is the linear prediction for runs with XSPH,
///    where u'' = -A u alone no longer describes the algorithm.
#include <Eigen/Core>
#include <complex>
#include <limits>
#include <string>

#include "sphstab/core/status.hpp"
#include "sphstab/system/force_function.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

struct LinearGrowth {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double gamma = nan;         ///< max Re sqrt(-mu) >= 0
  std::complex<double> mu{};  ///< the eigenvalue attaining gamma
  double lambda_max = nan;    ///< max |mu|
  double min_real = nan;      ///< min Re mu (< 0: a real exponential mode)
  double asymmetry = nan;     ///< ||A - A^T||_F / ||A||_F (linear_growth only)
  int colours = 0;            ///< complex force evaluations used for A (linear_growth only)
  Eigen::VectorXd mode;       ///< real shape of the fastest mode (unit norm), when requested
  Status status = Status::NotComputed;
  double seconds = 0;  ///< wall time
};

/// Growth of u'' = -A u for a dense square A (n >= 1). Throws std::invalid_argument for an empty, non-square or
/// non-finite A. With mode = true the eigenvectors are computed too (dgeev, about 3x slower).
LinearGrowth matrix_growth(const Eigen::MatrixXd& A, bool mode = false);

/// matrix_growth of A = -da/du at u (size dofs()), A by ComplexStepJacobian. Throws std::invalid_argument for a
/// size mismatch; a non-finite Jacobian is reported as Status::NumericalIssue.
LinearGrowth linear_growth(const ForceFunction& force, const Eigen::VectorXd& u, bool mode = false);

struct MapGrowth {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double spectral_radius = nan;  ///< max |lambda| of the one-step map
  double gamma = nan;            ///< log(spectral_radius) / dt (< 0 when a dissipative hook damps every mode)
  Status status = Status::NotComputed;
};

/// Spectral radius of the one-step map of kick-drift-kick leap-frog for u'' = -A u with an optional linear
/// velocity smoothing w = S v (S: n x n on the DOFs, e.g. xsph_smoothing_matrix (x) I_dim; empty = no hook):
///   v_h = v - dt/2 A u;  w = S v_h;  Replace: v_h <- w;  u' = u + dt w;  v' = v_h - dt/2 A u'
/// (second_order_system.hpp). Dense 2n x 2n map, all eigenvalues by dgeev. Throws std::invalid_argument for
/// size mismatches or dt <= 0.
MapGrowth leapfrog_map_growth(const Eigen::MatrixXd& A, double dt, const Eigen::MatrixXd& S, VelocityHookMode mode);

}  // namespace sphstab
