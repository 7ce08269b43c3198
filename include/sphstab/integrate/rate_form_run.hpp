#pragma once
/// \file rate_form_run.hpp
/// Time stepping of the rate-form scheme (forms/rate_form.hpp), y = (x, v, q) with q = (rho, S) per particle.
///
/// **Predictor-corrector** (RateFormIntegrator::PredictorCorrector, the default) of Gray, Monaghan & Swift
/// [GMS2001, (6.14)-(6.18)], with the stress integrated like the density (GMS do not say; the natural reading):
///   predictor   v_p = v0 + dt a0,  rho_p = rho0 + dt drho0,  S_p = S0 + dt dS0,
///               x = x0 + dt vhat0 + dt^2/2 a0   (particles move with the XSPH velocity; x is not corrected)
///   corrector   v = v_p + dt/2 (a - a0),  rho = rho_p + dt/2 (drho - drho0),  S likewise,
/// with (a, drho, dS) = F(x, v_p, rho_p, S_p). Two rate evaluations per step (one with reuse_corrector_rate). Second
/// order in dt without XSPH; with XSPH, d^2x/dt^2 = d vhat/dt is not a0, so GMS's uncorrected x is FIRST order
/// (tests/growth/rate_form_spectrum_test.cpp measures 1.25). PositionUpdate::Trapezoid corrects x like the rest, x = x0
/// + dt/2 (vhat0 + vhat_p), which is second order with XSPH too; its predictor keeps GMS's x_p, so the step is Heun's
/// for the whole state only where a does not depend on x (at rest without pre-stress, Jvx = 0). There, for
/// y' = lambda y, both steps multiply by R(z) = 1 + z + z^2/2, z = dt lambda; on the imaginary axis
/// |R(i theta)|^2 = 1 + theta^4/4 > 1, so an undamped oscillation grows for every dt (slowly: ln|R|/dt ~
/// dt^3 |lambda|^4 / 8); see integrate/time_step.hpp. With pre-stress the dt^2/2 a0 of x_p adds dt^3/4 Jvx a0 to v
/// (measured, 1D, h = 1.3, xi = 0.9, dt max|Im lambda| = 0.96: spectral radius of the step 1.0823, max |R| 1.1011).
///
/// **Leap-frog** (RateFormIntegrator::Leapfrog): the staggered scheme of Powell's MCM code [Powell2012, algorithm
/// 1.1, (1.40)]: x, rho and S at whole steps t_n = n dt, v at half steps ("f^n = f^{n-1} + dt f'^{n-1/2},
/// f^{n+1/2} = f^{n-1/2} + dt f'^n"). Step n -> n+1 holds x^n, q^n, v^{n+1/2} and the rates of the whole-step
/// evaluation E_n = F(x^n, v*^n, q^n) (xdot^n = vhat, qdot^n, a^n):
///   1. leapfrog_xsph > 0: v^{n+1/2} <- v^{n+1/2} + eps sum_j (v_j - v_i) W_ij(x^n)    Powell (2.71), the velocity
///      itself (the literal reading; xsph.hpp: W_ij = W(r_ij) V_j), before the position update; (2.71) prints the
///      sum over i in N(j), an index typo for j in N(i)
///   2. H = F(x^n + dt/2 (v^{n+1/2} + xdot^n - v*^n), v^{n+1/2}, q^n + dt/2 qdot^n)     alg. 1.1 "Calculate
///      <D>^{n-1/2} and <rhodot>^{n-1/2}", "Calculate <sigmadot>^{n-1/2}" (1.32), (1.33), one step on
///   3. x^{n+1} = x^n + dt xdot^{n+1/2},  q^{n+1} = q^n + dt qdot^{n+1/2}  (rates of H) "Update density", "Update
///      stress", and the last line "x^n <- x^{n-1} + dt^{n+1/2} v^{n+1/2}" read as x^{n+1} <- x^n + ... (see below);
///      then the radial return of S^{n+1} when yield_stress is finite
///   4. E_{n+1} = F(x^{n+1}, v*^{n+1}, q^{n+1}), v*^{n+1} = v^{n+1/2} + dt/2 a^n        "Calculate a_i^n" (1.36)
///   5. v^{n+3/2} = v^{n+1/2} + dt a^{n+1}                                       "v^{n+1/2} <- v^{n-1/2} + dt^n a^n"
/// Start: E_0 = F(y0), v^{1/2} = v^0 + dt/2 a^0. The recorded and returned state is synchronised,
/// y^n = (x^n, v^n, q^n) with v^n = v^{n-1/2} + dt/2 a^n (velocity Verlet's velocity, second order); the kinetic
/// energy is 1/2 sum m |v^n|^2 of that velocity.
/// Why two rate evaluations per step (like the predictor-corrector, and like MCM's two particle loops): a^{n+1}
/// needs S^{n+1}, which needs the stress rate at v^{n+1/2}, which needs a^n; F evaluates every rate at one state,
/// so one call cannot serve both (a single call per step must lag one of them by a step: first order, and no longer
/// the staggered map). H's acceleration is discarded; E's rates of x and q only predict the half-step state, and its
/// velocity v* enters only the viscosity.
/// Why the half-step state: the rates of x and q depend on x and q nonlinearly (kernel gradients at the current
/// positions, volumes m/rho, the Jaumann rotation), so a midpoint step needs them at t_{n+1/2} to O(dt^2); xdot^n -
/// v*^n is the scheme's own XSPH increment vhat - v (zero without it). At rest these dependences vanish
/// (growth/rate_form_spectrum.hpp: J = [[0, X, 0], [Jvx, Jvv, Jvq], [0, Jqv, 0]]), so with Jvv = 0 (no viscosity) the
/// linearised step is exactly the classic staggered map v^{n+3/2} - 2 v^{n+1/2} + v^{n-1/2} = dt^2 B v^{n+1/2},
/// stable iff dt <= 2 / max |Im lambda| (growth/rate_form_time_step.hpp). Second order in dt (observed orders 2.00 in
/// 1D, 2.01-2.03 in 2D, tests/integrate/rate_form_leapfrog_test.cpp), except with both XSPHs at once (the midpoint
/// position is then first order in their product). Powell's literal ordering evaluates <D>^{n-1/2} at the newest
/// positions and at rho^{n-1}, S^{n-1}: the same linearised map, first order in the nonlinear terms.
/// \note Powell's XSPH smooths by a fixed epsilon per STEP, not per unit time, so a run with it does not converge as
///       dt -> 0 (halving dt doubles the smoothing per unit time; the test measures orders -0.9). The dt-consistent
///       XSPH is the scheme's drift-only one, RateFormOptions::xsph [GMS2001, (3.6)], which the leap-frog also runs.
/// \note [Powell2012, algorithm 1.1], last line: "x^n <- x^{n-1} + dt^{n+1/2} v^{n+1/2}" pairs the step
///       dt^{n+1/2} and v^{n+1/2} with x^{n-1} -> x^n; (1.40) gives x^{n+1} = x^n + dt^{n+1/2} xdot^{n+1/2}, and
///       only that reading makes the next pass's <D>^{n+1/2} use the positions the velocity v^{n+1/2} reached.
/// \note Momentum: the pair forces of the plain gradient's momentum equation are antisymmetric, sum_i m_i a_i = 0,
///       so sum m v^{n+1/2} and sum m v^n are conserved to rounding; Powell's XSPH conserves it for equal masses
///       without fixed neighbours (xsph.hpp).
///
/// **Plasticity** (yield_stress finite): after every completed step, every particle that carries a stress (free, and
/// fixed ones when they evolve) gets the von Mises radial return (models/von_mises.hpp). The initial state is not
/// returned.
///
/// **Neighbour rebuild** (neighbour_skin > 0; Verlet list): particles that move by many smoothing lengths (colliding
/// bodies, a slab pulled apart) meet pairs the discretisation's list never held. The run then works on its own copy of
/// the scheme (RateFormScheme::rebuilt) whose list has radius support + skin, built at y0 and rebuilt at the state
/// about to be evaluated whenever one of its free particles has moved more than skin / 2 (Euclidean) from the last
/// build. The check precedes every rate evaluation (stages included), so two particles have closed in by at most skin
/// since the build and every pair within the support is in the list at every evaluation. Kernel sums do not depend
/// on the list radius (rate_form.hpp), so the run is that of an exact all-pairs search, whatever the skin, to rounding;
/// and a run that never rebuilds equals the skin-0 run to rounding while no pair enters the support. The C_ij / S-SPH
/// local means use the pairs within the support at the last build, so for them the build instants are part of the
/// scheme. Rates already evaluated are kept across a rebuild. Driven particles (RateFormScheme::set_driven) keep their
/// prescribed acceleration, and Powell's XSPH (leapfrog_xsph) leaves their velocity alone too.
///
/// An unstable run is a result, not an exception: the run loop (integrate/run.hpp) stops at the first non-finite state,
/// non-positive density, kinetic-energy growth beyond the limit or exception thrown by a rate evaluation (a model
/// that refuses the state, e.g. the artificial stress at rho <= 0), and reports the step, time and particle
/// (RunStatus, message), keeping the record written so far.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/run.hpp"

