#include "sphstab/integrate/scene_run.hpp"

#include "sphstab/integrate/linear_step_map.hpp"

namespace sphstab {

template <int Dim>
RateFormRunOptions scene_run_options(const Scene<Dim>& s, const std::string& integrator) {
  RateFormRunOptions o{.dt = s.time_step(s.cfl),
                       .t_end = s.t_end,
                       .yield_stress = s.yield_stress,
                       .neighbour_skin = s.neighbour_skin};
  select_rate_form_integrator(o, integrator == "auto" ? s.integrator : integrator);
  o.leapfrog_xsph = o.integrator == RateFormIntegrator::Leapfrog ? s.leapfrog_xsph : 0.0;
  return o;
}

template RateFormRunOptions scene_run_options(const Scene<1>&, const std::string&);
template RateFormRunOptions scene_run_options(const Scene<2>&, const std::string&);

}  // namespace sphstab
