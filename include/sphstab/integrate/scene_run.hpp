#pragma once
/// \file scene_run.hpp
/// The run options of a scene (problems/scene.hpp) as the scene asks to be run: its time step rule, run length,
/// yield stress, neighbour skin, integrator and Powell's XSPH. `sphstab scene` and Python's sphstab.run start from
/// these and override what their caller gives.
#include <string>

#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/problems/scene.hpp"

namespace sphstab {

/// dt = s.time_step(s.cfl), t_end = s.t_end, the scene's yield stress, skin and leap-frog XSPH, and its integrator
/// unless `integrator` names another ("pc", "pc1", "leapfrog"; "auto": the scene's; off the leap-frog Powell's XSPH
/// is off, it belongs to the leap-frog); the rest RateFormRunOptions' defaults. Throws std::invalid_argument for an
/// integrator name select_rate_form_integrator does not know.
template <int Dim>
RateFormRunOptions scene_run_options(const Scene<Dim>& s, const std::string& integrator = "auto");

}  // namespace sphstab
