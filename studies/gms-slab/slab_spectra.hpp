#pragma once
// The frozen-state spectra of the gms-slab study (studies/common/gms.hpp): linearised spectra of states along the
// eps = 0 run of the slab [GMS2001, §7.3] at a coarser grid, under eps = 0 and 0.3, viscosity off and, at the last
// state, on (frozen_spectrum.csv, frozen_mode_*.csv and the frozen_* summary keys).
#include <string>
#include <vector>

#include "common/gms.hpp"
#include "common/study.hpp"
#include "slab_case.hpp"
#include "sphstab/forms/rate_form.hpp"

namespace gslab {

/// Frozen-state spectra (common/gms.hpp) along the eps = 0 run at a coarser grid (dp_spectrum): the start (stress
/// free) and `times` before the break, under eps = 0 and 0.3, the last time also with the viscosity on. Elastic
/// linearisations: the von Mises return is not part of the rate (the run has it).
inline void frozen_spectra(double dp_spectrum, double skin, const std::vector<double>& times, const std::string& out,
                           study::Summary& sum) {
  const ElasticMaterial mat = ElasticMaterial::from_bulk_shear(1, kMu, 1);
  const Scene<2> scene = gms_slab_scene({.spacing = dp_spectrum, .end_zone = kEndZone, .acceleration = kAcceleration},
                                        kYield, {.material = mat, .scheme = row_loop(gms_scheme_options(0))});
  const double h = scene.scheme->discretisation().h;
  study::frozen_spectra_along_run(
      *scene.scheme, scene.y0,
      {.dt = 0.5 * h / mat.p_wave_speed(), .yield_stress = kYield, .neighbour_skin = skin * dp_spectrum}, times,
      times.back(), out, sum);
  sum.set("frozen_dp", dp_spectrum, 3);
  sum.set("frozen_particles", scene.scheme->discretisation().size());
}

}  // namespace gslab
