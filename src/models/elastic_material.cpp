#include "sphstab/models/elastic_material.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

std::string uniaxial_state_name(UniaxialState state) { return state == UniaxialState::Strain ? "strain" : "stress"; }

ElasticMaterial ElasticMaterial::from_lame(double lambda, double mu, double density) {
  return {lambda, mu, lambda + 2 * mu / 3, density};
}

ElasticMaterial ElasticMaterial::from_bulk_shear(double bulk_modulus, double mu, double density) {
  return {bulk_modulus - 2 * mu / 3, mu, bulk_modulus, density};
}

ElasticMaterial ElasticMaterial::from_young_poisson(double young, double poisson, double density) {
  if (!(young > 0) || !std::isfinite(young))
    throw std::invalid_argument("ElasticMaterial: Young's modulus must be finite and > 0 (got " + format_number(young) +
                                ")");
  if (!(poisson > -1 && poisson < 0.5))
    throw std::invalid_argument("ElasticMaterial: Poisson's ratio must lie in (-1, 0.5) (got " +
                                format_number(poisson) + ")");
  // Each constant straight from (E, nu), in the operation order the forms (lambda) and the rate form (K) always used.
  ElasticMaterial m(young * poisson / ((1 + poisson) * (1 - 2 * poisson)), young / (2 * (1 + poisson)),
                    young / (3 * (1 - 2 * poisson)), density);
  m.validate("ElasticMaterial");
  return m;
}

double ElasticMaterial::sound_speed() const { return std::sqrt(m_bulk_modulus / m_density); }
double ElasticMaterial::p_wave_speed() const { return std::sqrt((m_bulk_modulus + 4 * m_mu / 3) / m_density); }

void ElasticMaterial::validate(const char* who, ShearModulusRule shear) const {
  const std::string w(who);
  if (!std::isfinite(m_lambda) || !std::isfinite(m_mu) || !std::isfinite(m_bulk_modulus) || !std::isfinite(m_density))
    throw std::invalid_argument(w + ": material constants must be finite (lambda " + format_number(m_lambda) + ", mu " +
                                format_number(m_mu) + ", K " + format_number(m_bulk_modulus) + ", density " +
                                format_number(m_density) + ")");
  if (!(m_density > 0)) throw std::invalid_argument(w + ": density must be > 0 (got " + format_number(m_density) + ")");
  if (shear == ShearModulusRule::Positive ? !(m_mu > 0) : !(m_mu >= 0))
    throw std::invalid_argument(w + ": shear modulus mu must be " +
                                (shear == ShearModulusRule::Positive ? "> 0" : ">= 0") + " (got " +
                                format_number(m_mu) + ")");
  if (!(m_bulk_modulus > 0))
    throw std::invalid_argument(w + ": bulk modulus K = " + format_number(m_bulk_modulus) +
                                " <= 0 (Poisson's ratio outside (-1, 0.5); need 3 lambda + 2 mu > 0)");
}

}  // namespace sphstab
