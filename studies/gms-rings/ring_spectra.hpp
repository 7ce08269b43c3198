#pragma once
// The frozen-state spectra of the gms-rings study (studies/common/gms.hpp): linearised spectra of states along the
// eps = 0 collision of the rings [GMS2001, §7.2] at a coarser grid, under eps = 0 and 0.3, viscosity off and, at the
// first time, on (frozen_spectrum.csv, frozen_mode_*.csv and the frozen_* summary keys).
#include <string>
#include <vector>

#include "common/gms.hpp"
#include "common/study.hpp"
#include "ring_case.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/problems/colliding_rings.hpp"

namespace grings {

/// Frozen-state spectra (common/gms.hpp) along the eps = 0 collision at a coarser grid (dp_spectrum: dense
/// eigenproblems of 2N and, with the viscosity on, 4N for N particles): at the start (at rest in the rings' frame:
/// stress free, so stable) and at `times` (the first: the contact, when the closest particles of the two rings are
/// nearest, also with the viscosity on; the later ones: the rebound, with the rings in hoop tension).
inline void frozen_spectra(double dp_spectrum, double gap, double skin, const std::vector<double>& times,
                           const std::string& out, study::Summary& sum) {
  const ElasticMaterial mat = gms_material();
  const Scene<2> scene =
      gms_rings_scene({.inner_radius = 3, .outer_radius = 4, .spacing = dp_spectrum, .gap = gap, .speed = 0.059},
                      {.material = mat, .scheme = gms_scheme_options(0)});
  const double h = scene.scheme->discretisation().h;
  study::frozen_spectra_along_run(*scene.scheme, scene.y0,
                                  {.dt = 0.5 * h / mat.p_wave_speed(), .neighbour_skin = skin * dp_spectrum}, times,
                                  times.front(), out, sum);
  sum.set("frozen_dp", dp_spectrum, 3);
  sum.set("frozen_particles", scene.scheme->discretisation().size());
}

}  // namespace grings
