#include "sphstab/core/load_direction.hpp"

#include <stdexcept>

#include "sphstab/core/named_values.hpp"

namespace sphstab {

constexpr NamedValue<LoadDirection> kLoadDirectionNames[] = {{LoadDirection::Tension, "tension"},
                                                             {LoadDirection::Compression, "compression"}};

std::string load_direction_name(LoadDirection d) { return name_of(d, kLoadDirectionNames); }
LoadDirection parse_load_direction(const std::string& name) {
  return parse_named(name, kLoadDirectionNames, "load direction");
}

}  // namespace sphstab
