#pragma once
/// \file run_output.hpp
/// Output of a time-stepping run as observers (integrate/run_observer.hpp): a diagnostics CSV, a VTK (.vtp + .pvd)
/// series for ParaView, and a throttled progress line. Pass their addresses in LeapfrogOptions::observers.
///
/// \code{.cpp}
/// sphstab::DiagnosticsCsv csv("run/diag.csv", system.dofs_per_particle);
/// sphstab::VtkSeries vtk("run/snap", system);
/// sphstab::ProgressReport progress("swegle");
/// opt.snapshot_every = 100;
/// opt.observers = {&csv, &vtk, &progress};
/// auto result = sphstab::run_leapfrog(system, u0, v0, opt);
/// \endcode
#include <string>
#include <utility>
#include <vector>

#include "sphstab/integrate/run_observer.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/progress.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

/// Diagnostics CSV (columns diagnostics_columns(dofs_per_particle)); rows are flushed as written, so a stopped run
/// keeps everything up to the failing state. Throws std::runtime_error if the file cannot be opened.
class DiagnosticsCsv final : public RunObserver {
 public:
  DiagnosticsCsv(const std::string& path, int dofs_per_particle);
  void record(const Diagnostics& d) override;
  void finished(const std::string& message) override;

 private:
  CsvWriter m_csv;
  int m_dpp;
};

/// Snapshots as <prefix>_<step>.vtp (points X + u; displacement, velocity, acceleration) and the index
/// <prefix>.pvd, rewritten at every snapshot so it stays valid if the run stops. Throws std::invalid_argument
/// when the system has no reference_positions or the prefix is empty.
class VtkSeries final : public RunObserver {
 public:
  VtkSeries(std::string prefix, const SecondOrderSystem& system);
  void snapshot(const StepView& state) override;

 private:
  std::string m_prefix;
  Eigen::VectorXd m_x0;
  int m_dpp;
  std::vector<std::pair<double, std::string>> m_pvd;
};

/// "label: step n/N t = ..." on stderr at most every interval_seconds (io/progress.hpp), and the final message when a
/// progress line was shown (a run shorter than the interval prints nothing).
class ProgressReport final : public RunObserver {
 public:
  explicit ProgressReport(std::string label, double interval_seconds = 2.0);
  void advanced(long n, long nsteps, double t) override;
  void finished(const std::string& message) override;

 private:
  ProgressLine m_line;
  bool m_reported = false;
};

}  // namespace sphstab
