#pragma once
/// \file swegle_run.hpp
/// Runs the Swegle test scene (problems/swegle.hpp) [Powell2012, ch. 4 §2.2]: any force function advanced with
/// leap-frog (optionally with XSPH) through run_growth_test (growth_run.hpp): kinetic-energy samples, a blow-up
/// status at a displacement limit, the fitted growth rate.
#include <Eigen/Core>
#include <memory>

#include "sphstab/growth/growth_run.hpp"
#include "sphstab/problems/swegle.hpp"

namespace sphstab {

/// Run settings in the scene's units: dt = courant h / c_P, limits as multiples of dx.
struct SwegleRunOptions {
  double t_end = 20;                ///< us (> 0)
  double courant = 0.3;             ///< dt = courant h / c_P (> 0)
  double displacement_limit = 0.1;  ///< stop (blow-up) when max |u - u0| > limit * dx (Lagrangian neighbour list:
                                    ///< pairs at the support edge could change beyond ~0.1 dx)
  double linear_limit = 1e-3;       ///< end of the fit window: max |u - u0| <= limit * dx
  GrowthRunOptions run;             ///< record_every, xsph, window, reference_time, progress (dt, t_end and the
                                    ///< limits are set from the fields above)
};

/// Runs the scene from (u0, scene.v0) with `force` (u0 empty = the lattice); see growth_run.hpp.
GrowthRun run_swegle(const SwegleScene& scene, std::shared_ptr<const ForceFunction> force,
                     const SwegleRunOptions& options = {}, const Eigen::VectorXd& u0 = Eigen::VectorXd());

}  // namespace sphstab
