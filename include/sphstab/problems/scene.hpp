#pragma once
/// \file scene.hpp
/// A runnable scene: a test case as the rate-form system (forms/rate_form.hpp, y' = F(y)) at its initial state, with
/// the run length, plasticity and neighbour skin the case needs, and its named measures. One type for every scene
/// the toolkit runs (the GMS plate, rings and slab: problems/gms_scenes.hpp); the CLI (`sphstab scene`) and the
/// studies build a scene here and run it with the run loop (integrate/run.hpp, run_rate_form), so a scene is set up
/// once.
///
/// A scene also says how it is stepped unless the caller chooses otherwise (integrator, Powell's XSPH, CFL number);
/// integrate/scene_run.hpp turns that into the run's options, so the CLI and Python run a scene the same way.
///
/// \code{.cpp}
/// sphstab::Scene<2> s = sphstab::gms_rings_scene({.spacing = 0.2});
/// const auto r = sphstab::run_rate_form(*s.scheme, s.y0, sphstab::scene_run_options(s));  // integrate/scene_run.hpp
/// const double fragments = s.measures.front().value(sphstab::rate_form_positions(*s.scheme, r.y), r.y);
/// \endcode
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"

namespace sphstab {

/// A named scalar of a state: x holds the current positions of every particle (Dim x N, rate_form_positions), y the
/// state.
template <int Dim>
struct SceneMeasure {
  std::string name;
  std::function<double(const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x, const Eigen::VectorXd& y)> value;
};

template <int Dim>
struct Scene {
  std::string name;                               ///< e.g. "rings"
  std::shared_ptr<RateFormScheme<Dim>> scheme;    ///< the system
  Eigen::VectorXd y0;                             ///< initial state
  double spacing = 0;                             ///< the particle spacing dp
  double t_end = 0;                               ///< the case's default run length
  double yield_stress = std::numeric_limits<double>::infinity();  ///< von Mises Y of the run (+inf: elastic)
  double neighbour_skin = 0;                      ///< Verlet skin the run needs (bodies that move by many h), a length
  std::vector<SceneMeasure<Dim>> measures;        ///< the case's own measures (the first is its headline)
  /// The default integrator, by the names of select_rate_form_integrator: "pc" (GMS's predictor-corrector, two rate
  /// evaluations per step), "pc1" (one per step) or "leapfrog".
  std::string integrator = "pc";
  double leapfrog_xsph = 0;  ///< Powell's XSPH (2.71) epsilon of the leap-frog (0: off)
  double cfl = 0.5;          ///< the default time step is time_step(cfl)

  /// dt = cfl h / c_P (the CFL rule of the scheme's P-wave speed); throws std::invalid_argument for cfl <= 0.
  double time_step(double cfl) const;
  /// The measure called `name`; throws std::invalid_argument naming the valid ones.
  const SceneMeasure<Dim>& measure(const std::string& name) const;
};

extern template struct Scene<1>;
extern template struct Scene<2>;

}  // namespace sphstab
