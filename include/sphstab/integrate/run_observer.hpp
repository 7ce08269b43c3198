#pragma once
/// \file run_observer.hpp
/// What a time integrator tells the outside world while it runs. Output (CSV, VTK, progress lines) lives in io/
/// as observers (io/run_output.hpp); the integrator only calls them, so it never depends on a file format.
#include <Eigen/Core>
#include <string>

#include "sphstab/integrate/diagnostics.hpp"

namespace sphstab {

/// The synchronised state after a step (references valid during the call only).
struct StepView {
  long step;
  double time;
  const Eigen::VectorXd& u;
  const Eigen::VectorXd& v;
  const Eigen::VectorXd& a;
};

/// Callbacks of a run; every method has an empty default, so an observer overrides only what it needs.
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  /// A diagnostics record (step 0, every diagnostics_every steps, the last step, and the failing state of a
  /// stopped run).
  virtual void record(const Diagnostics& /*diagnostics*/) {}
  /// A snapshot of the state (step 0, every snapshot_every steps, the last step).
  virtual void snapshot(const StepView& /*state*/) {}
  /// After every step: step n of nsteps at time t (progress reporting).
  virtual void advanced(long /*n*/, long /*nsteps*/, double /*t*/) {}
  /// The run ended (completed or stopped) with this message.
  virtual void finished(const std::string& /*message*/) {}
};

}  // namespace sphstab
