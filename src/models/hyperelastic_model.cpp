#include "sphstab/models/hyperelastic_model.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab::detail {

void require_positive_jacobian(double J, const std::string& who) {
  if (!(J > 0) || !std::isfinite(J))
    throw std::invalid_argument(who + ": J = det F = " + format_number(J) +
                                " <= 0 (inverted material; reduce the load or the time step)");
}

}  // namespace sphstab::detail
