#pragma once
/// \file run_observer.hpp
/// What a time integrator tells the outside world while it runs. Output (CSV, VTK, progress lines) lives in io/
/// as observers (io/run_output.hpp); the integrator only calls them, so it never depends on a file format.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>

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
  /// A diagnostics record (step 0, every record_every steps, the last step, and the failing state of a
  /// stopped run).
  virtual void record(const Diagnostics& /*diagnostics*/) {}
  /// A snapshot of the state (step 0, every snapshot_every steps, the last step).
  virtual void snapshot(const StepView& /*state*/) {}
  /// After every step: step n of nsteps at time t (progress reporting).
  virtual void advanced(long /*n*/, long /*nsteps*/, double /*t*/) {}
  /// The run ended (completed or stopped) with this message.
  virtual void finished(const std::string& /*message*/) {}
  /// Asked after every step's records and snapshots: a non-empty reason stops the run with RunStatus::Stopped (an
  /// observer's own stop rule, e.g. two particles closer than a gap; integrate/run.hpp).
  virtual std::string stop_request() { return {}; }
};

/// An observer made of a callable, called with every snapshot of the state (RunOptions::snapshot_every; 1: after
/// every step, and at step 0). A study measures its probes this way instead of stepping by hand.
/// The callable may set a stop reason (stop(why)); the run then ends with RunStatus::Stopped after this snapshot.
class SnapshotFunction final : public RunObserver {
 public:
  explicit SnapshotFunction(std::function<void(const StepView&)> f) : m_f(std::move(f)) {}
  void snapshot(const StepView& state) override { m_f(state); }
  std::string stop_request() override { return m_stop; }
  /// Asks the run to stop after the current snapshot, with this reason.
  void stop(std::string why) { m_stop = std::move(why); }

 private:
  std::function<void(const StepView&)> m_f;
  std::string m_stop;
};

}  // namespace sphstab