namespace sphstab {

enum class PositionUpdate { Gms, Trapezoid };
enum class RateFormIntegrator {
  PredictorCorrector,  ///< [GMS2001, (6.14)-(6.18)] (default)
  Leapfrog             ///< [Powell2012, algorithm 1.1, (1.40)], staggered
};

struct RateFormRunOptions {
  double dt = 0;  ///< > 0
  /// Predictor-corrector only: GMS (6.15) uncorrected, or trapezoid-corrected (see above).
  PositionUpdate positions = PositionUpdate::Gms;
  double t_end = 0;      ///< > 0; dt is reduced to t_end / ceil(t_end / dt)
  int record_every = 1;  ///< kinetic energy recorded every k steps (>= 1), and at the last step
  double energy_growth = std::numeric_limits<double>::infinity();  ///< stop when KE > energy_growth * KE(0)
  /// Called at every record with (step, time, state); may be empty.
  std::function<void(long, double, const Eigen::VectorXd&)> observer = {};
  /// The run loop's observers (integrate/run_observer.hpp; e.g. io/run_output.hpp's ProgressReport), not owned.
  std::vector<RunObserver*> observers = {};
  RateFormIntegrator integrator = RateFormIntegrator::PredictorCorrector;
  /// Predictor-corrector only: a step's F^0 is the previous step's corrector evaluation F(x, v_p, rho_p, S_p) instead
  /// of a fresh F at the corrected state: ONE rate evaluation per step. [GMS2001, §6.2] call the scheme a
  /// "predictor-corrector leapfrog" and do not say F^0 is recomputed; read as a leapfrog, F is evaluated once per step
  /// (for a = a(x) it is velocity Verlet). The two readings differ by O(dt^2) in the rates (the corrections of v, rho,
  /// S), and both are second order without XSPH (tests/integrate/rate_form_reuse_rate_test.cpp). Not with a yield
  /// stress (the radial return changes S after the corrector's evaluation).
  bool reuse_corrector_rate = false;
  /// Leap-frog only: epsilon of Powell's XSPH (2.71), >= 0 (Powell 0.1); 0: off. The predictor-corrector's XSPH is
  /// the scheme's own, RateFormOptions::xsph [GMS2001, (3.6)].
  double leapfrog_xsph = 0;
  /// Leap-frog only, for schemes with absorbing particles (RateFormScheme::set_absorbing): their acceleration is taken
  /// from the half-step evaluation H (at v^{n+1/2}) instead of E_{n+1} (at v*^{n+1}). That is Powell's algorithm 2.3
  /// literally, "a_i^{n-1/2} uses <L>_i^{n-1/2}", so v^{n+3/2} = v^{n+1/2} + dt a(v^{n+1/2}): forward Euler (2.66) in
  /// the boundary particles' own velocities. false (default): the whole-step acceleration like every other particle.
  bool absorbing_half_step = false;
  /// Von Mises yield stress Y > 0 of the radial return after each step; +infinity (default): elastic.
  double yield_stress = std::numeric_limits<double>::infinity();
  /// Stop (RunStatus::DisplacementLimit, with the particle) when a free particle has moved more than this (max norm)
  /// from its position in the discretisation, checked every step. The neighbour list is built once, at those
  /// positions, so a run whose particles move by more than the list's margin is no longer the scheme: set this to
  /// the margin. With a neighbour_skin it is measured from the positions of the last build (a guard on the list in
  /// use, not on the whole motion). > 0; +infinity (default): unchecked.
  double max_displacement = std::numeric_limits<double>::infinity();
  /// Verlet skin of the run's own neighbour list (a length, see above), >= 0. 0 (default): the discretisation's list,
  /// built once, is kept (bit-for-bit the run without this option). > 0: list radius support + skin, rebuilt before a
  /// rate evaluation at which a free particle has moved more than skin / 2 (Euclidean) since the last build. Cost: a
  /// larger list (about ((support + skin) / support)^Dim pairs) against fewer builds.
  double neighbour_skin = 0;
};

struct RateFormRunResult : RunResult {
  std::vector<double> times, kinetic_energy;
  Eigen::VectorXd y;  ///< the last state (the failing one for a stopped run)
  /// Neighbour lists the run built, the one at y0 included (0 without a neighbour_skin: the discretisation's list).
  long neighbour_builds = 0;
};

/// The chosen integrator as a Stepper of the run loop (integrate/run.hpp), holding the synchronised state y^n. Checks
/// non-finite entries and rho <= 0 (neither recorded) and the displacement limit (max norm, from the positions of
/// the last neighbour build); watches the kinetic energy; a record appends (t, kinetic energy) and calls
/// options.observer. Of `options` it uses the integrator's own fields (integrator, positions, reuse_corrector_rate,
/// leapfrog_xsph, absorbing_half_step, yield_stress, neighbour_skin) and the observer; the run's (dt, t_end,
/// record_every, energy_growth, max_displacement) are RunOptions'. Throws std::invalid_argument as run_rate_form.
template <int Dim>
class RateFormStepper final : public Stepper {
 public:
  RateFormStepper(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0, const RateFormRunOptions& options);
  ~RateFormStepper() override;
  void step(double dt) override;
  long steps() const override;
  double time() const override;
  long evaluations() const override;
  StateFault check(const BlowUpLimits& limits) const override;
  double energy() const override;
  void record(long step, const std::vector<RunObserver*>& observers) override;

