#include "sphstab/core/length_scale.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

void check_length(double value, const std::string& what) {
  if (std::isfinite(value) && value >= kMinLength && value <= kMaxLength) return;
  if (std::isnan(value) || !(value > 0))
    throw std::invalid_argument(what + " must be finite and > 0 (got " + format_number(value) + ")");
  throw std::invalid_argument(what + " = " + format_number(value) + " is outside the supported length range [" +
                              format_number(kMinLength) + ", " + format_number(kMaxLength) +
                              "] (kernel derivatives form up to h^-5: rescale the problem to units nearer 1)");
}

}  // namespace sphstab
