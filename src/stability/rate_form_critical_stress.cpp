#include "sphstab/stability/rate_form_critical_stress.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "sphstab/core/format.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"

namespace sphstab {

template <int Dim>
RateFormCriticalStress rate_form_critical_stress(std::shared_ptr<const Discretisation<Dim>> disc,
                                                 const ElasticMaterial& material, const RateFormOptions& options,
                                                 const RateFormCriticalOptions& c) {
  if (!disc) throw std::invalid_argument("rate_form_critical_stress: null discretisation");
  material.validate("rate_form_critical_stress", ShearModulusRule::NonNegative);
  if (!(c.growth_tolerance > 0) || !(c.rtol > 0) || !(c.step > 1) || !(c.min > 0) || !(c.start > 0) ||
      !(c.max > c.min) || !std::isfinite(c.max))
    throw std::invalid_argument(
        "rate_form_critical_stress: need growth_tolerance > 0, rtol > 0, step > 1, 0 < min < max < inf, start > 0");
  const double K = material.bulk_modulus(), M = K + 4 * material.mu() / 3, sgn = load_sign(c.direction);
  // Tension: sigma0 < K (xi finite); keep a margin so the density stays well defined.
  const double max_tau = c.direction == LoadDirection::Tension ? std::min(c.max, 0.999 * K / M) : c.max;
  RateFormCriticalStress r;
  std::string failure;
  std::map<double, double> growth;  // tau -> growth rate of the unstable evaluations
  auto xi_of = [&](double tau) { return 1 / (1 - sgn * tau * M / K); };
  auto stable = [&](double tau) {
    ++r.evaluations;
    const RateFormScheme<Dim> scheme(disc, material, options, material.density() / xi_of(tau));
    const RateFormSpectrum s = rate_form_spectrum(scheme, scheme.uniform_state(), {.basis = c.basis});
    if (s.status != Status::Successful) {
      if (failure.empty()) failure = "spectrum at sigma0/M = " + format_number(sgn * tau) + ": " + s.reason;
      return true;  // reported below; do not steer the bracket by a failed evaluation
    }
    const double scale = s.eigenvalues.size() ? s.eigenvalues.cwiseAbs().maxCoeff() : 0.0;
    const bool ok = !(s.growth_rate > c.growth_tolerance * scale);
    if (!ok) growth[tau] = s.growth_rate;
    return ok;
  };
  r.bracket = bracket_critical_load(stable, std::min(c.start, max_tau), max_tau, c.min, c.step);
  bisect_critical_load(r.bracket, stable, c.rtol);
  const double tau = r.bracket.critical();
  r.stress_over_modulus = sgn * tau;
  r.stress = sgn * tau * M;
  r.xi = std::isinf(tau) ? RateFormCriticalStress::nan : xi_of(tau);
  if (const auto it = growth.find(r.bracket.hi); it != growth.end()) r.growth_above = it->second;
  if (!failure.empty()) {
    r.status = Status::NumericalIssue;
    r.reason = failure;
  } else {
    r.status = Status::Successful;
    r.reason = r.bracket.outcome == LoadBracket::Outcome::StableToMax
                   ? "stable up to sigma0/M = " + format_number(sgn * max_tau)
                   : (r.bracket.outcome == LoadBracket::Outcome::UnstableToMin ? "unstable at zero load" : "ok");
  }
  return r;
}

template RateFormCriticalStress rate_form_critical_stress<1>(std::shared_ptr<const Discretisation<1>>,
                                                             const ElasticMaterial&, const RateFormOptions&,
                                                             const RateFormCriticalOptions&);
template RateFormCriticalStress rate_form_critical_stress<2>(std::shared_ptr<const Discretisation<2>>,
                                                             const ElasticMaterial&, const RateFormOptions&,
                                                             const RateFormCriticalOptions&);

}  // namespace sphstab