  const Eigen::VectorXd& state() const;
  long neighbour_builds() const;
  const std::vector<double>& times() const;
  const std::vector<double>& kinetic_energy() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m;
};

/// Runs the chosen integrator from y0 (size scheme.size()): the run loop (integrate/run.hpp) over a RateFormStepper. Throws std::invalid_argument for dt <= 0, t_end <= 0,
/// record_every < 1, a state of the wrong size, leapfrog_xsph < 0 (or > 0 with the predictor-corrector),
/// yield_stress <= 0, max_displacement <= 0, absorbing_half_step with the predictor-corrector, a negative or non-finite
/// neighbour_skin, or (with a skin) non-finite positions in y0 or a periodic box shorter than twice the list radius.
template <int Dim>
RateFormRunResult run_rate_form(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0,
                                const RateFormRunOptions& options);

/// The one-step map of the integrator `options` chooses, linearised at state y by central differences of the
/// integrator's own step code (the run's code, not a re-derivation), with increments delta max(1, |z_k|). The state
/// z it acts on is the integrator's whole carried state, so the map's size depends on it:
///   - predictor-corrector [GMS2001, (6.14)-(6.18)]: z = y (size scheme.size());
///   - with reuse_corrector_rate (pc1): z = (y, F^0), the carried rate is state (2 size; linearised at F^0 = F(y));
///   - leap-frog [Powell2012, algorithm 1.1]: z = (y with v*^n in its velocity slots, v^{n+1/2}, a^n) (size + 2 dofs),
///     as leapfrog_step_matrix.
/// At a rest state (F(y) = 0) the step is linear to O(delta^2), and the spectral radius rho of the matrix is the
/// integrator's amplification of small perturbations at this dt: ln(rho) / dt is the map's growth rate
/// (growth/stability_verdict.hpp). integrate/linear_step_map.hpp writes the same maps in closed form from J = dF/dy;
/// the two agree (tests/integrate/linear_step_map_test.cpp). Dense: size(z)^2 doubles and 2 size(z) steps. Throws
/// std::invalid_argument for the options run_rate_form rejects, a neighbour skin or a yield stress, or delta <= 0.
template <int Dim>
Eigen::MatrixXd rate_form_step_matrix(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y, double dt,
                                      const RateFormRunOptions& options, double delta = 1e-7);

/// The leap-frog's one-step map linearised at state y: the matrix M with dz^{n+1} = M dz^n for the staggered state
/// z = (y^n with v*^n in its velocity slots, v^{n+1/2}, a^n) (sizes scheme.size() + 2 dofs), by central differences
/// of the integrator's own step (steps 1-5 above, Powell's XSPH and absorbing_half_step included) with increments
/// delta max(1, |z_k|). At a rest state (F(y) = 0, v = 0) the map is linear to O(delta^2), so the spectral radius of M
/// decides the stability of small perturbations at this dt: the time-step limit of the whole scheme, boundary
/// conditions included, where the spectral rule of growth/rate_form_time_step.hpp (Jvv = 0) does not apply. Dense:
/// (size + 2 dofs)^2 doubles and 2 (size + 2 dofs) steps. Throws std::invalid_argument for the options run_rate_form
/// rejects, the predictor-corrector, a neighbour skin or a yield stress, or delta <= 0.
template <int Dim>
Eigen::MatrixXd leapfrog_step_matrix(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y, double dt,
                                     const RateFormRunOptions& options = {.integrator = RateFormIntegrator::Leapfrog},
                                     double delta = 1e-7);

}  // namespace sphstab
