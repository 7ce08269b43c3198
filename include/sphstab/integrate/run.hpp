#pragma once
/// \file run.hpp
/// The run loop: every time integrator of sphstab (the second-order leap-frog of integrate/leapfrog.hpp, the GMS
/// predictor-corrector and Powell's staggered leap-frog of integrate/rate_form_run.hpp) is a Stepper, and `run` is
/// the one loop that advances a stepper to t_end, applies the stop rules, schedules the records and snapshots, and
/// turns a run that goes bad into a result (RunStatus, message, step, time, particle) instead of an exception.
///
/// What belongs where:
///   - the loop (here): the step count and the dt that lands on t_end, the schedule (record at step 0, every
///     record_every steps, the last step, and once at the failing state of a stopped run), the energy-growth rule,
///     exceptions thrown by a step or a measurement (RunStatus::Exception), the observers' own stop rules
///     (RunObserver::stop_request, RunStatus::Stopped), progress and the final message to the observers;
///   - the stepper: one step of its integrator, its own state checks (non-finite entries, density, displacement, box)
///     and what a record or snapshot of its state is (a Diagnostics row, a kinetic-energy sample, a VTK frame).
///
/// \code{.cpp}
/// MyStepper stepper(...);              // a Stepper: step(dt), time(), check(), energy(), record(), ...
/// sphstab::RunOptions o{.dt = 0.01, .t_end = 1.0, .record_every = 10};
/// o.limits.energy_growth = 100;
/// const sphstab::RunResult r = sphstab::run(stepper, o);
/// if (!r.completed()) std::cerr << r.message << "\n";   // e.g. "energy-growth: ... at step 812, t = 8.12"
/// \endcode
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "sphstab/integrate/run_observer.hpp"

namespace sphstab {

enum class RunStatus {
  Completed,           ///< reached t_end / max_steps
  NonFinite,           ///< NaN or inf in the state
  DisplacementLimit,   ///< a particle moved further than limits.max_displacement
  LeftBox,             ///< a particle's position left [box_lo, box_hi]
  EnergyGrowth,        ///< |E| > limits.energy_growth * max(|E(0)|, limits.energy_floor)
  NonPositiveDensity,  ///< a rate-form run reached rho <= 0 (integrate/rate_form_run.hpp)
  Exception,           ///< a step or a measurement threw (e.g. a model refused the state); the message says what
  Stopped              ///< an observer asked to stop (RunObserver::stop_request: a study's own rule)
};
/// "completed", "non-finite", "displacement-limit", "left-box", "energy-growth", "non-positive-density", "exception",
/// "stopped".
std::string run_status_name(RunStatus status);

/// The stop rules of a run. The state checks (displacement, box) are the stepper's (its state says what a particle's
/// displacement is); the energy rule is the loop's, on the stepper's energy().
struct BlowUpLimits {
  int check_every = 1;  ///< steps between checks (the last step is always checked); >= 1
  double max_displacement = std::numeric_limits<double>::infinity();
  /// Box on current positions, per component; empty = no box check (steppers that have no box refuse one).
  Eigen::VectorXd box_lo, box_hi;
  /// Energy-growth factor (infinite = off).
  double energy_growth = std::numeric_limits<double>::infinity();
  double energy_floor = 0;  ///< lower bound of the reference energy (needed if E(0) = 0)
};

/// A stop found by a stepper's check of its own state (status Completed: none).
struct StateFault {
  RunStatus status = RunStatus::Completed;
  int particle = -1;  ///< the particle that failed, or -1
  std::string why;    ///< e.g. "density <= 0"; the loop appends the step, time and particle
  /// Whether the failing state is recorded (and snapshotted) at the stop. The rate form does not record a state
  /// with NaN or rho <= 0 (its kinetic energy would be meaningless); the second-order leap-frog records every one.
  bool record = true;
  explicit operator bool() const { return status != RunStatus::Completed; }
};

/// A time integrator one step at a time, as the run loop drives it. The state (and what "position", "energy",
/// "record" mean) is the stepper's; the loop only schedules.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// Advances one step of size dt. May throw: the loop reports it as RunStatus::Exception.
  virtual void step(double dt) = 0;
  virtual long steps() const = 0;
  virtual double time() const = 0;
  /// Rate (or force) evaluations so far, the start included.
  virtual long evaluations() const = 0;
  /// The stepper's own stop rules on its current state: non-finite entries first, then what the limits ask of
  /// positions (displacement, box). Throws std::invalid_argument (before the first step) for a limit it cannot check.
  virtual StateFault check(const BlowUpLimits& limits) const = 0;
  /// The energy the growth rule watches (total energy where the system has one, else kinetic).
  virtual double energy() const = 0;
  /// A record of the current state (step 0, every record_every steps, the last, the failing state).
  virtual void record(long step, const std::vector<RunObserver*>& observers) = 0;
  /// A snapshot of the current state (RunObserver::snapshot); default: none.
  virtual void snapshot(long /*step*/, const std::vector<RunObserver*>& /*observers*/) {}
};

