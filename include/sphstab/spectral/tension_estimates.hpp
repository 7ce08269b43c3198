#pragma once
/// \file tension_estimates.hpp
/// Closed-form estimates of the critical tension of a regular 1D lattice (Powell §3.4), computed for an interior
/// free particle i (complete neighbourhood: the sums run over the whole infinite line). With g_m = G_{i,i+m}
/// = -sign(m) W'(|m| dx) dx and H_m = W''(|m| dx) dx:
///
///   A_ii(T)      = k_ii - n T l_ii,     k_ii = sum_m g_m^2,          l_ii = sum_{m != 0} H_m
///   A_i,i+1(T)   = k_next - n T l_next, k_next = sum_m g_m g_{m-1},  l_next = -H_1
///
/// - first principal minor (3.42): A_ii < 0 for T > k_ii / (n l_ii) (inf if l_ii <= 0);
/// - second principal minors (3.49): the 2 x 2 block [A_ii A_i,i+1; A_i,i+1 A_ii] has eigenvalues A_ii -+ A_i,i+1,
///   so the smallest T > 0 with A_ii - |A_i,i+1| < 0 is min over the signs of (k_ii -+ k_next) / (n (l_ii -+ l_next))
///   for positive denominators (never above (3.42));
/// - nearest-neighbour only (3.43): T = W'(dx)^2 dx / (n W''(dx)) and (3.51): 2/3 of that (inf if W''(dx) <= 0);
/// - Swegle: unstable for T W''(dx) > 0, i.e. T_crit = 0 if W''(dx) > 0, else inf.
/// All are sufficient conditions for instability, i.e. upper bounds on the matrix T_crit (except Swegle, which uses a
/// different gradient approximation, Powell (3.44)).
///
/// \note Powell (3.41) prints W'_ij W'_ji in A_ii (a sign typo: the diagonal of K is sum_j G_ij^2 > 0) and (3.48)
///       prints W_ij W_{i+1,j} where W'_ij W'_{i+1,j} = K_{i,i+1} is meant; both are used corrected here.
#include "sphstab/jacobian/linearisation.hpp"
#include "sphstab/kernel/kernel.hpp"

namespace sphstab {

struct TensionEstimates1D {
  double first_minor = 0;                             ///< (3.42)
  double second_minor = 0;                            ///< (3.49)
  double nearest_neighbour = 0;                       ///< (3.43)
  double nearest_neighbour_minor = 0;                 ///< (3.51)
  double swegle = 0;                                  ///< 0 or inf
  double k_ii = 0, l_ii = 0, k_next = 0, l_next = 0;  ///< the entries above (T-independent parts)
};

/// Estimates from the kernel on the infinite lattice of spacing dx (h, dx > 0; n = initial_stress_multiplier >= 0; n =
/// 0 gives inf everywhere; no neighbour inside the support, 2h <= dx, gives NaN everywhere). Throws
/// std::invalid_argument for non-positive h or dx, or negative n.
TensionEstimates1D tension_estimates_1d(const Kernel<1>& kernel, double h, double dx, int n);

/// The principal-minor estimates (3.42) and (3.49) read from the matrices of the UNCORRECTED form's linearisation
/// (analytic_jacobian_1d with MomentumForm::Uncorrected: K = A0, L = -A1; k_ii = K(row, row), l_ii = L(row, row),
/// k_next = K(row, row+1), l_next = L(row, row+1)), for the form with initial-stress multiplier n; the
/// nearest-neighbour and Swegle fields are NaN (they need W'(dx), which K does not hold). For a cross-check of the
/// kernel sums against the assembled operators. Throws std::invalid_argument if row or row + 1 is out of range.
TensionEstimates1D tension_estimates_1d(const Linearisation& uncorrected, int row, int n);

/// Smallest T > 0 with the 2 x 2 principal minor not positive definite (see above); exposed for tests.
double second_minor_tension(double k_ii, double l_ii, double k_next, double l_next, int n);

}  // namespace sphstab
