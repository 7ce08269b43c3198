#include "sphstab/integrate/scene_run.hpp"

#include "sphstab/integrate/linear_step_map.hpp"

namespace sphstab {

template <int Dim>
RateFormRunOptions scene_run_options(const Scene<Dim>& s) {
  RateFormRunOptions o{.dt = s.time_step(s.cfl),
                       .t_end = s.t_end,
                       .yield_stress = s.yield_stress,
                       .neighbour_skin = s.neighbour_skin};
  select_rate_form_integrator(o, s.integrator);
  o.leapfrog_xsph = s.leapfrog_xsph;
  return o;
}

template RateFormRunOptions scene_run_options(const Scene<1>&);
template RateFormRunOptions scene_run_options(const Scene<2>&);

}  // namespace sphstab
