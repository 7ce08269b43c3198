#pragma once
/// \file growth_run.hpp
/// A perturbation run for stability tests (Swegle test, 1D pre-tensioned lattice): leap-frog from a small initial
/// velocity with any force function, optional XSPH velocity smoothing, kinetic-energy samples, a displacement limit
/// at which the run stops with a status (a blow-up is a result, never an exception), and the exponential growth
/// rate fitted over the linear window (growth_fit.hpp; KE ~ e^{2 gamma t}).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/growth/growth_fit.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/xsph.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

struct GrowthRunOptions {
  double dt = 0;                  ///< time step (> 0)
  double t_end = 0;               ///< run length (> 0)
  double displacement_limit = 0;  ///< stop (blow-up) when max |u - u0| exceeds it (> 0; length units)
  double linear_limit = 0;        ///< end of the fit window: max |u - u0| <= linear_limit (> 0)
  int record_every = 5;           ///< kinetic-energy sample every k steps (>= 1)
  bool xsph = false;              ///< XSPH velocity hook (xsph.hpp)
  XsphOptions xsph_options;       ///< epsilon 0.1 (Powell 2.71)
  VelocityHookMode xsph_mode = VelocityHookMode::Replace;
  GrowthWindowOptions window;
  /// Reference energy of the growth window: the initial kinetic energy (0) or, for a run that does not start in
  /// equilibrium, the largest kinetic energy within [0, reference_time] (the response to the initial imbalance);
  /// the window then ends with the run instead of with the linear regime.
  double reference_time = 0;
  std::vector<RunObserver*> observers;  ///< passed to the leap-frog run (e.g. io/run_output.hpp's ProgressReport)
};

struct GrowthRun {
  RunStatus status = RunStatus::Completed;
  std::string message;
  long steps = 0;
  double t_stop = 0;  ///< time reached (the blow-up time when status != Completed)
  double dt = 0;
  std::vector<double> t, kinetic, max_displacement;  ///< samples (max |u - u0|)
  double t_linear_end = 0;                           ///< last sample time with max |u - u0| <= linear_limit
  Eigen::VectorXd u_linear;                          ///< u - u0 at t_linear_end (the developed mode while still linear)
  Eigen::VectorXd u_end;                             ///< final displacement
  double initial_energy = 0;                         ///< 1/2 sum m v0^2
  double reference_energy = 0;
  ExponentialGrowthFit fit;
  double wall_seconds = 0;

  bool blew_up() const { return status != RunStatus::Completed; }
};

/// Runs u'' = a(u) from (u0, v0) (empty u0 = zero) with the masses force->dof_mass(). Throws
/// std::invalid_argument for inconsistent inputs; a blow-up is reported in the result.
template <int Dim>
GrowthRun run_growth_test(std::shared_ptr<const Discretisation<Dim>> discretisation,
                          std::shared_ptr<const ForceFunction> force, const Eigen::VectorXd& u0,
                          const Eigen::VectorXd& v0, const GrowthRunOptions& options);

}  // namespace sphstab
