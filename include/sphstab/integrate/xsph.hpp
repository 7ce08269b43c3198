#pragma once
/// \file xsph.hpp
/// XSPH velocity smoothing (Powell (2.71); Monaghan's XSPH) as a leap-frog velocity hook:
///   w_i = v_i + epsilon sum_{j in N(i)} (v_j - v_i) W_ij,   W_ij = W(|x_i - x_j|, h) V_j,
/// for the free particles i, with the kernel at the CURRENT positions x = x0 + u (fixed particles: u = 0) and
/// fixed particles taking part with v = 0 (clamped) unless include_fixed = false. Powell uses epsilon = 0.1.
///
/// How w is used is the SecondOrderSystem's hook_mode (second_order_system.hpp): VelocityHookMode::Replace sets
/// v <- w before the drift (Powell (2.71) "v_i += ...", applied to the velocity itself: dissipative, damps
/// short waves), DriftOnly moves the particles with w and keeps v (Monaghan's XSPH, non-dissipative).
///
/// \note Momentum: for equal masses m_i W_ij = rho V_i V_j W(r_ij) is symmetric, so the exchange between free
///       particles cancels: sum_i m_i (w_i - v_i) = -epsilon sum_{i free, j fixed} m_i v_i W_ij, i.e. exactly zero
///       without fixed neighbours (periodic sets, or include_fixed = false); the fixed layers act as a wall.
///
/// \code{.cpp}
/// sphstab::SecondOrderSystem sys = ...;
/// sys.velocity_hook = sphstab::xsph_hook(disc, {.epsilon = 0.1});
/// sys.hook_mode = sphstab::VelocityHookMode::Replace;  // Powell (2.71)
/// \endcode
#include <memory>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

struct XsphOptions {
  double epsilon = 0.1;           ///< >= 0 (Powell 2.71: 0.1; GMS use 0.5 for DriftOnly)
  bool current_positions = true;  ///< kernel at x0 + u (true) or at x0 (false: a fixed linear smoothing)
  bool include_fixed = true;      ///< fixed particles take part with v = 0
};

/// The hook w = w(u, v) (interleaved free DOFs, Dim per particle). Owns a reusable operator cache (W reassembled
/// in place every call when current_positions). Throws std::invalid_argument for a null discretisation or epsilon
/// < 0 / non-finite.
template <int Dim>
VelocityHook xsph_hook(std::shared_ptr<const Discretisation<Dim>> discretisation, const XsphOptions& options = {});

/// The linear map w = (S (x) I_Dim) v of the hook at u = 0 (reference positions): S = I + epsilon (W_ff - diag(W 1)),
/// n_free x n_free, where the row sums of W run over the free neighbours and, with include_fixed, the fixed ones.
template <int Dim>
SparseMatrix<> xsph_smoothing_matrix(const Discretisation<Dim>& discretisation, const XsphOptions& options = {});

}  // namespace sphstab
