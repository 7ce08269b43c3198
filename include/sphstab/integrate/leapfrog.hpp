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
/// An unstable run is a result: run_leapfrog (the run loop of integrate/run.hpp driving a LeapfrogStepper) stops and
/// reports a RunStatus with the step and time, and keeps everything its observers wrote so far.
///
/// \code{.cpp}
/// sphstab::SecondOrderSystem sys;
/// sys.acceleration = [](const Eigen::VectorXd& u, Eigen::VectorXd& a) { a = -u; };
/// sys.strain_energy = [](const Eigen::VectorXd& u) { return 0.5 * u.squaredNorm(); };
/// sphstab::LeapfrogOptions opt;
/// opt.dt = 0.01;
/// opt.t_end = 10.0;
/// opt.record_every = 10;
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
#include "sphstab/integrate/run.hpp"
#include "sphstab/integrate/run_observer.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

/// Kick-drift-kick stepper holding the synchronised state (u^n, v^n, a^n, t^n). Construction evaluates a(u0).
/// As a Stepper (integrate/run.hpp): checks non-finite entries, max |u_k| and the box on X + u; watches the total
/// energy (kinetic alone without a strain energy); records are Diagnostics rows, snapshots StepViews.
class LeapfrogStepper final : public Stepper {
 public:
  /// Throws std::invalid_argument if the system is invalid or u0, v0 sizes differ.
  LeapfrogStepper(SecondOrderSystem system, Eigen::VectorXd u0, Eigen::VectorXd v0, double t0 = 0);

  /// Advances one step of size dt (> 0; not checked for speed).
  void step(double dt) override;

  const Eigen::VectorXd& u() const { return m_u; }
  const Eigen::VectorXd& v() const { return m_v; }
  const Eigen::VectorXd& a() const { return m_a; }
  double time() const override { return m_t; }
  long steps() const override { return m_steps; }
  long evaluations() const override { return m_evaluations; }
  const SecondOrderSystem& system() const { return m_system; }

  /// Throws std::invalid_argument for a box without reference_positions or of the wrong size.
  StateFault check(const BlowUpLimits& limits) const override;
  double energy() const override;
  void record(long step, const std::vector<RunObserver*>& observers) override;
  void snapshot(long step, const std::vector<RunObserver*>& observers) override;

 private:
  void evaluate();
  SecondOrderSystem m_system;
  Eigen::VectorXd m_u, m_v, m_a, m_w;
  double m_t = 0;
  long m_steps = 0, m_evaluations = 0;
};

/// The leap-frog run's options: the run loop's (integrate/run.hpp; records are Diagnostics rows, energy is the total
/// energy where the system has a strain energy, else kinetic; limits.box_lo/box_hi need reference_positions) and a
/// state callback.
struct LeapfrogOptions : RunOptions {
  bool keep_history = true;  ///< keep records in LeapfrogResult::history
  int observe_every = 0;     ///< observer callback at step 0, every k steps and the last step (0: never)
  std::function<void(const StepView&)> observer;
};

struct LeapfrogResult : RunResult {
  Eigen::VectorXd u, v;
  std::vector<Diagnostics> history;
};

/// Runs leap-frog from (u0, v0) at t = 0 under `options`. Throws std::invalid_argument for inconsistent inputs
/// (never for a numerical blow-up, which is reported in the result).
LeapfrogResult run_leapfrog(const SecondOrderSystem& system, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0,
                       const LeapfrogOptions& options);

}  // namespace sphstab
