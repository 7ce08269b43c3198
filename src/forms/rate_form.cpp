#include "sphstab/forms/rate_form.hpp"

#include "rate_form_impl.hpp"

namespace sphstab {

RateFormMaterial RateFormMaterial::from_youngs(double youngs_modulus, double poisson_ratio, double density) {
  if (!(youngs_modulus > 0) || !std::isfinite(youngs_modulus))
    throw std::invalid_argument("RateFormMaterial: Young's modulus must be finite and > 0 (got " +
                                format_number(youngs_modulus) + ")");
  if (!(poisson_ratio > -1 && poisson_ratio < 0.5))
    throw std::invalid_argument("RateFormMaterial: Poisson's ratio must lie in (-1, 1/2) (got " +
                                format_number(poisson_ratio) + ")");
  RateFormMaterial m{.density = density,
                     .bulk_modulus = youngs_modulus / (3 * (1 - 2 * poisson_ratio)),
                     .shear_modulus = youngs_modulus / (2 * (1 + poisson_ratio))};
  m.validate("RateFormMaterial");
  return m;
}

double RateFormMaterial::sound_speed() const { return std::sqrt(bulk_modulus / density); }
double RateFormMaterial::p_wave_speed() const { return std::sqrt((bulk_modulus + 4 * shear_modulus / 3) / density); }

void RateFormMaterial::validate(const char* who) const {
  const auto ok = [](double v, bool strict) { return std::isfinite(v) && (strict ? v > 0 : v >= 0); };
  if (!ok(density, true) || !ok(bulk_modulus, true) || !ok(shear_modulus, false))
    throw std::invalid_argument(std::string(who) + ": need density > 0, bulk modulus > 0, shear modulus >= 0 (got " +
                                format_number(density) + ", " + format_number(bulk_modulus) + ", " +
                                format_number(shear_modulus) + ")");
}

ContinuityForm parse_continuity_form(const std::string& name) {
  if (name == "summation") return ContinuityForm::Summation;
  if (name == "divergence") return ContinuityForm::Divergence;
  throw std::invalid_argument("unknown continuity form '" + name + "' (valid: summation, divergence)");
}

ViscositySwitch parse_viscosity_switch(const std::string& name) {
  if (name == "off") return ViscositySwitch::Off;
  if (name == "compression") return ViscositySwitch::Compression;
  if (name == "always") return ViscositySwitch::Always;
  throw std::invalid_argument("unknown viscosity switch '" + name + "' (valid: off, compression, always)");
}

RateFormGradient parse_rate_form_gradient(const std::string& name) {
  if (name == "plain") return RateFormGradient::Plain;
  if (name == "ncsph") return RateFormGradient::Ncsph;
  throw std::invalid_argument("unknown rate-form gradient '" + name + "' (valid: plain, ncsph)");
}

RateFormMomentum parse_rate_form_momentum(const std::string& name) {
  if (name == "symmetric") return RateFormMomentum::Symmetric;
  if (name == "antisymmetric") return RateFormMomentum::Antisymmetric;
  if (name == "cij") return RateFormMomentum::Cij;
  if (name == "ssph") return RateFormMomentum::StabilisedSph;
  throw std::invalid_argument("unknown rate-form momentum '" + name + "' (valid: symmetric, antisymmetric, cij, ssph)");
}

PairLoop parse_pair_loop(const std::string& name) {
  if (name == "rows") return PairLoop::Rows;
  if (name == "pairs") return PairLoop::Pairs;
  throw std::invalid_argument("unknown pair loop '" + name + "' (valid: rows, pairs)");
}



template class RateFormScheme<1>;

}  // namespace sphstab
