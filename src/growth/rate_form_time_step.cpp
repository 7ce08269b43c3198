#include "sphstab/growth/rate_form_time_step.hpp"

#include <cmath>

#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/integrate/time_step.hpp"

namespace sphstab {

template <int Dim>
RateFormTimeStep rate_form_time_step(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y) {
  RateFormTimeStep out;
  const RateFormSpectrum sp = rate_form_spectrum(scheme, y);
  out.status = sp.status;
  out.reason = sp.reason;
  if (sp.status != Status::Successful) return out;
  out.max_imag = 0;
  for (const auto& l : sp.eigenvalues)
    if (std::abs(l.imag()) > out.max_imag) {
      out.max_imag = std::abs(l.imag());
      out.dominant = l;
    }
  out.growth_rate = sp.growth_rate;
  out.leapfrog = leapfrog_time_step_limit(sp.eigenvalues);
  out.predictor_corrector = heun_time_step_limit(sp.eigenvalues);
  out.cfl_unit = scheme.discretisation().h / scheme.material().p_wave_speed();
  out.courant = out.leapfrog / out.cfl_unit;
  return out;
}

template RateFormTimeStep rate_form_time_step<1>(const RateFormScheme<1>&, const Eigen::VectorXd&);
template RateFormTimeStep rate_form_time_step<2>(const RateFormScheme<2>&, const Eigen::VectorXd&);

}  // namespace sphstab
