#pragma once
/// \file leapfrog.hpp
/// Explicit leap-frog (kick-drift-kick, velocity Verlet) for ü = a(u), with diagnostics, blow-up detection and
/// observers (output lives in io/run_output.hpp).
///
/// One step (Powell Alg. 1.1 / eq. 1.40 written in synchronised form; one force evaluation per step):
///   v^{n+1/2} = v^n + dt/2 a(u^n)
///   w = v^{n+1/2}, or the velocity hook's w (XSPH); Replace mode also sets v^{n+1/2} = w
///   u^{n+1}   = u^n + dt w
///   v^{n+1}   = v^{n+1/2} + dt/2 a(u^{n+1})
/// Second order in dt, time reversible and symplectic (without a hook). For ü = -A u (A symmetric positive
/// semidefinite in the mass inner product) it is stable iff dt <= 2 / sqrt(lambda_max(A)), and the energy
/// ½ vᵀMv + ½ uᵀKu oscillates with relative amplitude O(dt²) without secular drift (a modified energy is
/// conserved exactly).
///
/// An unstable run is a result: run_leapfrog stops and reports a RunStatus with the step and time, and keeps
/// everything its observers wrote so far.
///
/// \code{.cpp}
/// sphstab::SecondOrderSystem sys;
/// sys.acceleration = [](const Eigen::VectorXd& u, Eigen::VectorXd& a) { a = -u; };
/// sys.strain_energy = [](const Eigen::VectorXd& u) { return 0.5 * u.squaredNorm(); };
/// sphstab::LeapfrogOptions opt;
/// opt.dt = 0.01;
/// opt.t_end = 10.0;
/// opt.diagnostics_every = 10;
/// opt.limits.energy_growth = 10.0;
/// auto result = sphstab::run_leapfrog(sys, Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1), opt);
/// if (result.status != sphstab::RunStatus::Completed) std::cerr << result.message << "\n";
/// \endcode
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "sphstab/integrate/diagnostics.hpp"
#include "sphstab/integrate/run_observer.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

/// Kick-drift-kick stepper holding the synchronised state (u^n, v^n, a^n, t^n). Construction evaluates a(u0).
class LeapfrogStepper {
 public:
  /// Throws std::invalid_argument if the system is invalid or u0, v0 sizes differ.
  LeapfrogStepper(SecondOrderSystem system, Eigen::VectorXd u0, Eigen::VectorXd v0, double t0 = 0);

  /// Advances one step of size dt (> 0; not checked for speed).
  void step(double dt);

  const Eigen::VectorXd& u() const { return m_u; }
  const Eigen::VectorXd& v() const { return m_v; }
  const Eigen::VectorXd& a() const { return m_a; }
  double time() const { return m_t; }
  long steps() const { return m_steps; }
  long force_evaluations() const { return m_evaluations; }
  const SecondOrderSystem& system() const { return m_system; }

 private:
  void evaluate();
  SecondOrderSystem m_system;
  Eigen::VectorXd m_u, m_v, m_a, m_w;
  double m_t = 0;
  long m_steps = 0, m_evaluations = 0;
};

enum class RunStatus {
  Completed,          ///< reached t_end / max_steps
  NonFinite,          ///< NaN or inf in u, v or a
  DisplacementLimit,  ///< max |u_k| > limits.max_displacement
  LeftBox,            ///< a particle's X + u left [box_lo, box_hi]
  EnergyGrowth,       ///< |E| > limits.energy_growth * max(|E(0)|, limits.energy_floor)
  NonPositiveDensity  ///< a rate-form run reached rho <= 0 (integrate/rate_form_run.hpp)
};
std::string run_status_name(RunStatus status);

struct BlowUpLimits {
  int check_every = 1;  ///< steps between state checks (NaN, displacement, box, energy); >= 1
  double max_displacement = std::numeric_limits<double>::infinity();
  /// Box on current positions X + u, per component (size dofs_per_particle each); empty = no box check.
  Eigen::VectorXd box_lo, box_hi;
  /// Energy-growth factor (infinite = off). E = total energy if the system has a strain energy, else kinetic.
  double energy_growth = std::numeric_limits<double>::infinity();
  double energy_floor = 0;  ///< lower bound of the reference energy (needed if E(0) = 0)
};

struct LeapfrogOptions {
  double dt = 0;        ///< > 0 (use cfl_time_step for the CFL rule)
  double t_end = 0;     ///< > 0: run to t_end (with land_on_t_end, dt is reduced to t_end / ceil(t_end / dt))
  long max_steps = -1;  ///< used when t_end <= 0
  bool land_on_t_end = true;
  int diagnostics_every = 0;  ///< record every k steps (0: only step 0 and the last step)
  bool keep_history = true;   ///< keep records in RunResult::history
  int snapshot_every = 0;     ///< RunObserver::snapshot every k steps (0: none)
  int observe_every = 0;      ///< observer callback every k steps (0: never)
  std::function<void(const StepView&)> observer;
  /// Output of the run (io/run_output.hpp: diagnostics CSV, VTK series, progress line), not owned.
  std::vector<RunObserver*> observers;
  BlowUpLimits limits;
};

struct RunResult {
  RunStatus status = RunStatus::Completed;
  std::string message;  ///< human-readable outcome incl. step and time
  long steps = 0;       ///< steps taken (the step at which a blow-up was detected)
  double time = 0;      ///< time reached
  double dt = 0;        ///< step size used
  Eigen::VectorXd u, v;
  std::vector<Diagnostics> history;
  double wall_seconds = 0;
  long force_evaluations = 0;
  bool completed() const { return status == RunStatus::Completed; }
};

/// Runs leap-frog from (u0, v0) at t = 0 under `options`. Throws std::invalid_argument for inconsistent inputs
/// (never for a numerical blow-up, which is reported in the result).
RunResult run_leapfrog(const SecondOrderSystem& system, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0,
                       const LeapfrogOptions& options);

}  // namespace sphstab
