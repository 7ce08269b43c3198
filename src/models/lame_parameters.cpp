#include "sphstab/models/lame_parameters.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"
#include "sphstab/models/hyperelastic_model.hpp"

namespace sphstab {

std::string uniaxial_state_name(UniaxialState state) { return state == UniaxialState::Strain ? "strain" : "stress"; }

LameParameters LameParameters::from_young_poisson(double young, double poisson) {
  if (!(young > 0) || !std::isfinite(young))
    throw std::invalid_argument("LameParameters: Young's modulus must be finite and > 0 (got " + format_number(young) +
                                ")");
  if (!(poisson > -1 && poisson < 0.5))
    throw std::invalid_argument("LameParameters: Poisson's ratio must lie in (-1, 0.5) (got " + format_number(poisson) +
                                ")");
  return {.lambda = young * poisson / ((1 + poisson) * (1 - 2 * poisson)), .mu = young / (2 * (1 + poisson))};
}

void LameParameters::validate(const char* who) const {
  if (!std::isfinite(lambda) || !std::isfinite(mu))
    throw std::invalid_argument(std::string(who) + ": Lame constants must be finite (lambda " + format_number(lambda) +
                                ", mu " + format_number(mu) + ")");
  if (!(mu > 0))
    throw std::invalid_argument(std::string(who) + ": shear modulus mu must be > 0 (got " + format_number(mu) + ")");
  if (!(3 * lambda + 2 * mu > 0))
    throw std::invalid_argument(std::string(who) + ": Poisson's ratio " + format_number(poisson()) +
                                " outside (-1, 0.5) (need 3 lambda + 2 mu > 0)");
}

namespace detail {
void require_positive_jacobian(double J, const std::string& who) {
  if (!(J > 0) || !std::isfinite(J))
    throw std::invalid_argument(who + ": J = det F = " + format_number(J) +
                                " <= 0 (inverted material; reduce the load or the time step)");
}
}  // namespace detail

}  // namespace sphstab
