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
/// nearest, also with the viscosity on; the later ones: the rebound, with the rings in hoop tension). Class by class
/// in the four mirror classes of the two rings (study::FrozenMirror), so the mode named is the same on any machine.
inline void frozen_spectra(double dp_spectrum, double gap, double skin, const std::vector<double>& times,
                           const std::string& out, study::Summary& sum) {
  const ElasticMaterial mat = gms_material();
  const Scene<2> scene =
      gms_rings_scene({.inner_radius = 3, .outer_radius = 4, .spacing = dp_spectrum, .gap = gap, .speed = 0.059},
                      {.material = mat, .scheme = gms_scheme_options(0)});
  const double h = scene.scheme->discretisation().h;
  // The rings are mirror images about x = 0 and each is symmetric about y = 0; the run keeps the particles' mirror
  // partners to rounding (1e-6 dp is far above it and far below the spacing).
  const study::FrozenMirror mirror{.centre = Eigen::Vector2d::Zero(), .tolerance = 1e-6 * dp_spectrum};
  const std::vector<study::FrozenRow> rows = study::frozen_spectra_along_run(
      *scene.scheme, scene.y0, {.dt = 0.5 * h / mat.p_wave_speed(), .neighbour_skin = skin * dp_spectrum}, times,
      times.front(), out, sum, &mirror);
  // The last state's largest growth rate under eps = 0.3 over eps = 0 (viscosity off), for the summary's reading.
  double g0 = 0, g03 = 0, residual = 0;
  for (const study::FrozenRow& r : rows) {
    residual = std::max(residual, r.spectrum.symmetry_residual);
    if (r.t == rows.back().t && !r.viscosity) (r.eps == 0 ? g0 : g03) = r.spectrum.growth_rate;
  }
  sum.set("frozen_last_t", rows.back().t, 3);
  sum.set("frozen_last_eps03_over_eps0", g03 / g0, 2);
  sum.set("frozen_symmetry_residual", residual, 1);
  sum.set("frozen_dp", dp_spectrum, 3);
  sum.set("frozen_particles", scene.scheme->discretisation().size());
}

}  // namespace grings