/// The options of every run: duration, schedule, stop rules and observers (the integrator's own options are its
/// stepper's).
struct RunOptions {
  double dt = 0;        ///< > 0, finite
  double t_end = 0;     ///< > 0: run to t_end (with land_on_t_end, dt is reduced to t_end / ceil(t_end / dt))
  long max_steps = -1;  ///< used when t_end <= 0
  /// false: steps of exactly dt while the stepper's clock is short of t_end (the last step passes t_end).
  bool land_on_t_end = true;
  int record_every = 0;    ///< records at step 0, every k steps (0: none between) and at the last step
  int snapshot_every = 0;  ///< snapshots at step 0, every k steps and the last step (0: none)
  BlowUpLimits limits;
  /// Output of the run (io/run_output.hpp: diagnostics CSV, VTK series, progress line), not owned.
  std::vector<RunObserver*> observers;
};

/// What every run reports; integrator front doors extend it with their state (leapfrog.hpp, rate_form_run.hpp).
struct RunResult {
  RunStatus status = RunStatus::Completed;
  std::string message;  ///< "completed N steps of dt = ... to t = ..." or "<status>: <why> at step N, t = T[, particle P]"
  std::string reason;   ///< <why> of a stopped run (e.g. the exception's message); empty when completed
  long steps = 0;       ///< steps taken (the step at which a stop was detected)
  double time = 0;      ///< time reached
  double dt = 0;        ///< step size used
  int particle = -1;    ///< the particle that stopped the run, or -1
  long evaluations = 0;
  double wall_seconds = 0;
  /// The threads the run could use, and the steps it took on one of them (core/adaptive_threads.hpp: with several
  /// threads the run measures both counts and steps with the faster; set_fixed_threads(true) keeps the count).
  int threads = 1;
  long steps_on_one_thread = 0;
  bool completed() const { return status == RunStatus::Completed; }
};

/// The number of steps and the step size a run with these options takes (`who` names the caller in errors).
/// Throws std::invalid_argument for a non-finite or non-positive dt, neither t_end > 0 nor max_steps >= 0, or more
/// than 2^53 steps.
std::pair<long, double> run_steps(const RunOptions& options, const std::string& who);

/// Advances `stepper` from its current state (step 0) under `options`. Throws std::invalid_argument for inconsistent
/// options (run_steps, negative intervals, check_every < 1, energy_growth <= 1, a zero reference energy without a
/// floor, a null observer, a limit the stepper cannot check); never for a numerical failure, which is the result's
/// status. An exception thrown by a step, a record or a snapshot (other than std::bad_alloc) stops the run with
/// RunStatus::Exception and its message; such a failing state is not recorded again.
RunResult run(Stepper& stepper, const RunOptions& options, const std::string& who = "run");

}  // namespace sphstab
