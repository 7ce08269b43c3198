#pragma once
/// \file linear_step_map.hpp
/// The one-step maps of the rate-form integrators (integrate/rate_form_run.hpp) for a LINEAR system y' = J y, in
/// closed form, derived from the stepper code as it is implemented (src/integrate/rate_form_run.cpp), not from the
/// papers. At a fixed point y* (F(y*) = 0, e.g. a uniform state at rest) the same matrices with J = dF/dy at y* are
/// the stepper's linearisation exactly: every stepper is affine in the rates it evaluates, and all its stage states
/// equal y*, so dF = J dy is all that enters (elsewhere the stages' J differ from J(y*) by O(dt |F(y*)|)). Not
/// covered: a yield stress, Powell's XSPH and absorbing_half_step act outside F; only rate_form_step_matrix, by
/// central differences of the stepper, sees them.
///
/// Notation (all n x n, n = size of y): P the diagonal projector on the free particles' position slots, Q = I - P,
/// S the shift that puts each velocity slot's entry into its position slot ((S w)[x_k] = w[v_k], zero elsewhere),
/// so S J y is the acceleration a0 written in the position slots. V (nv x n) selects the velocity slots, V^T inserts
/// them, X selects the position slots; nv = free velocity DOFs.
///
/// **Predictor-corrector** [GMS2001, (6.14)-(6.18)], two rate evaluations per step:
///   y_p = y + dt f0 + dt^2/2 S f0  (f0 = J y; x_p = x + dt vhat0 + dt^2/2 a0, GMS (6.15))   => y_p = A y,
///   A = I + dt J + dt^2/2 S J;  f1 = J y_p;
///   Gms positions:  y1 = y_p + dt/2 Q (f1 - f0)          (x not corrected)  => M = A + dt/2 Q J (A - I)
///   Trapezoid:      y1 = Q (y_p + dt/2 (f1 - f0)) + P (y + dt/2 (f0 + f1))
///                   => M = Q A + dt/2 Q J (A - I) + P (I + dt/2 J + dt/2 J A).
/// Expanded, Gms: M = I + dt J + dt^2/2 (S J + Q J^2) + dt^3/4 Q J S J. Where the position rows of J are the
/// velocity selection (no XSPH: x' = v), P J^2 = S J, so M = R(dt J) + dt^3/4 Q J S J with Heun's polynomial
/// R(z) = 1 + z + z^2/2: a polynomial in dt J plus the uncorrected positions' term, which vanishes when the
/// accelerations do not depend on x (Jvx = 0: at rest without pre-stress). On the imaginary axis
/// |R(i theta)|^2 = 1 + theta^4/4, so a neutral oscillation of frequency omega grows at
/// ln|R| / dt = ln(1 + (omega dt)^4 / 4) / (2 dt) ~ omega^4 dt^3 / 8.
///
/// **PC1** (reuse_corrector_rate): the same step with f0 = g, the rate carried from the previous step's corrector
/// evaluation, and g1 = f1. The map acts on (y, g) (2n):
///   y_p = y + B g,  B = dt I + dt^2/2 S;  f1 = J (y + B g);
///   Gms:        y1 = y_p + dt/2 Q (f1 - g)
///   Trapezoid:  y1 = Q (y_p + dt/2 (f1 - g)) + P (y + dt/2 (g + f1));      g1 = f1.
/// The consistent subspace g = J y is not invariant, so the map has n more eigenvalues than the PC's.
///
/// **Staggered leap-frog** [Powell2012, algorithm 1.1] (MCM), state z = (y, vh, a) (n + 2 nv), y's velocity slots
/// holding v*^n (they enter only through F, e.g. a viscosity), vh = v^{n+1/2}, a = a^n:
///   fe = J y;  y_h = (I - V^T V)(y + dt/2 fe) + X^T dt/2 (vh - V y) + V^T vh      (step 2: the half-step state)
///   y' = (I - V^T V)(y + dt J y_h) + V^T (vh + dt/2 a)                               (steps 3, 4)
///   a' = V J y';  vh' = vh + dt a'                                                   (steps 4, 5)
/// At rest without viscosity this is the classic staggered map v^{n+3/2} - 2 v^{n+1/2} + v^{n-1/2} = dt^2 B v^{n+1/2}
/// (rate_form_run.hpp), neutral for dt max|Im lambda| <= 2.
///
/// All maps are dense (products of dense n x n matrices: O(n^3)); they are meant for the small lattices on which a
/// verdict is computed (growth/stability_verdict.hpp). Shapes: J n x n; returned matrices as listed above.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sphstab/integrate/rate_form_run.hpp"

namespace sphstab {

/// Where the free particles' positions and velocities sit in the state vector y: for each free velocity DOF k
/// (f Dim + a, docs/conventions.md §1) the offset of x_k and of v_k in y. Entries of y in neither list (density,
/// stress, fixed particles) are advanced like any other rate.
struct StateLayout {
  int size = 0;               ///< length of y
  std::vector<int> position;  ///< offset of x_k in y, one per free velocity DOF
  std::vector<int> velocity;  ///< offset of v_k in y, same length
  /// Throws std::invalid_argument("who: ...") for lists of different lengths, offsets outside [0, size) or repeated.
  void validate(const std::string& who) const;
};

/// The layout of a rate-form scheme's state (position_offset / velocity_offset of its free particles).
template <int Dim>
StateLayout state_layout(const RateFormScheme<Dim>& scheme);

/// The predictor-corrector's map M (n x n), y^{n+1} = M y^n, for y' = J y (see above). Throws std::invalid_argument
/// for a J that is not layout.size square or not finite, an invalid layout, or dt <= 0.
Eigen::MatrixXd predictor_corrector_map(const Eigen::MatrixXd& J, const StateLayout& layout, double dt,
                                        PositionUpdate positions = PositionUpdate::Gms);

/// PC1's map (2n x 2n) on (y, g), g the carried rate (see above). Throws as predictor_corrector_map.
Eigen::MatrixXd predictor_corrector_reuse_map(const Eigen::MatrixXd& J, const StateLayout& layout, double dt,
                                              PositionUpdate positions = PositionUpdate::Gms);

/// The staggered leap-frog's map ((n + 2 nv) square) on (y, v^{n+1/2}, a^n) (see above). Throws as
/// predictor_corrector_map.
Eigen::MatrixXd staggered_leapfrog_map(const Eigen::MatrixXd& J, const StateLayout& layout, double dt);

/// The map of the integrator that `options` selects (integrator, reuse_corrector_rate, positions) at dt =
/// options.dt: the same state vector as rate_form_step_matrix. Throws std::invalid_argument as above, and for the
/// options that act outside F (leapfrog_xsph > 0, absorbing_half_step, a finite yield stress): their map needs
/// rate_form_step_matrix.
Eigen::MatrixXd linear_step_map(const Eigen::MatrixXd& J, const StateLayout& layout, const RateFormRunOptions& options);

/// A short name of the integrator `options` selects: "pc", "pc-trapezoid", "pc1", "pc1-trapezoid" or "leapfrog".
std::string rate_form_integrator_name(const RateFormRunOptions& options);

/// Selects the integrator named "pc" (or "predictor-corrector"), "pc1" (reuse_corrector_rate) or "leapfrog" in
/// `options` (integrator and reuse_corrector_rate; the rest untouched). Throws std::invalid_argument("unknown
/// integrator '<name>' (valid: pc, pc1, leapfrog)") otherwise.
void select_rate_form_integrator(RateFormRunOptions& options, const std::string& name);

}  // namespace sphstab
