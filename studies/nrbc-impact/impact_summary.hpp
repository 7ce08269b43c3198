#pragma once
// The key numbers of summary.md.in: the run table, the wave speeds against rayleigh_speed() (A.35) and the reference's
// cost.
#include <cmath>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "impact_cases.hpp"
#include "impact_measures.hpp"
#include "impact_run.hpp"
#include "sphstab/spectral/plane_wave_reflection.hpp"

namespace nrbc_impact {

/// The key numbers of the runs, and the settings of `base` (cfl, t_end) with the scheme's gradient.
inline void summarise(study::Summary& sum, const std::vector<ImpactRun>& runs, const std::vector<Measures>& measures,
                      const Incident& in, const ImpactCase& base, const std::string& gradient) {
  const double c_p = kSteel.p_wave_speed(), c_s = std::sqrt(kSteel.mu() / kSteel.density());
  const double c_r = rayleigh_speed(c_p, c_s);
  std::string md;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const ImpactRun& r = runs[k];
    const Measures& m = measures[k];
    if (r.c.name == "narrow" && m.sides_measured) {
      const std::string key = std::string("c_r_reflected_") + boundary_name(r.c.boundary);
      sum.set(key, m.reflected, 4);
      sum.set(key + "_err", m.reflected_err, 2);
      sum.set(key + "_rel", 100 * (m.reflected / c_r - 1), 2);
    }
    if (&r == m.reference) continue;
    study::md_row(md,
                  {r.c.name, boundary_name(r.c.boundary), study::sig(r.c.v_patch, 2), std::to_string(r.particles),
                   std::to_string(r.absorbing), r.status, study::sig(100 * m.error_surface, 3) + " %",
                   study::sig(100 * m.error_depth, 3) + " %",
                   std::isnan(m.reflected) ? "-" : study::sig(m.reflected, 4) + " ± " + study::sig(m.reflected_err, 2),
                   study::sig(r.cpu, 3), study::sig(r.cpu / m.reference->cpu, 3)});
  }
  const ImpactRun& ref = runs[0];
  sum.set("table", md);
  sum.set("c_p", c_p, 5);
  sum.set("c_s", c_s, 5);
  sum.set("c_r", c_r, 5);
  sum.set("c_r_incident", in.c_r, 4);
  sum.set("c_r_incident_err", in.c_r_err, 2);
  sum.set("c_r_incident_rel", 100 * (in.c_r / c_r - 1), 2);
  sum.set("reference_particles", ref.particles);
  sum.set("reference_cpu", ref.cpu, 3);
  sum.set("gradient", gradient);
  sum.set("cfl", base.cfl, 3);
  sum.set("t_end", base.t_end, 3);
}

}  // namespace nrbc_impact
