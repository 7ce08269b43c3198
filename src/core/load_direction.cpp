#include "sphstab/core/load_direction.hpp"

#include <stdexcept>

namespace sphstab {

std::string load_direction_name(LoadDirection d) { return d == LoadDirection::Tension ? "tension" : "compression"; }

LoadDirection parse_load_direction(const std::string& name) {
  if (name == "tension") return LoadDirection::Tension;
  if (name == "compression") return LoadDirection::Compression;
  throw std::invalid_argument("unknown load direction '" + name + "' (valid: tension, compression)");
}

}  // namespace sphstab
